// EffectPass::Apply with FX11 semantics: set what the pass assigns, in order,
// and for every shader it sets, upload and bind what that shader reads.
#include <array>

#include "effect_impl.h"
#include "variables.h"

namespace fx::detail {
namespace {

using rhi::DeviceContext;
using RC = rhi::RegisterClass;

constexpr UINT kMaxBindCount = 128;

void SetConstantBuffer(DeviceContext* c, ShaderStage stage, UINT slot, rhi::Buffer* b) {
  switch (stage) {
    case ShaderStage::Vertex: c->VSSetConstantBuffers(slot, 1, &b); break;
    case ShaderStage::Hull: c->HSSetConstantBuffers(slot, 1, &b); break;
    case ShaderStage::Domain: c->DSSetConstantBuffers(slot, 1, &b); break;
    case ShaderStage::Geometry: c->GSSetConstantBuffers(slot, 1, &b); break;
    case ShaderStage::Pixel: c->PSSetConstantBuffers(slot, 1, &b); break;
    case ShaderStage::Compute: c->CSSetConstantBuffers(slot, 1, &b); break;
  }
}

void SetShaderResources(DeviceContext* c, ShaderStage stage, UINT slot, UINT n, rhi::ShaderResourceView* const* v) {
  switch (stage) {
    case ShaderStage::Vertex: c->VSSetShaderResources(slot, n, v); break;
    case ShaderStage::Hull: c->HSSetShaderResources(slot, n, v); break;
    case ShaderStage::Domain: c->DSSetShaderResources(slot, n, v); break;
    case ShaderStage::Geometry: c->GSSetShaderResources(slot, n, v); break;
    case ShaderStage::Pixel: c->PSSetShaderResources(slot, n, v); break;
    case ShaderStage::Compute: c->CSSetShaderResources(slot, n, v); break;
  }
}

void SetSamplers(DeviceContext* c, ShaderStage stage, UINT slot, UINT n, rhi::SamplerState* const* s) {
  switch (stage) {
    case ShaderStage::Vertex: c->VSSetSamplers(slot, n, s); break;
    case ShaderStage::Hull: c->HSSetSamplers(slot, n, s); break;
    case ShaderStage::Domain: c->DSSetSamplers(slot, n, s); break;
    case ShaderStage::Geometry: c->GSSetSamplers(slot, n, s); break;
    case ShaderStage::Pixel: c->PSSetSamplers(slot, n, s); break;
    case ShaderStage::Compute: c->CSSetSamplers(slot, n, s); break;
  }
}

// The shader object the assignment sets: a pass's SetGeometryShader of a
// ConstructGSWithSO over a vertex shader sets the stream-output GS.
void SetShader(DeviceContext* c, ShaderStage stage, const ShaderState* s) {
  switch (stage) {
    case ShaderStage::Vertex: c->VSSetShader(s ? s->vs.Get() : nullptr, nullptr, 0); break;
    case ShaderStage::Hull: c->HSSetShader(s ? s->hs.Get() : nullptr, nullptr, 0); break;
    case ShaderStage::Domain: c->DSSetShader(s ? s->ds.Get() : nullptr, nullptr, 0); break;
    case ShaderStage::Geometry: c->GSSetShader(s ? s->gs.Get() : nullptr, nullptr, 0); break;
    case ShaderStage::Pixel: c->PSSetShader(s ? s->ps.Get() : nullptr, nullptr, 0); break;
    case ShaderStage::Compute: c->CSSetShader(s ? s->cs.Get() : nullptr, nullptr, 0); break;
  }
}

template <class T>
std::array<T*, kMaxBindCount> Gather(const ObjectSlots<T>& slots, UINT count) {
  std::array<T*, kMaxBindCount> objects{};
  for (UINT i = 0; i < count && i < kMaxBindCount; ++i) objects[i] = slots.Get(i);
  return objects;
}

// FX11 binds a pixel shader's UAVs through the output merger, keeping the
// render targets, from the shader's lowest UAV register to its highest (the
// loader refused UAVs outside u0..u7 and outside pixel and compute shaders),
// and keeps the hidden counters (initial counts -1).
void BindPixelShaderUavs(EffectImpl& e, DeviceContext* c, const ShaderState& s) {
  constexpr UINT kSlots = rhi::PS_CS_UAV_REGISTER_COUNT;
  std::array<rhi::UnorderedAccessView*, kSlots> views{};
  UINT first = kSlots, end = 0;
  for (const Binding& b : s.bindings) {
    if (b.cls != RC::UnorderedAccess) continue;
    for (UINT i = 0; i < b.count && b.slot + i < kSlots; ++i) views[b.slot + i] = e.uavs[b.variable].Get(i);
    first = std::min(first, b.slot);
    end = std::max(end, std::min(b.slot + b.count, kSlots));
  }
  if (first >= end) return;
  std::array<UINT, kSlots> keepCounts;
  keepCounts.fill(UINT(-1));
  c->OMSetRenderTargetsAndUnorderedAccessViews(rhi::KEEP_RENDER_TARGETS_AND_DEPTH_STENCIL, nullptr, nullptr, first,
                                               end - first, views.data() + first, keepCounts.data());
}

void BindShaderInputs(EffectImpl& e, DeviceContext* c, ShaderStage stage, const ShaderState& s) {
  e.Upload(c, s);
  for (const Binding& b : s.bindings) {
    const UINT count = std::min(b.count, kMaxBindCount);
    switch (b.cls) {
      case RC::ConstantBuffer: {
        const CBufferState& cb = e.cbuffers[b.variable];
        SetConstantBuffer(c, stage, b.slot, cb.userBuffer ? cb.userBuffer.Get() : cb.layouts[b.layout].buffer.Get());
        break;
      }
      case RC::ShaderResource: SetShaderResources(c, stage, b.slot, count, Gather(e.srvs[b.variable], count).data()); break;
      case RC::Sampler: SetSamplers(c, stage, b.slot, count, Gather(e.samplers[b.variable], count).data()); break;
      case RC::UnorderedAccess:
        // Pixel-shader UAVs share the output merger's slots: bound together below.
        if (stage == ShaderStage::Compute)
          c->CSSetUnorderedAccessViews(b.slot, count, Gather(e.uavs[b.variable], count).data(), nullptr);
        break;
    }
  }
  if (stage == ShaderStage::Pixel) BindPixelShaderUavs(e, c, s);
}

void RunAction(EffectImpl& e, DeviceContext* c, const PassAction& a) {
  switch (a.kind) {
    case PassAction::Kind::Shader: {
      const ShaderState* s = a.index >= 0 ? &e.shaders[a.index] : nullptr;
      SetShader(c, a.stage, s);
      if (s) BindShaderInputs(e, c, a.stage, *s);
      break;
    }
    case PassAction::Kind::Blend:
      c->OMSetBlendState(a.index >= 0 ? e.blendStates[a.index].Get(a.element) : nullptr, a.blendFactor.data(),
                         a.sampleMask);
      break;
    case PassAction::Kind::DepthStencil:
      c->OMSetDepthStencilState(a.index >= 0 ? e.depthStates[a.index].Get(a.element) : nullptr, a.stencilRef);
      break;
    case PassAction::Kind::Rasterizer:
      c->RSSetState(a.index >= 0 ? e.rasterStates[a.index].Get(a.element) : nullptr);
      break;
  }
}

}  // namespace

void EffectImpl::Upload(rhi::DeviceContext* context, const ShaderState& shader) {
  for (const Binding& b : shader.bindings) {
    if (b.cls != RC::ConstantBuffer) continue;
    CBufferState& cb = cbuffers[b.variable];
    GpuLayout& layout = cb.layouts[b.layout];
    if (cb.userBuffer || layout.uploadedVersion == cb.version || !layout.buffer) continue;
    std::vector<uint8_t> bytes(std::max<uint32_t>(layout.compiled.size, 16));
    ApplyCopyPlan(layout.plan, cb.data, bytes);
    context->UpdateSubresource(layout.buffer.Get(), 0, nullptr, bytes.data(), 0, 0);
    layout.uploadedVersion = cb.version;
  }
}

HRESULT PassImpl::Apply(UINT Flags, rhi::DeviceContext* pContext) {
  if (!effect_ || !pContext || Flags != 0) return rhi::E_INVALIDARG;
  pContext->SetMarker(marker_.c_str());  // ID3DUserDefinedAnnotation: "technique/pass"
  for (const PassAction& action : actions_) RunAction(*effect_, pContext, action);
  return rhi::S_OK;
}

HRESULT PassImpl::GetDesc(PASS_DESC* pDesc) {
  if (!effect_ || !pDesc) return rhi::E_FAIL;
  *pDesc = {};
  pDesc->Name = ast_->name.c_str();
  pDesc->Annotations = static_cast<UINT>(ast_->annotations.size());
  for (const PassAction& a : actions_) {
    if (a.kind == PassAction::Kind::Shader && a.stage == ShaderStage::Vertex) {
      const auto* code = a.index >= 0 ? effect_->shaders[a.index].code.get() : nullptr;
      pDesc->pIAInputSignature = code ? code->spirv.data() : nullptr;
      pDesc->IAInputSignatureSize = code ? code->spirv.size() * 4 : 0;
    }
    if (a.kind == PassAction::Kind::Blend) {
      std::copy(a.blendFactor.begin(), a.blendFactor.end(), pDesc->BlendFactor);
      pDesc->SampleMask = a.sampleMask;
    }
    if (a.kind == PassAction::Kind::DepthStencil) pDesc->StencilRef = a.stencilRef;
  }
  return rhi::S_OK;
}

EffectVariable* PassImpl::GetAnnotationByIndex(UINT Index) {
  return effect_ ? effect_->Annotation(ast_->annotations, Index) : VariableImpl::Invalid();
}

EffectVariable* PassImpl::GetAnnotationByName(LPCSTR Name) {
  return effect_ ? effect_->Annotation(ast_->annotations, Name) : VariableImpl::Invalid();
}

// FX11's GetShaderDescHelper: the variable (and element) the pass's last
// assignment to `stage` names; an inline shader or NULL gets an anonymous one.
HRESULT PassImpl::ShaderDesc(ShaderStage stage, PASS_SHADER_DESC* pDesc) {
  if (!effect_ || !pDesc) return rhi::E_FAIL;
  const ShaderAssignment* last = nullptr;
  for (const PassAssignment& a : ast_->assignments) {
    if (const auto* s = std::get_if<ShaderAssignment>(&a.value); s && s->stage == stage) last = s;
  }
  *pDesc = {};
  if (last && !last->variable.empty()) {
    pDesc->pShaderVariable = effect_->GetVariableByName(last->variable.c_str())->AsShader();
    pDesc->ShaderIndex = last->element;
  } else {
    pDesc->pShaderVariable = effect_->AnonymousShader(stage, last ? last->shader : -1);
  }
  return rhi::S_OK;
}

}  // namespace fx::detail
