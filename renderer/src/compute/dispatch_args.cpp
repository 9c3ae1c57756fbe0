// DispatchIndirect arguments written on the GPU (renderer/compute/dispatch_args.h;
// shaders_hlsl/compute/dispatch_args.fx).
#include "renderer/compute/dispatch_args.h"

#include "compute/effect_values.h"
#include "renderer/effect_files.h"

namespace renderer::compute {

using namespace rhi;

DispatchArgs::~DispatchArgs() = default;

std::unique_ptr<DispatchArgs> DispatchArgs::Create(Device* device, uint32_t slots, std::string* error) {
  std::unique_ptr<DispatchArgs> args(new DispatchArgs());
  if (!args->Initialize(device, slots, error)) return nullptr;
  return args;
}

bool DispatchArgs::Initialize(Device* device, uint32_t slots, std::string* error) {
  if (slots == 0) {
    *error = "dispatch args: no slots asked for";
    return false;
  }
  slots_ = slots;
  if (!args_.CreateRaw(device, slots * kSlotBytes / 4, RESOURCE_MISC_DRAWINDIRECT_ARGS)) {
    *error = "dispatch args: creating the argument buffer failed";
    return false;
  }
  effect_ = LoadEffect(device, "compute/dispatch_args.fx", {}, error);
  return effect_ && (write_ = FindPass(effect_.Get(), nullptr, "Write", error));
}

namespace {

// Sets to null every compute shader-resource slot that views `resource`, as a D3D11
// program does before it writes a resource it read (binding it for writing while it
// is bound for reading makes the runtime force the slot to NULL, with a warning).
void UnbindFromComputeReads(DeviceContext* ctx, Resource* resource) {
  ShaderResourceView* views[COMMONSHADER_INPUT_RESOURCE_SLOT_COUNT] = {};
  ctx->CSGetShaderResources(0, COMMONSHADER_INPUT_RESOURCE_SLOT_COUNT, views);
  for (UINT slot = 0; slot < COMMONSHADER_INPUT_RESOURCE_SLOT_COUNT; ++slot) {
    if (!views[slot]) continue;
    ComPtr<Resource> viewed;
    views[slot]->GetResource(viewed.GetAddressOf());
    views[slot]->Release();
    if (viewed.Get() != resource) continue;
    ShaderResourceView* none = nullptr;
    ctx->CSSetShaderResources(slot, 1, &none);
  }
}

}  // namespace

bool DispatchArgs::Write(DeviceContext* ctx, UnorderedAccessView* count, uint32_t countWord, uint32_t threadsPerGroup,
                         uint32_t slot, uint32_t maxCount) {
  if (slot >= slots_ || threadsPerGroup == 0 || !count) return false;
  SetUint(effect_.Get(), "CountWord", countWord);
  SetUint(effect_.Get(), "ItemsPerGroup", threadsPerGroup);
  SetUint(effect_.Get(), "MaxCount", maxCount);
  SetUint(effect_.Get(), "ArgsOffset", offset(slot));
  SetUav(effect_.Get(), "Count", count);
  SetUav(effect_.Get(), "Args", args_.uav.Get());
  UnbindFromComputeReads(ctx, args_.buffer.Get());  // IndirectArgs of the dispatches sized by the last Write
  write_->Apply(0, ctx);
  ctx->Dispatch(1, 1, 1);
  UnorderedAccessView* none[2] = {};
  ctx->CSSetUnorderedAccessViews(0, 2, none, nullptr);  // the arguments are read next (indirect, SRV)
  return true;
}

void DispatchArgs::Bind(fx::Effect* effect, uint32_t slot) const {
  effect->GetVariableByName("IndirectArgs")->AsShaderResource()->SetResource(args_.srv.Get());
  SetUint(effect, "IndirectArgsOffset", offset(slot));
}

void DispatchArgs::Dispatch(DeviceContext* ctx, uint32_t slot) const {
  ctx->DispatchIndirect(args_.buffer.Get(), offset(slot));
}

}  // namespace renderer::compute
