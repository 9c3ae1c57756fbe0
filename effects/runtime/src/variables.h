// Every effect variable is one VariableImpl: it implements all of FX11's
// variable interfaces, and the As*() casts hand out `this` only for the
// matching kind (an invalid object otherwise), as FX11 does.
#pragma once

#include <memory>
#include <string>

#include "effect_impl.h"

namespace fx::detail {

class VariableImpl final : public EffectScalarVariable,
                           public EffectVectorVariable,
                           public EffectMatrixVariable,
                           public EffectStringVariable,
                           public EffectShaderResourceVariable,
                           public EffectUnorderedAccessViewVariable,
                           public EffectSamplerVariable,
                           public EffectBlendVariable,
                           public EffectDepthStencilVariable,
                           public EffectRasterizerVariable,
                           public EffectConstantBuffer,
                           public EffectShaderVariable {
 public:
  enum class Kind { Invalid, Numeric, ConstantBuffer, Resource, UnorderedAccess, Sampler, Blend, DepthStencil,
                    Rasterizer, String, Shader };

  // The shared invalid object every failed lookup returns.
  static VariableImpl* Invalid();

  Kind kind = Kind::Invalid;
  EffectImpl* effect = nullptr;
  std::string name;
  std::string semantic;
  std::string typeName;
  int index = -1;  // Numeric / ConstantBuffer: the cbuffer; objects: index into the AST's list
  // Numeric: the variable (or element, or member) inside cbuffers[index].
  const VariableType* type = nullptr;
  std::shared_ptr<VariableType> ownedType;  // an element's type (the array's without its first dimension)
  uint32_t offset = 0;
  // Objects: which elements of the variable this view covers.
  std::vector<uint32_t> arrayDims;
  uint32_t firstElement = 0;
  uint32_t explicitBindPoint = ~0u;
  const std::vector<fx::Annotation>* annotations = nullptr;  // the variable's own
  const fx::Annotation* annotation = nullptr;  // set when this view IS an annotation (read-only)
  // Shader views without a variable (index -1): the inline shader they stand
  // for, -1 for a NULL shader.
  int anonymousShader = -1;

  // EffectVariable
  BOOL IsValid() override { return kind != Kind::Invalid; }
  HRESULT GetDesc(EFFECT_VARIABLE_DESC* pDesc) override;
  HRESULT GetTypeDesc(EFFECT_TYPE_DESC* pDesc) override;
  EffectVariable* GetAnnotationByIndex(UINT Index) override;
  EffectVariable* GetAnnotationByName(LPCSTR Name) override;
  EffectVariable* GetMemberByIndex(UINT Index) override;
  EffectVariable* GetMemberByName(LPCSTR Name) override;
  EffectVariable* GetElement(UINT Index) override;
  EffectConstantBuffer* GetParentConstantBuffer() override;
  EffectScalarVariable* AsScalar() override;
  EffectVectorVariable* AsVector() override;
  EffectMatrixVariable* AsMatrix() override;
  EffectStringVariable* AsString() override { return Is(Kind::String); }
  EffectShaderResourceVariable* AsShaderResource() override { return Is(Kind::Resource); }
  EffectUnorderedAccessViewVariable* AsUnorderedAccessView() override { return Is(Kind::UnorderedAccess); }
  EffectSamplerVariable* AsSampler() override { return Is(Kind::Sampler); }
  EffectBlendVariable* AsBlend() override { return Is(Kind::Blend); }
  EffectDepthStencilVariable* AsDepthStencil() override { return Is(Kind::DepthStencil); }
  EffectRasterizerVariable* AsRasterizer() override { return Is(Kind::Rasterizer); }
  EffectConstantBuffer* AsConstantBuffer() override { return Is(Kind::ConstantBuffer); }
  EffectShaderVariable* AsShader() override { return Is(Kind::Shader); }
  HRESULT SetRawValue(const void* pData, UINT ByteOffset, UINT ByteCount) override;
  HRESULT GetRawValue(void* pData, UINT ByteOffset, UINT ByteCount) override;

  // Scalar
  HRESULT SetFloat(float Value) override { return SetFloatArray(&Value, 0, 1); }
  HRESULT GetFloat(float* pValue) override { return GetFloatArray(pValue, 0, 1); }
  HRESULT SetFloatArray(const float* pData, UINT Offset, UINT Count) override;
  HRESULT GetFloatArray(float* pData, UINT Offset, UINT Count) override;
  HRESULT SetInt(int Value) override { return SetIntArray(&Value, 0, 1); }
  HRESULT GetInt(int* pValue) override { return GetIntArray(pValue, 0, 1); }
  HRESULT SetIntArray(const int* pData, UINT Offset, UINT Count) override;
  HRESULT GetIntArray(int* pData, UINT Offset, UINT Count) override;
  HRESULT SetBool(bool Value) override;
  HRESULT GetBool(bool* pValue) override;

  // Vector (arrays pass 4 components per element, like D3DXVECTOR4 arrays)
  HRESULT SetFloatVector(const float* pData) override;
  HRESULT GetFloatVector(float* pData) override;
  HRESULT SetIntVector(const int* pData) override;
  HRESULT GetIntVector(int* pData) override;
  HRESULT SetBoolVector(const bool* pData) override;
  HRESULT SetFloatVectorArray(const float* pData, UINT Offset, UINT Count) override;
  HRESULT GetFloatVectorArray(float* pData, UINT Offset, UINT Count) override;
  HRESULT SetIntVectorArray(const int* pData, UINT Offset, UINT Count) override;

  // Matrix
  HRESULT SetMatrix(const float* pData) override { return SetMatrixArray(pData, 0, 1); }
  HRESULT GetMatrix(float* pData) override { return GetMatrixArray(pData, 0, 1); }
  HRESULT SetMatrixArray(const float* pData, UINT Offset, UINT Count) override;
  HRESULT GetMatrixArray(float* pData, UINT Offset, UINT Count) override;
  HRESULT SetMatrixTranspose(const float* pData) override;
  HRESULT GetMatrixTranspose(float* pData) override;

  // String
  HRESULT GetString(LPCSTR* ppString) override;

  // Shader resource / UAV
  HRESULT SetResource(rhi::ShaderResourceView* pResource) override { return SetResourceArray(&pResource, 0, 1); }
  HRESULT GetResource(rhi::ShaderResourceView** ppResource) override;
  HRESULT SetResourceArray(rhi::ShaderResourceView* const* ppResources, UINT Offset, UINT Count) override;
  HRESULT SetUnorderedAccessView(rhi::UnorderedAccessView* pResource) override;
  HRESULT GetUnorderedAccessView(rhi::UnorderedAccessView** ppResource) override;

  // Sampler and state objects
  HRESULT GetSampler(UINT Index, rhi::SamplerState** ppSampler) override;
  HRESULT SetSampler(UINT Index, rhi::SamplerState* pSampler) override;
  HRESULT GetBackingStore(UINT Index, rhi::SAMPLER_DESC* pDesc) override;
  HRESULT GetBlendState(UINT Index, rhi::BlendState** ppState) override;
  HRESULT SetBlendState(UINT Index, rhi::BlendState* pState) override;
  HRESULT UndoSetBlendState(UINT Index) override { return SetBlendState(Index, nullptr); }
  HRESULT GetBackingStore(UINT Index, rhi::BLEND_DESC* pDesc) override;
  HRESULT GetDepthStencilState(UINT Index, rhi::DepthStencilState** ppState) override;
  HRESULT SetDepthStencilState(UINT Index, rhi::DepthStencilState* pState) override;
  HRESULT UndoSetDepthStencilState(UINT Index) override { return SetDepthStencilState(Index, nullptr); }
  HRESULT GetBackingStore(UINT Index, rhi::DEPTH_STENCIL_DESC* pDesc) override;
  HRESULT GetRasterizerState(UINT Index, rhi::RasterizerState** ppState) override;
  HRESULT SetRasterizerState(UINT Index, rhi::RasterizerState* pState) override;
  HRESULT UndoSetRasterizerState(UINT Index) override { return SetRasterizerState(Index, nullptr); }
  HRESULT GetBackingStore(UINT Index, rhi::RASTERIZER_DESC* pDesc) override;

  // Constant buffer
  HRESULT SetConstantBuffer(rhi::Buffer* pConstantBuffer) override;
  HRESULT UndoSetConstantBuffer() override { return SetConstantBuffer(nullptr); }
  HRESULT GetConstantBuffer(rhi::Buffer** ppConstantBuffer) override;

  // Shader
  HRESULT GetVertexShader(UINT Index, rhi::VertexShader** ppShader) override;
  HRESULT GetGeometryShader(UINT Index, rhi::GeometryShader** ppShader) override;
  HRESULT GetPixelShader(UINT Index, rhi::PixelShader** ppShader) override;
  HRESULT GetComputeShader(UINT Index, rhi::ComputeShader** ppShader) override;
  HRESULT GetShaderDesc(UINT ShaderIndex, EFFECT_SHADER_DESC* pDesc) override;

 private:
  VariableImpl* Is(Kind k) { return kind == k ? this : Invalid(); }
  bool IsNumeric(VariableType::Class cls) const {
    return kind == Kind::Numeric && type && type->cls == cls;
  }
  int ShaderAt(UINT index) const;  // Shader: the EffectImpl::shaders index of element `index`, -1 for NULL
  uint32_t ElementCount() const;  // numeric or object elements this view covers (1 when not an array)
  uint32_t ElementStride() const;  // numeric: bytes between elements in FX11 packing
  uint8_t* Bytes();                // numeric: the view's first byte in the FX11 shadow
  void Touch();                    // numeric: marks the cbuffer changed
  // Scalars and vectors: element e, component c, converted from/to the variable's scalar type.
  template <class T>
  HRESULT SetComponents(const T* values, UINT firstElement, UINT elements, UINT components, UINT srcStride);
  template <class T>
  HRESULT GetComponents(T* values, UINT firstElement, UINT elements, UINT components, UINT dstStride);
  HRESULT MatrixAccess(float* data, UINT Offset, UINT Count, bool write, bool transpose);
  template <class Slots>
  Slots* ObjectSlotsFor(Kind k, UINT index, size_t* element);
};

// Creates the effect's variable objects from its AST (globals and cbuffers).
void BuildVariables(EffectImpl& effect);

}  // namespace fx::detail
