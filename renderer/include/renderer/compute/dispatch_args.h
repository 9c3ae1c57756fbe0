// Dispatch sizes from counts the GPU wrote (renderer/compute/): DispatchIndirect
// arguments computed on the GPU, so a pass over "as many items as the last pass
// produced" needs no read-back. Shaders: shaders_hlsl/compute/dispatch_args.fx
// writes them; a shader dispatched with them includes compute/indirect.hlsli.
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include "fx/effect.h"
#include "renderer/compute/viewed_buffer.h"
#include "rhi/rhi.h"

namespace renderer::compute {

// A buffer of `slots` DispatchIndirect argument slots (RESOURCE_MISC_DRAWINDIRECT_ARGS,
// with raw views). A slot is 4 words: groups in x, y, z, then the count it was
// sized for (indirect.hlsli reads it).
class DispatchArgs {
 public:
  static constexpr uint32_t kSlotBytes = 16;

  static std::unique_ptr<DispatchArgs> Create(rhi::Device* device, uint32_t slots, std::string* error);
  ~DispatchArgs();

  // On the GPU: count = min(word `countWord` of the raw UAV `count`, maxCount);
  // slot `slot` = (ceil(count / threadsPerGroup), 1, 1, count), the group count
  // split into x * y when over 65,535 (D3D11's limit a dimension): y the fewest
  // rows, x the fewest groups a row, so at most y - 1 groups past the last.
  // Refused (false, nothing written) for a slot out of range, threadsPerGroup
  // 0 or no count view. Compute shader-resource slots that view the arguments
  // (IndirectArgs, Bind) are set to null first, so writing them raises no
  // D3D11 hazard; the compute stage's UAV slots 0-1 are left unbound.
  bool Write(rhi::DeviceContext* context, rhi::UnorderedAccessView* count, uint32_t countWord, uint32_t threadsPerGroup,
             uint32_t slot, uint32_t maxCount = UINT32_MAX);

  // Sets indirect.hlsli's variables in `effect` (IndirectArgs, IndirectArgsOffset)
  // for a dispatch sized by `slot`; apply the pass after it.
  void Bind(fx::Effect* effect, uint32_t slot) const;
  // context->DispatchIndirect(buffer(), offset(slot)).
  void Dispatch(rhi::DeviceContext* context, uint32_t slot) const;

  rhi::Buffer* buffer() const { return args_.buffer.Get(); }
  static uint32_t offset(uint32_t slot) { return slot * kSlotBytes; }
  uint32_t slots() const { return slots_; }
  uint64_t MemoryBytes() const { return uint64_t(slots_) * kSlotBytes; }

 private:
  DispatchArgs() = default;
  bool Initialize(rhi::Device* device, uint32_t slots, std::string* error);

  uint32_t slots_ = 0;
  ViewedBuffer args_;
  rhi::ComPtr<fx::Effect> effect_;
  fx::EffectPass* write_ = nullptr;
};

}  // namespace renderer::compute
