#include "variables.h"

#include <cstring>
#include <strings.h>

namespace fx::detail {
namespace {

using rhi::E_FAIL;
using rhi::E_INVALIDARG;
using rhi::S_OK;

uint32_t Round16(uint32_t n) { return (n + 15) / 16 * 16; }

// FX11 converts on every Set/Get to the type the variable was declared with.
void Store(uint8_t* dst, ScalarType to, double value, bool isBool) {
  uint32_t bits = 0;
  switch (to) {
    case ScalarType::Float: {
      float f = static_cast<float>(value);
      std::memcpy(&bits, &f, 4);
      break;
    }
    case ScalarType::Int:
    case ScalarType::UInt: bits = static_cast<uint32_t>(static_cast<int64_t>(value)); break;
    // bool true is stored as FX11 stores it (0xFFFFFFFF), whatever the source type.
    case ScalarType::Bool: bits = (isBool ? value != 0 : value != 0) ? 0xFFFFFFFFu : 0u; break;
    case ScalarType::Double: bits = 0; break;  // doubles are not supported in cbuffers here
  }
  std::memcpy(dst, &bits, 4);
}

double Load(const uint8_t* src, ScalarType from) {
  uint32_t bits;
  std::memcpy(&bits, src, 4);
  switch (from) {
    case ScalarType::Float: {
      float f;
      std::memcpy(&f, &bits, 4);
      return f;
    }
    case ScalarType::Int: return static_cast<int32_t>(bits);
    case ScalarType::UInt: return bits;
    case ScalarType::Bool: return bits != 0 ? 1 : 0;
    case ScalarType::Double: return 0;
  }
  return 0;
}

template <class T>
void AddRefOut(T* object, T** out) {
  if (object) object->AddRef();
  *out = object;
}

const char* ResourceTypeName(ResourceKind k) {
  static const char* const kNames[] = {"texture", "Texture1D", "Texture1DArray", "Texture2D", "Texture2DArray",
                                       "Texture2DMS", "Texture2DMSArray", "Texture3D", "TextureCube",
                                       "TextureCubeArray", "Buffer", "ByteAddressBuffer", "StructuredBuffer",
                                       "RWTexture1D", "RWTexture1DArray", "RWTexture2D", "RWTexture2DArray",
                                       "RWTexture3D", "RWBuffer", "RWByteAddressBuffer", "RWStructuredBuffer",
                                       "AppendStructuredBuffer", "ConsumeStructuredBuffer"};
  return kNames[static_cast<int>(k)];
}

const char* ShaderTypeName(ShaderStage stage) {
  static const char* const kNames[] = {"VertexShader", "HullShader",  "DomainShader",
                                       "GeometryShader", "PixelShader", "ComputeShader"};
  return kNames[static_cast<int>(stage)];
}

uint32_t Product(const std::vector<uint32_t>& dims, size_t from) {
  uint32_t n = 1;
  for (size_t i = from; i < dims.size(); ++i) n *= dims[i];
  return n;
}

}  // namespace

VariableImpl* VariableImpl::Invalid() {
  static VariableImpl invalid;
  return &invalid;
}

// --------------------------------------------------------------------------
// Shape

uint32_t VariableImpl::ElementCount() const {
  if (kind == Kind::Numeric) return type ? type->ElementCount() : 0;
  return Product(arrayDims, 0);
}

uint32_t VariableImpl::ElementStride() const { return type ? Round16(PackedElementSize(*type)) : 0; }

uint8_t* VariableImpl::Bytes() {
  // An annotation's bytes are never written: every setter refuses annotations.
  if (annotation) return const_cast<uint8_t*>(annotation->bytes.data()) + offset;
  return effect->cbuffers[index].data.data() + offset;
}

void VariableImpl::Touch() { ++effect->cbuffers[index].version; }

HRESULT VariableImpl::GetDesc(EFFECT_VARIABLE_DESC* pDesc) {
  if (!IsValid() || !pDesc) return E_FAIL;
  *pDesc = {};
  pDesc->Name = name.c_str();
  pDesc->Semantic = semantic.empty() ? nullptr : semantic.c_str();
  pDesc->BufferOffset = kind == Kind::Numeric ? offset : 0;
  pDesc->ExplicitBindPoint = explicitBindPoint;
  pDesc->Annotations = annotations ? static_cast<UINT>(annotations->size()) : 0;
  return S_OK;
}

EffectVariable* VariableImpl::GetAnnotationByIndex(UINT Index) {
  return IsValid() && annotations ? effect->Annotation(*annotations, Index) : Invalid();
}

EffectVariable* VariableImpl::GetAnnotationByName(LPCSTR Name) {
  return IsValid() && annotations ? effect->Annotation(*annotations, Name) : Invalid();
}

HRESULT VariableImpl::GetTypeDesc(EFFECT_TYPE_DESC* pDesc) {
  if (!IsValid() || !pDesc) return E_FAIL;
  *pDesc = {};
  if (kind != Kind::Numeric) {
    pDesc->TypeName = typeName.c_str();
    pDesc->Class = kind == Kind::ConstantBuffer ? SVC_STRUCT : SVC_OBJECT;
    pDesc->Elements = arrayDims.empty() ? 0 : ElementCount();
    return S_OK;
  }
  pDesc->TypeName = type->name.c_str();
  switch (type->cls) {
    case VariableType::Class::Scalar: pDesc->Class = SVC_SCALAR; break;
    case VariableType::Class::Vector: pDesc->Class = SVC_VECTOR; break;
    case VariableType::Class::Matrix: pDesc->Class = type->rowMajor ? SVC_MATRIX_ROWS : SVC_MATRIX_COLUMNS; break;
    case VariableType::Class::Struct: pDesc->Class = SVC_STRUCT; break;
  }
  pDesc->Elements = type->arrayDims.empty() ? 0 : type->ElementCount();
  pDesc->Members = static_cast<UINT>(type->members.size());
  pDesc->Rows = type->rows;
  pDesc->Columns = type->columns;
  pDesc->PackedSize = type->size;
  return S_OK;
}

EffectVariable* VariableImpl::GetElement(UINT Index) {
  if (!IsValid() || kind == Kind::ConstantBuffer) return Invalid();
  const std::vector<uint32_t>& dims = kind == Kind::Numeric ? type->arrayDims : arrayDims;
  if (dims.empty() || Index >= dims[0]) return Invalid();
  auto key = std::make_tuple(static_cast<const VariableImpl*>(this), -1, Index);
  if (auto it = effect->subViews.find(key); it != effect->subViews.end()) return it->second;
  VariableImpl view = *this;
  view.name = name + "[" + std::to_string(Index) + "]";
  if (kind == Kind::Numeric) {
    // An element of T[a][b] is a T[b]: drop the first dimension, step over whole sub-arrays.
    auto element = std::make_shared<VariableType>(*type);
    element->arrayDims.erase(element->arrayDims.begin());
    view.offset = offset + Index * Product(type->arrayDims, 1) * ElementStride();
    element->size = element->arrayDims.empty()
                        ? element->elementSize
                        : (element->ElementCount() - 1) * ElementStride() + element->elementSize;
    view.ownedType = element;
    view.type = element.get();
  } else {
    view.arrayDims.erase(view.arrayDims.begin());
    view.firstElement = firstElement + Index * Product(arrayDims, 1);
  }
  return effect->subViews[key] = effect->Own(std::move(view));
}

EffectVariable* VariableImpl::GetMemberByIndex(UINT Index) {
  if (kind == Kind::ConstantBuffer) {
    // A cbuffer's members are its variables, in declaration order.
    for (VariableImpl* v : effect->globals)
      if (v->kind == Kind::Numeric && v->index == index && Index-- == 0) return v;
    return Invalid();
  }
  if (kind != Kind::Numeric || type->cls != VariableType::Class::Struct || !type->arrayDims.empty() ||
      Index >= type->members.size())
    return Invalid();
  auto key = std::make_tuple(static_cast<const VariableImpl*>(this), static_cast<int>(Index), 0u);
  if (auto it = effect->subViews.find(key); it != effect->subViews.end()) return it->second;
  const StructMember& m = type->members[Index];
  VariableImpl view = *this;
  view.name = name + "." + m.name;
  view.semantic.clear();
  view.offset = offset + m.offset;
  view.ownedType.reset();
  view.type = &m.type;
  return effect->subViews[key] = effect->Own(std::move(view));
}

EffectVariable* VariableImpl::GetMemberByName(LPCSTR Name) {
  if (!Name) return Invalid();
  if (kind == Kind::ConstantBuffer) {
    for (VariableImpl* v : effect->globals)
      if (v->kind == Kind::Numeric && v->index == index && v->name == Name) return v;
    return Invalid();
  }
  if (kind != Kind::Numeric || type->cls != VariableType::Class::Struct) return Invalid();
  for (UINT i = 0; i < type->members.size(); ++i)
    if (type->members[i].name == Name) return GetMemberByIndex(i);
  return Invalid();
}

EffectConstantBuffer* VariableImpl::GetParentConstantBuffer() {
  if (kind != Kind::Numeric) return Invalid();
  return effect->cbufferViews[index];
}

EffectScalarVariable* VariableImpl::AsScalar() { return IsNumeric(VariableType::Class::Scalar) ? this : Invalid(); }
EffectVectorVariable* VariableImpl::AsVector() { return IsNumeric(VariableType::Class::Vector) ? this : Invalid(); }
EffectMatrixVariable* VariableImpl::AsMatrix() { return IsNumeric(VariableType::Class::Matrix) ? this : Invalid(); }

// --------------------------------------------------------------------------
// Numeric values

HRESULT VariableImpl::SetRawValue(const void* pData, UINT ByteOffset, UINT ByteCount) {
  if (annotation) return E_FAIL;  // FX11: annotations are read-only
  if (kind != Kind::Numeric || !pData || uint64_t(ByteOffset) + ByteCount > type->size) return E_INVALIDARG;
  std::memcpy(Bytes() + ByteOffset, pData, ByteCount);
  Touch();
  return S_OK;
}

HRESULT VariableImpl::GetRawValue(void* pData, UINT ByteOffset, UINT ByteCount) {
  if (kind != Kind::Numeric || !pData || uint64_t(ByteOffset) + ByteCount > type->size) return E_INVALIDARG;
  std::memcpy(pData, Bytes() + ByteOffset, ByteCount);
  return S_OK;
}

template <class T>
HRESULT VariableImpl::SetComponents(const T* values, UINT first, UINT elements, UINT components, UINT srcStride) {
  if (annotation) return E_FAIL;
  if (kind != Kind::Numeric || !values || uint64_t(first) + elements > ElementCount() ||
      type->cls == VariableType::Class::Struct || type->cls == VariableType::Class::Matrix)
    return E_INVALIDARG;
  components = std::min(components, type->columns);
  for (UINT e = 0; e < elements; ++e)
    for (UINT c = 0; c < components; ++c)
      Store(Bytes() + (first + e) * ElementStride() + c * 4, type->scalar, static_cast<double>(values[e * srcStride + c]),
            std::is_same_v<T, bool>);
  Touch();
  return S_OK;
}

template <class T>
HRESULT VariableImpl::GetComponents(T* values, UINT first, UINT elements, UINT components, UINT dstStride) {
  if (kind != Kind::Numeric || !values || uint64_t(first) + elements > ElementCount() ||
      type->cls == VariableType::Class::Struct || type->cls == VariableType::Class::Matrix)
    return E_INVALIDARG;
  components = std::min(components, type->columns);
  for (UINT e = 0; e < elements; ++e)
    for (UINT c = 0; c < components; ++c)
      values[e * dstStride + c] = static_cast<T>(Load(Bytes() + (first + e) * ElementStride() + c * 4, type->scalar));
  return S_OK;
}

HRESULT VariableImpl::SetFloatArray(const float* p, UINT o, UINT n) { return SetComponents(p, o, n, 1, 1); }
HRESULT VariableImpl::GetFloatArray(float* p, UINT o, UINT n) { return GetComponents(p, o, n, 1, 1); }
HRESULT VariableImpl::SetIntArray(const int* p, UINT o, UINT n) { return SetComponents(p, o, n, 1, 1); }
HRESULT VariableImpl::GetIntArray(int* p, UINT o, UINT n) { return GetComponents(p, o, n, 1, 1); }
HRESULT VariableImpl::SetBool(bool v) { return SetComponents(&v, 0, 1, 1, 1); }
HRESULT VariableImpl::GetBool(bool* p) {
  int v = 0;
  HRESULT hr = GetComponents(&v, 0, 1, 1, 1);
  if (rhi::SUCCEEDED(hr)) *p = v != 0;
  return hr;
}

HRESULT VariableImpl::SetFloatVector(const float* p) { return SetComponents(p, 0, 1, 4, 4); }
HRESULT VariableImpl::GetFloatVector(float* p) { return GetComponents(p, 0, 1, 4, 4); }
HRESULT VariableImpl::SetIntVector(const int* p) { return SetComponents(p, 0, 1, 4, 4); }
HRESULT VariableImpl::GetIntVector(int* p) { return GetComponents(p, 0, 1, 4, 4); }
HRESULT VariableImpl::SetBoolVector(const bool* p) { return SetComponents(p, 0, 1, 4, 4); }
HRESULT VariableImpl::SetFloatVectorArray(const float* p, UINT o, UINT n) { return SetComponents(p, o, n, 4, 4); }
HRESULT VariableImpl::GetFloatVectorArray(float* p, UINT o, UINT n) { return GetComponents(p, o, n, 4, 4); }
HRESULT VariableImpl::SetIntVectorArray(const int* p, UINT o, UINT n) { return SetComponents(p, o, n, 4, 4); }

// D3DX matrices are row-major 4x4 (m[row * 4 + col]); the variable stores
// column c of a column_major matrix in register c, row r of a row_major one in register r.
HRESULT VariableImpl::MatrixAccess(float* data, UINT Offset, UINT Count, bool write, bool transpose) {
  if (annotation && write) return E_FAIL;
  if (!IsNumeric(VariableType::Class::Matrix) || !data || uint64_t(Offset) + Count > ElementCount())
    return E_INVALIDARG;
  for (UINT e = 0; e < Count; ++e) {
    float* m = data + e * 16;
    if (!write) std::fill(m, m + 16, 0.0f);
    uint8_t* element = Bytes() + (Offset + e) * ElementStride();
    for (UINT r = 0; r < type->rows; ++r) {
      for (UINT c = 0; c < type->columns; ++c) {
        uint8_t* at = element + (type->rowMajor ? r * 16 + c * 4 : c * 16 + r * 4);
        float& value = transpose ? m[c * 4 + r] : m[r * 4 + c];
        if (write)
          Store(at, type->scalar, value, false);
        else
          value = static_cast<float>(Load(at, type->scalar));
      }
    }
  }
  if (write) Touch();
  return S_OK;
}

HRESULT VariableImpl::SetMatrixArray(const float* p, UINT o, UINT n) {
  return MatrixAccess(const_cast<float*>(p), o, n, true, false);
}
HRESULT VariableImpl::GetMatrixArray(float* p, UINT o, UINT n) { return MatrixAccess(p, o, n, false, false); }
HRESULT VariableImpl::SetMatrixTranspose(const float* p) { return MatrixAccess(const_cast<float*>(p), 0, 1, true, true); }
HRESULT VariableImpl::GetMatrixTranspose(float* p) { return MatrixAccess(p, 0, 1, false, true); }

// --------------------------------------------------------------------------
// Objects

HRESULT VariableImpl::GetString(LPCSTR* ppString) {
  if (kind != Kind::String || !ppString) return E_FAIL;
  if (annotation) {
    *ppString = annotation->stringValue.c_str();
    return S_OK;
  }
  const auto& values = effect->ast.strings[index].values;
  *ppString = firstElement < values.size() ? values[firstElement].c_str() : "";
  return S_OK;
}

template <class Slots>
Slots* VariableImpl::ObjectSlotsFor(Kind k, UINT elementIndex, size_t* element) {
  if (kind != k || elementIndex >= ElementCount()) return nullptr;
  *element = firstElement + elementIndex;
  Slots* slots = nullptr;
  if constexpr (std::is_same_v<Slots, ObjectSlots<rhi::ShaderResourceView>>) slots = &effect->srvs[index];
  if constexpr (std::is_same_v<Slots, ObjectSlots<rhi::UnorderedAccessView>>) slots = &effect->uavs[index];
  if constexpr (std::is_same_v<Slots, ObjectSlots<rhi::SamplerState>>) slots = &effect->samplers[index];
  if constexpr (std::is_same_v<Slots, ObjectSlots<rhi::BlendState>>) slots = &effect->blendStates[index];
  if constexpr (std::is_same_v<Slots, ObjectSlots<rhi::DepthStencilState>>) slots = &effect->depthStates[index];
  if constexpr (std::is_same_v<Slots, ObjectSlots<rhi::RasterizerState>>) slots = &effect->rasterStates[index];
  if (slots->user.size() <= *element) slots->user.resize(*element + 1);
  return slots;
}

#define FXRT_OBJECT_ACCESSORS(Type, KindName, GetName, SetName)                                    \
  HRESULT VariableImpl::GetName(UINT Index, rhi::Type** pp) {                                       \
    size_t e;                                                                                       \
    auto* slots = ObjectSlotsFor<ObjectSlots<rhi::Type>>(Kind::KindName, Index, &e);                \
    if (!slots || !pp) return E_FAIL;                                                               \
    AddRefOut(slots->Get(e), pp);                                                                   \
    return S_OK;                                                                                    \
  }                                                                                                 \
  HRESULT VariableImpl::SetName(UINT Index, rhi::Type* p) {                                         \
    size_t e;                                                                                       \
    auto* slots = ObjectSlotsFor<ObjectSlots<rhi::Type>>(Kind::KindName, Index, &e);                \
    if (!slots) return E_FAIL;                                                                      \
    slots->user[e] = p;                                                                             \
    return S_OK;                                                                                    \
  }
FXRT_OBJECT_ACCESSORS(SamplerState, Sampler, GetSampler, SetSampler)
FXRT_OBJECT_ACCESSORS(BlendState, Blend, GetBlendState, SetBlendState)
FXRT_OBJECT_ACCESSORS(DepthStencilState, DepthStencil, GetDepthStencilState, SetDepthStencilState)
FXRT_OBJECT_ACCESSORS(RasterizerState, Rasterizer, GetRasterizerState, SetRasterizerState)
#undef FXRT_OBJECT_ACCESSORS

HRESULT VariableImpl::GetBackingStore(UINT Index, rhi::SAMPLER_DESC* pDesc) {
  if (kind != Kind::Sampler || !pDesc || firstElement + Index >= effect->ast.samplers[index].descs.size()) return E_FAIL;
  *pDesc = effect->ast.samplers[index].descs[firstElement + Index];
  return S_OK;
}
HRESULT VariableImpl::GetBackingStore(UINT Index, rhi::BLEND_DESC* pDesc) {
  if (kind != Kind::Blend || !pDesc || firstElement + Index >= effect->ast.blendStates[index].descs.size()) return E_FAIL;
  *pDesc = effect->ast.blendStates[index].descs[firstElement + Index];
  return S_OK;
}
HRESULT VariableImpl::GetBackingStore(UINT Index, rhi::DEPTH_STENCIL_DESC* pDesc) {
  if (kind != Kind::DepthStencil || !pDesc || firstElement + Index >= effect->ast.depthStencilStates[index].descs.size())
    return E_FAIL;
  *pDesc = effect->ast.depthStencilStates[index].descs[firstElement + Index];
  return S_OK;
}
HRESULT VariableImpl::GetBackingStore(UINT Index, rhi::RASTERIZER_DESC* pDesc) {
  if (kind != Kind::Rasterizer || !pDesc || firstElement + Index >= effect->ast.rasterizerStates[index].descs.size())
    return E_FAIL;
  *pDesc = effect->ast.rasterizerStates[index].descs[firstElement + Index];
  return S_OK;
}

HRESULT VariableImpl::GetResource(rhi::ShaderResourceView** pp) {
  size_t e;
  auto* slots = ObjectSlotsFor<ObjectSlots<rhi::ShaderResourceView>>(Kind::Resource, 0, &e);
  if (!slots || !pp) return E_FAIL;
  AddRefOut(slots->Get(e), pp);
  return S_OK;
}

HRESULT VariableImpl::SetResourceArray(rhi::ShaderResourceView* const* pp, UINT Offset, UINT Count) {
  if (kind != Kind::Resource || !pp || uint64_t(Offset) + Count > ElementCount()) return E_INVALIDARG;
  for (UINT i = 0; i < Count; ++i) {
    size_t e;
    ObjectSlotsFor<ObjectSlots<rhi::ShaderResourceView>>(Kind::Resource, Offset + i, &e)->user[e] = pp[i];
  }
  return S_OK;
}

HRESULT VariableImpl::SetUnorderedAccessView(rhi::UnorderedAccessView* p) {
  size_t e;
  auto* slots = ObjectSlotsFor<ObjectSlots<rhi::UnorderedAccessView>>(Kind::UnorderedAccess, 0, &e);
  if (!slots) return E_FAIL;
  slots->user[e] = p;
  return S_OK;
}

HRESULT VariableImpl::GetUnorderedAccessView(rhi::UnorderedAccessView** pp) {
  size_t e;
  auto* slots = ObjectSlotsFor<ObjectSlots<rhi::UnorderedAccessView>>(Kind::UnorderedAccess, 0, &e);
  if (!slots || !pp) return E_FAIL;
  AddRefOut(slots->Get(e), pp);
  return S_OK;
}

HRESULT VariableImpl::SetConstantBuffer(rhi::Buffer* p) {
  if (kind != Kind::ConstantBuffer) return E_FAIL;
  effect->cbuffers[index].userBuffer = p;
  return S_OK;
}

HRESULT VariableImpl::GetConstantBuffer(rhi::Buffer** pp) {
  if (kind != Kind::ConstantBuffer || !pp) return E_FAIL;
  CBufferState& cb = effect->cbuffers[index];
  AddRefOut(cb.userBuffer ? cb.userBuffer.Get() : cb.layouts.empty() ? nullptr : cb.layouts[0].buffer.Get(), pp);
  return S_OK;
}

int VariableImpl::ShaderAt(UINT Index) const {
  if (index < 0) return Index == 0 ? anonymousShader : -2;
  const auto& shaders = effect->ast.shaderVariables[index].shaders;
  return firstElement + Index < shaders.size() ? shaders[firstElement + Index] : -2;
}

#define FXRT_SHADER_GETTER(Type, Member)                                                   \
  HRESULT VariableImpl::Get##Type(UINT Index, rhi::Type** pp) {                            \
    if (kind != Kind::Shader || !pp) return E_FAIL;                                        \
    int s = ShaderAt(Index);                                                               \
    if (s < -1) return E_INVALIDARG;                                                       \
    AddRefOut(s < 0 ? nullptr : effect->shaders[s].Member.Get(), pp);                      \
    return S_OK;                                                                           \
  }
FXRT_SHADER_GETTER(VertexShader, vs)
FXRT_SHADER_GETTER(GeometryShader, gs)
FXRT_SHADER_GETTER(PixelShader, ps)
FXRT_SHADER_GETTER(ComputeShader, cs)
#undef FXRT_SHADER_GETTER

HRESULT VariableImpl::GetShaderDesc(UINT ShaderIndex, EFFECT_SHADER_DESC* pDesc) {
  if (kind != Kind::Shader || !pDesc) return E_FAIL;
  int s = ShaderAt(ShaderIndex);
  if (s < -1) return E_INVALIDARG;
  *pDesc = {};
  pDesc->IsInline = index < 0 ? rhi::TRUE : rhi::FALSE;
  if (s < 0) return S_OK;  // NULL
  const ShaderState& shader = effect->shaders[s];
  pDesc->pBytecode = shader.code->spirv.data();
  pDesc->BytecodeLength = static_cast<UINT>(shader.code->spirv.size() * 4);
  pDesc->pInputSignature = pDesc->pBytecode;
  if (shader.ast->hasStreamOutput) {
    for (size_t k = 0; k < rhi::SO_STREAM_COUNT; ++k) {
      const std::string& decl = shader.ast->soDeclarations[k];
      pDesc->SODecls[k] = decl.empty() ? nullptr : decl.c_str();
    }
    pDesc->RasterizedStream = shader.ast->rasterizedStream;
  }
  return S_OK;
}

// --------------------------------------------------------------------------
// Building the variables of an effect

namespace {

template <class Var>
VariableImpl ObjectView(EffectImpl& effect, VariableImpl::Kind kind, const Var& v, int index, std::string typeName) {
  VariableImpl view;
  view.kind = kind;
  view.effect = &effect;
  view.name = v.name;
  view.index = index;
  if constexpr (requires { v.arrayDims; }) view.arrayDims = v.arrayDims;
  view.annotations = &v.annotations;
  view.typeName = std::move(typeName);
  return view;
}

VariableImpl AnnotationView(EffectImpl& effect, const fx::Annotation& a) {
  VariableImpl view;
  view.effect = &effect;
  view.name = a.name;
  view.annotation = &a;
  if (a.type == "string") {
    view.kind = VariableImpl::Kind::String;
    view.typeName = "string";
  } else {
    view.kind = VariableImpl::Kind::Numeric;
    view.type = &a.valueType;
  }
  return view;
}

}  // namespace

EffectVariable* EffectImpl::Annotation(const std::vector<fx::Annotation>& list, UINT index) {
  if (index >= list.size()) return VariableImpl::Invalid();
  VariableImpl*& view = annotationViews[&list[index]];
  if (!view) view = Own(AnnotationView(*this, list[index]));
  return view;
}

EffectVariable* EffectImpl::Annotation(const std::vector<fx::Annotation>& list, LPCSTR name) {
  for (size_t i = 0; name && i < list.size(); ++i) {
    if (list[i].name == name) return Annotation(list, static_cast<UINT>(i));
  }
  return VariableImpl::Invalid();
}

VariableImpl* EffectImpl::AnonymousShader(ShaderStage stage, int shader) {
  VariableImpl*& view = anonymousShaders[{stage, shader}];
  if (!view) {
    VariableImpl v;
    v.kind = VariableImpl::Kind::Shader;
    v.effect = this;
    v.name = "$Anonymous";
    v.typeName = ShaderTypeName(stage);
    v.anonymousShader = shader;
    view = Own(std::move(v));
  }
  return view;
}

void BuildVariables(EffectImpl& effect) {
  const EffectAst& ast = effect.ast;
  auto add = [&](VariableImpl&& v) { effect.globals.push_back(effect.Own(std::move(v))); };
  for (size_t c = 0; c < ast.cbuffers.size(); ++c) {
    VariableImpl cb;
    cb.kind = VariableImpl::Kind::ConstantBuffer;
    cb.effect = &effect;
    cb.name = ast.cbuffers[c].name;
    cb.index = static_cast<int>(c);
    cb.typeName = ast.cbuffers[c].isTBuffer ? "tbuffer" : "cbuffer";
    if (ast.cbuffers[c].reg) cb.explicitBindPoint = ast.cbuffers[c].reg->index;
    effect.cbufferViews.push_back(effect.Own(std::move(cb)));
    for (const ConstantVariable& v : ast.cbuffers[c].variables) {
      VariableImpl view;
      view.kind = VariableImpl::Kind::Numeric;
      view.effect = &effect;
      view.name = v.name;
      view.semantic = v.semantic;
      view.index = static_cast<int>(c);
      view.type = &v.type;
      view.offset = v.offset;
      view.annotations = &v.annotations;
      add(std::move(view));
    }
  }
  for (size_t i = 0; i < ast.resources.size(); ++i) {
    const ResourceVariable& r = ast.resources[i];
    auto kind = IsUnorderedAccess(r.kind) ? VariableImpl::Kind::UnorderedAccess : VariableImpl::Kind::Resource;
    std::string typeName = ResourceTypeName(r.kind);
    if (!r.templateArgs.empty()) typeName += "<" + r.templateArgs + ">";
    VariableImpl view = ObjectView(effect, kind, r, static_cast<int>(i), std::move(typeName));
    if (r.reg) view.explicitBindPoint = r.reg->index;
    add(std::move(view));
  }
  for (size_t i = 0; i < ast.samplers.size(); ++i) {
    const SamplerVariable& s = ast.samplers[i];
    VariableImpl view = ObjectView(effect, VariableImpl::Kind::Sampler, s, static_cast<int>(i),
                                   s.comparison ? "SamplerComparisonState" : "SamplerState");
    if (s.reg) view.explicitBindPoint = s.reg->index;
    add(std::move(view));
  }
  for (size_t i = 0; i < ast.blendStates.size(); ++i)
    add(ObjectView(effect, VariableImpl::Kind::Blend, ast.blendStates[i], static_cast<int>(i), "BlendState"));
  for (size_t i = 0; i < ast.depthStencilStates.size(); ++i)
    add(ObjectView(effect, VariableImpl::Kind::DepthStencil, ast.depthStencilStates[i], static_cast<int>(i),
                   "DepthStencilState"));
  for (size_t i = 0; i < ast.rasterizerStates.size(); ++i)
    add(ObjectView(effect, VariableImpl::Kind::Rasterizer, ast.rasterizerStates[i], static_cast<int>(i),
                   "RasterizerState"));
  for (size_t i = 0; i < ast.strings.size(); ++i) {
    VariableImpl view = ObjectView(effect, VariableImpl::Kind::String, ast.strings[i], static_cast<int>(i), "string");
    if (ast.strings[i].values.size() > 1) view.arrayDims = {static_cast<uint32_t>(ast.strings[i].values.size())};
    add(std::move(view));
  }
  for (size_t i = 0; i < ast.shaderVariables.size(); ++i)
    add(ObjectView(effect, VariableImpl::Kind::Shader, ast.shaderVariables[i], static_cast<int>(i),
                   ShaderTypeName(ast.shaderVariables[i].stage)));
}

}  // namespace fx::detail
