// The effect's internal model: what the loader builds from the AST and what
// Apply and the variables work on. Internal to effects/runtime.
#pragma once

#include <array>
#include <deque>
#include <map>
#include <tuple>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "cbuffer_layout.h"
#include "fx/effect.h"
#include "fx/effect_ast.h"
#include "rhi/shader_bindings.h"
#include "shader_cache.h"

namespace fx::detail {

using rhi::ComPtr;

class VariableImpl;
class EffectImpl;

// One compiled layout of an effect cbuffer (usually every shader agrees on one).
struct GpuLayout {
  hlsl::ConstantBufferInfo compiled;
  std::vector<CopyRange> plan;
  ComPtr<rhi::Buffer> buffer;
  uint64_t uploadedVersion = 0;
};

struct CBufferState {
  const ConstantBuffer* ast = nullptr;
  std::vector<uint8_t> data;  // FX11 packing: what Set* and GetRawValue see
  uint64_t version = 1;       // bumped by every write; layouts upload when behind
  std::vector<GpuLayout> layouts;
  ComPtr<rhi::Buffer> userBuffer;  // EffectConstantBuffer::SetConstantBuffer
};

// An object variable's per-element values: the effect's own and the caller's overrides.
template <class T>
struct ObjectSlots {
  std::vector<ComPtr<T>> own;   // created from the effect's descs (states, samplers)
  std::vector<ComPtr<T>> user;  // Set*: SetResource, SetSampler, SetBlendState, ...
  T* Get(size_t i) const { return i < user.size() && user[i] ? user[i].Get() : i < own.size() ? own[i].Get() : nullptr; }
};

// What a shader binds at Apply, resolved at load time.
struct Binding {
  rhi::RegisterClass cls = rhi::RegisterClass::ConstantBuffer;
  uint32_t slot = 0;
  uint32_t count = 1;
  int variable = -1;  // index into cbuffers / resources / samplers of EffectImpl
  int layout = -1;    // cbuffers: index into CBufferState::layouts
};

struct ShaderState {
  const CompiledShader* ast = nullptr;
  std::shared_ptr<const CompiledCode> code;
  ComPtr<rhi::VertexShader> vs;
  ComPtr<rhi::HullShader> hs;
  ComPtr<rhi::DomainShader> ds;
  ComPtr<rhi::GeometryShader> gs;  // with stream output when the AST says ConstructGSWithSO
  ComPtr<rhi::PixelShader> ps;
  ComPtr<rhi::ComputeShader> cs;
  std::vector<Binding> bindings;
};

// A pass assignment with its references resolved to indices.
struct PassAction {
  enum class Kind { Shader, Blend, DepthStencil, Rasterizer } kind = Kind::Shader;
  ShaderStage stage = ShaderStage::Vertex;
  int index = -1;  // shader: EffectImpl::shaders; states: the state variable; -1 for NULL
  uint32_t element = 0;
  std::array<float, 4> blendFactor{};
  uint32_t sampleMask = rhi::DEFAULT_SAMPLE_MASK;
  uint32_t stencilRef = 0;
};

class PassImpl final : public EffectPass {
 public:
  BOOL IsValid() override { return effect_ != nullptr; }
  HRESULT GetDesc(PASS_DESC* pDesc) override;
  HRESULT GetVertexShaderDesc(PASS_SHADER_DESC* pDesc) override { return ShaderDesc(ShaderStage::Vertex, pDesc); }
  HRESULT GetGeometryShaderDesc(PASS_SHADER_DESC* pDesc) override { return ShaderDesc(ShaderStage::Geometry, pDesc); }
  HRESULT GetPixelShaderDesc(PASS_SHADER_DESC* pDesc) override { return ShaderDesc(ShaderStage::Pixel, pDesc); }
  HRESULT GetHullShaderDesc(PASS_SHADER_DESC* pDesc) override { return ShaderDesc(ShaderStage::Hull, pDesc); }
  HRESULT GetDomainShaderDesc(PASS_SHADER_DESC* pDesc) override { return ShaderDesc(ShaderStage::Domain, pDesc); }
  HRESULT GetComputeShaderDesc(PASS_SHADER_DESC* pDesc) override { return ShaderDesc(ShaderStage::Compute, pDesc); }
  EffectVariable* GetAnnotationByIndex(UINT Index) override;
  EffectVariable* GetAnnotationByName(LPCSTR Name) override;
  HRESULT Apply(UINT Flags, rhi::DeviceContext* pContext) override;
  HRESULT ShaderDesc(ShaderStage stage, PASS_SHADER_DESC* pDesc);

  EffectImpl* effect_ = nullptr;
  const Pass* ast_ = nullptr;
  std::vector<PassAction> actions_;
  std::string marker_;  // "technique/pass": Apply's SetMarker
};

class TechniqueImpl final : public EffectTechnique {
 public:
  BOOL IsValid() override { return effect_ != nullptr; }
  HRESULT GetDesc(TECHNIQUE_DESC* pDesc) override;
  EffectVariable* GetAnnotationByIndex(UINT Index) override;
  EffectVariable* GetAnnotationByName(LPCSTR Name) override;
  EffectPass* GetPassByIndex(UINT Index) override;
  EffectPass* GetPassByName(LPCSTR Name) override;

  EffectImpl* effect_ = nullptr;
  const Technique* ast_ = nullptr;
  std::vector<PassImpl> passes_;
};

class EffectImpl final : public Effect {
 public:
  BOOL IsValid() override { return rhi::TRUE; }
  HRESULT GetDevice(rhi::Device** ppDevice) override;
  HRESULT GetDesc(EFFECT_DESC* pDesc) override;
  EffectConstantBuffer* GetConstantBufferByIndex(UINT Index) override;
  EffectConstantBuffer* GetConstantBufferByName(LPCSTR Name) override;
  EffectVariable* GetVariableByIndex(UINT Index) override;
  EffectVariable* GetVariableByName(LPCSTR Name) override;
  EffectVariable* GetVariableBySemantic(LPCSTR Semantic) override;
  EffectTechnique* GetTechniqueByIndex(UINT Index) override;
  EffectTechnique* GetTechniqueByName(LPCSTR Name) override;

  // Writes the cbuffers' changed bytes to the buffers `shader` reads.
  void Upload(rhi::DeviceContext* context, const ShaderState& shader);
  // A variable view owned by the effect (elements and members are made on demand).
  VariableImpl* Own(VariableImpl&& view);
  // Annotation `index` of `list` (or the one called `name`) as a read-only variable.
  EffectVariable* Annotation(const std::vector<fx::Annotation>& list, UINT index);
  EffectVariable* Annotation(const std::vector<fx::Annotation>& list, LPCSTR name);
  // The anonymous shader variable of an inline shader (`shader` >= 0) or a
  // stage's NULL shader (`shader` -1).
  VariableImpl* AnonymousShader(ShaderStage stage, int shader);

  ComPtr<rhi::Device> device;  // a reference: the effect still has to go before the device (its RHI children)
  EffectAst ast;
  EFFECT_DESC stats;
  std::vector<CBufferState> cbuffers;
  std::vector<ObjectSlots<rhi::ShaderResourceView>> srvs;       // per ast.resources
  std::vector<ObjectSlots<rhi::UnorderedAccessView>> uavs;      // per ast.resources
  std::vector<ObjectSlots<rhi::SamplerState>> samplers;         // per ast.samplers
  std::vector<ObjectSlots<rhi::BlendState>> blendStates;        // per ast.blendStates
  std::vector<ObjectSlots<rhi::DepthStencilState>> depthStates; // per ast.depthStencilStates
  std::vector<ObjectSlots<rhi::RasterizerState>> rasterStates;  // per ast.rasterizerStates
  std::vector<ShaderState> shaders;                             // per ast.shaders
  std::vector<TechniqueImpl> techniques;

  std::deque<VariableImpl> views;           // every variable object; stable addresses
  std::vector<VariableImpl*> globals;       // GetVariableByIndex order
  std::vector<VariableImpl*> cbufferViews;  // per cbuffers
  std::map<std::tuple<const VariableImpl*, int, uint32_t>, VariableImpl*> subViews;  // (parent, member or -1, element)
  std::map<const fx::Annotation*, VariableImpl*> annotationViews;
  std::map<std::pair<ShaderStage, int>, VariableImpl*> anonymousShaders;

 private:
  ~EffectImpl() override;
};

// AST -> compiled shaders -> RHI objects. Appends "file:line:column: error: ..." lines to `errors`.
bool LoadEffect(EffectImpl& effect, const EFFECT_OPTIONS& options, std::vector<std::string>& errors);

}  // namespace fx::detail
