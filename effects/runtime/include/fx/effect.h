// The FX11 effect runtime (ID3DX11Effect) over the RHI.
//
// Porting FX11 code is a rename: ID3DX11Effect -> fx::Effect,
// ID3DX11EffectTechnique -> fx::EffectTechnique, ID3DX11EffectPass -> fx::EffectPass,
// ID3DX11EffectMatrixVariable -> fx::EffectMatrixVariable, D3DX11_PASS_DESC ->
// fx::PASS_DESC, D3DX11CreateEffectFromFile -> fx::CreateEffectFromFile, ...
// Differences, forced by the platform:
//  - effects are created from .fx source (there is no fxc bytecode): the front
//    end (effects/fx) parses it, glslang compiles each CompileShader to SPIR-V,
//    and the result is cached on disk (EFFECT_OPTIONS::CacheDirectory);
//  - PASS_DESC::pIAInputSignature is the vertex shader's SPIR-V, which is what
//    rhi::Device::CreateInputLayout matches against;
//  - EFFECT_SHADER_DESC::pBytecode and pInputSignature are SPIR-V;
//  - no ID3DX11EffectGroup (fxgroup techniques are found by name like the
//    others; EFFECT_DESC::Groups counts them), interfaces, classes or effect pools.
// Variables, techniques and passes are owned by the Effect (never released by
// the caller), as in FX11. Methods of an invalid object (IsValid() == FALSE)
// fail with E_FAIL and return invalid objects.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "rhi/rhi.h"

namespace fx {

using rhi::BOOL;
using rhi::FLOAT;
using rhi::HRESULT;
using rhi::INT;
using rhi::LPCSTR;
using rhi::SIZE_T;
using rhi::UINT;

struct EFFECT_OPTIONS {
  std::vector<std::string> IncludeDirs;  // searched after the including file's folder
  std::vector<std::pair<std::string, std::string>> Defines;  // NAME, value ("" means 1)
  // Where compiled SPIR-V is cached. nullopt: $XDG_CACHE_HOME/d3d11-on-vulkan/spirv,
  // else ~/.cache/d3d11-on-vulkan/spirv, else no cache. An empty string: no cache.
  std::optional<std::string> CacheDirectory;
  // Receives every error as "file:line:column: error: message" lines (may be null).
  std::string* Errors = nullptr;
};

// D3DX11_EFFECT_DESC, plus how the shaders were obtained (not in FX11).
struct EFFECT_DESC {
  UINT ConstantBuffers = 0;
  UINT GlobalVariables = 0;  // every top-level variable: numeric, resource, sampler, state, string, shader
  UINT InterfaceVariables = 0;
  UINT Techniques = 0;
  UINT Groups = 0;
  UINT ShadersCompiled = 0;   // compiled by glslang during creation
  UINT ShadersFromCache = 0;  // read from the SPIR-V cache instead
};

struct TECHNIQUE_DESC {
  LPCSTR Name = nullptr;
  UINT Passes = 0;
  UINT Annotations = 0;
};

struct PASS_DESC {
  LPCSTR Name = nullptr;
  UINT Annotations = 0;
  const void* pIAInputSignature = nullptr;  // the pass's vertex shader SPIR-V, for CreateInputLayout
  SIZE_T IAInputSignatureSize = 0;
  UINT StencilRef = 0;
  UINT SampleMask = rhi::DEFAULT_SAMPLE_MASK;
  FLOAT BlendFactor[4] = {0, 0, 0, 0};
};

// D3DX11_EFFECT_VARIABLE_DESC (Flags: 0; ExplicitBindPoint: the register, or ~0u).
struct EFFECT_VARIABLE_DESC {
  LPCSTR Name = nullptr;
  LPCSTR Semantic = nullptr;
  UINT Flags = 0;
  UINT Annotations = 0;
  UINT BufferOffset = 0;  // bytes from the start of its cbuffer under FX11 packing
  UINT ExplicitBindPoint = ~0u;
};

// D3D_SHADER_VARIABLE_CLASS, reduced to what effects hold.
enum SHADER_VARIABLE_CLASS : UINT {
  SVC_SCALAR = 0,
  SVC_VECTOR = 1,
  SVC_MATRIX_ROWS = 2,
  SVC_MATRIX_COLUMNS = 3,
  SVC_OBJECT = 4,
  SVC_STRUCT = 5,
};

// D3DX11_EFFECT_TYPE_DESC, reduced: TypeName, Class, Elements, Rows, Columns, PackedSize.
// TypeName of a templated object type keeps its arguments as declared
// ("RWStructuredBuffer<float4>"), so a tool can size a buffer for it.
struct EFFECT_TYPE_DESC {
  LPCSTR TypeName = nullptr;
  SHADER_VARIABLE_CLASS Class = SVC_OBJECT;
  UINT Elements = 0;  // 0 when not an array
  UINT Members = 0;
  UINT Rows = 0;
  UINT Columns = 0;
  UINT PackedSize = 0;  // bytes in the cbuffer (FX11 packing)
};

class EffectScalarVariable;
class EffectVectorVariable;
class EffectMatrixVariable;
class EffectStringVariable;
class EffectShaderResourceVariable;
class EffectUnorderedAccessViewVariable;
class EffectSamplerVariable;
class EffectBlendVariable;
class EffectDepthStencilVariable;
class EffectRasterizerVariable;
class EffectConstantBuffer;
class EffectShaderVariable;

// D3DX11_EFFECT_SHADER_DESC, less the signature entry counts: a shader of an
// effect as compiled. NULL shaders have no bytecode.
struct EFFECT_SHADER_DESC {
  const void* pInputSignature = nullptr;  // the SPIR-V, as PASS_DESC::pIAInputSignature
  BOOL IsInline = rhi::FALSE;                // written in the pass (CompileShader there), not a variable
  const void* pBytecode = nullptr;        // SPIR-V words
  UINT BytecodeLength = 0;                // bytes
  LPCSTR SODecls[rhi::SO_STREAM_COUNT] = {};  // ConstructGSWithSO's declarations as written, null when none
  UINT RasterizedStream = 0;
};

// D3DX11_PASS_SHADER_DESC: the shader variable a pass sets on a stage and the
// element of it. Inline and NULL shaders come as anonymous shader variables.
struct PASS_SHADER_DESC {
  EffectShaderVariable* pShaderVariable = nullptr;
  UINT ShaderIndex = 0;
};

// ID3DX11EffectVariable.
class EffectVariable {
 public:
  virtual BOOL IsValid() = 0;
  virtual HRESULT GetDesc(EFFECT_VARIABLE_DESC* pDesc) = 0;
  virtual HRESULT GetTypeDesc(EFFECT_TYPE_DESC* pDesc) = 0;  // FX11: GetType()->GetDesc()
  // Annotations are read-only variables: AsString()->GetString, AsScalar()->GetFloat, ...
  virtual EffectVariable* GetAnnotationByIndex(UINT Index) = 0;
  virtual EffectVariable* GetAnnotationByName(LPCSTR Name) = 0;
  virtual EffectVariable* GetMemberByIndex(UINT Index) = 0;
  virtual EffectVariable* GetMemberByName(LPCSTR Name) = 0;
  virtual EffectVariable* GetElement(UINT Index) = 0;
  virtual EffectConstantBuffer* GetParentConstantBuffer() = 0;

  virtual EffectScalarVariable* AsScalar() = 0;
  virtual EffectVectorVariable* AsVector() = 0;
  virtual EffectMatrixVariable* AsMatrix() = 0;
  virtual EffectStringVariable* AsString() = 0;
  virtual EffectShaderResourceVariable* AsShaderResource() = 0;
  virtual EffectUnorderedAccessViewVariable* AsUnorderedAccessView() = 0;
  virtual EffectSamplerVariable* AsSampler() = 0;
  virtual EffectBlendVariable* AsBlend() = 0;
  virtual EffectDepthStencilVariable* AsDepthStencil() = 0;
  virtual EffectRasterizerVariable* AsRasterizer() = 0;
  virtual EffectConstantBuffer* AsConstantBuffer() = 0;
  virtual EffectShaderVariable* AsShader() = 0;

  // Bytes in FX11's packed layout of the variable, from ByteOffset within it.
  virtual HRESULT SetRawValue(const void* pData, UINT ByteOffset, UINT ByteCount) = 0;
  virtual HRESULT GetRawValue(void* pData, UINT ByteOffset, UINT ByteCount) = 0;

 protected:
  ~EffectVariable() = default;
};

class EffectScalarVariable : public virtual EffectVariable {
 public:
  virtual HRESULT SetFloat(float Value) = 0;
  virtual HRESULT GetFloat(float* pValue) = 0;
  virtual HRESULT SetFloatArray(const float* pData, UINT Offset, UINT Count) = 0;
  virtual HRESULT GetFloatArray(float* pData, UINT Offset, UINT Count) = 0;
  virtual HRESULT SetInt(int Value) = 0;
  virtual HRESULT GetInt(int* pValue) = 0;
  virtual HRESULT SetIntArray(const int* pData, UINT Offset, UINT Count) = 0;
  virtual HRESULT GetIntArray(int* pData, UINT Offset, UINT Count) = 0;
  virtual HRESULT SetBool(bool Value) = 0;
  virtual HRESULT GetBool(bool* pValue) = 0;

 protected:
  ~EffectScalarVariable() = default;
};

class EffectVectorVariable : public virtual EffectVariable {
 public:
  virtual HRESULT SetFloatVector(const float* pData) = 0;
  virtual HRESULT GetFloatVector(float* pData) = 0;
  virtual HRESULT SetIntVector(const int* pData) = 0;
  virtual HRESULT GetIntVector(int* pData) = 0;
  virtual HRESULT SetBoolVector(const bool* pData) = 0;
  virtual HRESULT SetFloatVectorArray(const float* pData, UINT Offset, UINT Count) = 0;
  virtual HRESULT GetFloatVectorArray(float* pData, UINT Offset, UINT Count) = 0;
  virtual HRESULT SetIntVectorArray(const int* pData, UINT Offset, UINT Count) = 0;

 protected:
  ~EffectVectorVariable() = default;
};

// Matrices cross this interface as D3DX passes them: 16 floats, row-major
// (m[row * 4 + column]; a smaller matrix uses the top-left corner). The
// runtime stores them as the variable is packed (column_major by default).
class EffectMatrixVariable : public virtual EffectVariable {
 public:
  virtual HRESULT SetMatrix(const float* pData) = 0;
  virtual HRESULT GetMatrix(float* pData) = 0;
  virtual HRESULT SetMatrixArray(const float* pData, UINT Offset, UINT Count) = 0;
  virtual HRESULT GetMatrixArray(float* pData, UINT Offset, UINT Count) = 0;
  virtual HRESULT SetMatrixTranspose(const float* pData) = 0;
  virtual HRESULT GetMatrixTranspose(float* pData) = 0;

 protected:
  ~EffectMatrixVariable() = default;
};

class EffectStringVariable : public virtual EffectVariable {
 public:
  virtual HRESULT GetString(LPCSTR* ppString) = 0;

 protected:
  ~EffectStringVariable() = default;
};

class EffectShaderResourceVariable : public virtual EffectVariable {
 public:
  virtual HRESULT SetResource(rhi::ShaderResourceView* pResource) = 0;
  virtual HRESULT GetResource(rhi::ShaderResourceView** ppResource) = 0;
  virtual HRESULT SetResourceArray(rhi::ShaderResourceView* const* ppResources, UINT Offset, UINT Count) = 0;

 protected:
  ~EffectShaderResourceVariable() = default;
};

class EffectUnorderedAccessViewVariable : public virtual EffectVariable {
 public:
  virtual HRESULT SetUnorderedAccessView(rhi::UnorderedAccessView* pResource) = 0;
  virtual HRESULT GetUnorderedAccessView(rhi::UnorderedAccessView** ppResource) = 0;

 protected:
  ~EffectUnorderedAccessViewVariable() = default;
};

class EffectSamplerVariable : public virtual EffectVariable {
 public:
  virtual HRESULT GetSampler(UINT Index, rhi::SamplerState** ppSampler) = 0;
  virtual HRESULT SetSampler(UINT Index, rhi::SamplerState* pSampler) = 0;  // null restores the effect's
  virtual HRESULT GetBackingStore(UINT Index, rhi::SAMPLER_DESC* pDesc) = 0;

 protected:
  ~EffectSamplerVariable() = default;
};

class EffectBlendVariable : public virtual EffectVariable {
 public:
  virtual HRESULT GetBlendState(UINT Index, rhi::BlendState** ppState) = 0;
  virtual HRESULT SetBlendState(UINT Index, rhi::BlendState* pState) = 0;
  virtual HRESULT UndoSetBlendState(UINT Index) = 0;
  virtual HRESULT GetBackingStore(UINT Index, rhi::BLEND_DESC* pDesc) = 0;

 protected:
  ~EffectBlendVariable() = default;
};

class EffectDepthStencilVariable : public virtual EffectVariable {
 public:
  virtual HRESULT GetDepthStencilState(UINT Index, rhi::DepthStencilState** ppState) = 0;
  virtual HRESULT SetDepthStencilState(UINT Index, rhi::DepthStencilState* pState) = 0;
  virtual HRESULT UndoSetDepthStencilState(UINT Index) = 0;
  virtual HRESULT GetBackingStore(UINT Index, rhi::DEPTH_STENCIL_DESC* pDesc) = 0;

 protected:
  ~EffectDepthStencilVariable() = default;
};

class EffectRasterizerVariable : public virtual EffectVariable {
 public:
  virtual HRESULT GetRasterizerState(UINT Index, rhi::RasterizerState** ppState) = 0;
  virtual HRESULT SetRasterizerState(UINT Index, rhi::RasterizerState* pState) = 0;
  virtual HRESULT UndoSetRasterizerState(UINT Index) = 0;
  virtual HRESULT GetBackingStore(UINT Index, rhi::RASTERIZER_DESC* pDesc) = 0;

 protected:
  ~EffectRasterizerVariable() = default;
};

class EffectConstantBuffer : public virtual EffectVariable {
 public:
  // Binds the caller's buffer instead of the effect's (null: the effect's again).
  virtual HRESULT SetConstantBuffer(rhi::Buffer* pConstantBuffer) = 0;
  virtual HRESULT UndoSetConstantBuffer() = 0;
  virtual HRESULT GetConstantBuffer(rhi::Buffer** ppConstantBuffer) = 0;

 protected:
  ~EffectConstantBuffer() = default;
};

class EffectShaderVariable : public virtual EffectVariable {
 public:
  virtual HRESULT GetVertexShader(UINT Index, rhi::VertexShader** ppShader) = 0;
  virtual HRESULT GetGeometryShader(UINT Index, rhi::GeometryShader** ppShader) = 0;
  virtual HRESULT GetPixelShader(UINT Index, rhi::PixelShader** ppShader) = 0;
  virtual HRESULT GetComputeShader(UINT Index, rhi::ComputeShader** ppShader) = 0;
  virtual HRESULT GetShaderDesc(UINT ShaderIndex, EFFECT_SHADER_DESC* pDesc) = 0;

 protected:
  ~EffectShaderVariable() = default;
};

// ID3DX11EffectPass.
class EffectPass {
 public:
  virtual BOOL IsValid() = 0;
  virtual HRESULT GetDesc(PASS_DESC* pDesc) = 0;
  // What the pass sets on each stage (a stage it leaves alone reads as NULL).
  virtual HRESULT GetVertexShaderDesc(PASS_SHADER_DESC* pDesc) = 0;
  virtual HRESULT GetGeometryShaderDesc(PASS_SHADER_DESC* pDesc) = 0;
  virtual HRESULT GetPixelShaderDesc(PASS_SHADER_DESC* pDesc) = 0;
  virtual HRESULT GetHullShaderDesc(PASS_SHADER_DESC* pDesc) = 0;
  virtual HRESULT GetDomainShaderDesc(PASS_SHADER_DESC* pDesc) = 0;
  virtual HRESULT GetComputeShaderDesc(PASS_SHADER_DESC* pDesc) = 0;
  virtual EffectVariable* GetAnnotationByIndex(UINT Index) = 0;
  virtual EffectVariable* GetAnnotationByName(LPCSTR Name) = 0;
  // Sets what the pass assigns (shaders, NULL included; blend, depth-stencil and
  // rasterizer states with factor, mask and ref), uploads changed constant
  // buffers and binds, for each stage it sets a shader on, the cbuffers, SRVs,
  // samplers and UAVs the shader uses (a pixel shader's UAVs through
  // OMSetRenderTargetsAndUnorderedAccessViews with KEEP_RENDER_TARGETS_AND_DEPTH_STENCIL,
  // from its lowest UAV register on, hidden counters kept). What it does not assign
  // stays as it was. Flags must be 0. It first calls
  // pContext->SetMarker("technique/pass") (ID3DUserDefinedAnnotation), which a
  // tracing context (rhi/trace.h) records and the Vulkan context turns into a
  // debug-utils label when the validation layer is on.
  virtual HRESULT Apply(UINT Flags, rhi::DeviceContext* pContext) = 0;

 protected:
  ~EffectPass() = default;
};

// ID3DX11EffectTechnique.
class EffectTechnique {
 public:
  virtual BOOL IsValid() = 0;
  virtual HRESULT GetDesc(TECHNIQUE_DESC* pDesc) = 0;
  virtual EffectVariable* GetAnnotationByIndex(UINT Index) = 0;
  virtual EffectVariable* GetAnnotationByName(LPCSTR Name) = 0;
  virtual EffectPass* GetPassByIndex(UINT Index) = 0;
  virtual EffectPass* GetPassByName(LPCSTR Name) = 0;

 protected:
  ~EffectTechnique() = default;
};

// ID3DX11Effect. Release it before the device (RHI device children rule).
class Effect : public rhi::Unknown {
 public:
  virtual BOOL IsValid() = 0;
  virtual HRESULT GetDevice(rhi::Device** ppDevice) = 0;
  virtual HRESULT GetDesc(EFFECT_DESC* pDesc) = 0;
  virtual EffectConstantBuffer* GetConstantBufferByIndex(UINT Index) = 0;
  virtual EffectConstantBuffer* GetConstantBufferByName(LPCSTR Name) = 0;
  virtual EffectVariable* GetVariableByIndex(UINT Index) = 0;
  virtual EffectVariable* GetVariableByName(LPCSTR Name) = 0;
  virtual EffectVariable* GetVariableBySemantic(LPCSTR Semantic) = 0;  // case-insensitive, as FX11
  virtual EffectTechnique* GetTechniqueByIndex(UINT Index) = 0;
  virtual EffectTechnique* GetTechniqueByName(LPCSTR Name) = 0;
};

// D3DX11CreateEffectFromFile / D3DX11CreateEffectFromMemory. On failure *ppEffect
// is null and options.Errors (when set) holds the errors. The file name may be UTF-8
// (char), wide (wchar_t, as D3D11 programs pass it; converted to UTF-8 whatever the
// locale) or a std::filesystem::path.
HRESULT CreateEffectFromFile(const char* pFileName, const EFFECT_OPTIONS& options, rhi::Device* pDevice,
                             Effect** ppEffect);
HRESULT CreateEffectFromFile(const wchar_t* pFileName, const EFFECT_OPTIONS& options, rhi::Device* pDevice,
                             Effect** ppEffect);
HRESULT CreateEffectFromFile(const std::filesystem::path& fileName, const EFFECT_OPTIONS& options,
                             rhi::Device* pDevice, Effect** ppEffect);
HRESULT CreateEffectFromMemory(const void* pData, SIZE_T DataLength, const char* pVirtualFileName,
                               const EFFECT_OPTIONS& options, rhi::Device* pDevice, Effect** ppEffect);

// FX11's effect flags (D3DCOMPILE_EFFECT_*), the FXFlags of D3DX11CreateEffectFromMemory.
inline constexpr UINT COMPILE_EFFECT_CHILD_EFFECT = 1u << 0;    // effect pools: E_NOTIMPL, as FX11
inline constexpr UINT COMPILE_EFFECT_ALLOW_SLOW_OPS = 1u << 1;  // accepted; nothing is slow here

// D3DX11CreateEffectFromMemory(pData, DataLength, FXFlags, pDevice, ppEffect, srcName) in
// the form a port needs, so that a call ports with a rename: pData is the effect's source
// text (what the program read from its .fx file; there is no fxc bytecode), pSourceName
// names it in messages ("particles.fx:12:5: error: ...") and anchors relative #includes
// (may be null: "<memory>"), includeFolder is searched for #include after that (may be
// empty). FXFlags: COMPILE_EFFECT_* (child effects give E_NOTIMPL, unknown bits
// E_INVALIDARG). Errors, one "file:line:column: error: message" a line, go to *pErrors
// when given, else to stderr (where D3D11's debug output would show them). The SPIR-V
// cache is the default one (EFFECT_OPTIONS::CacheDirectory).
HRESULT CreateEffectFromMemory(const void* pData, SIZE_T DataLength, const char* pSourceName,
                               const std::filesystem::path& includeFolder, UINT FXFlags, rhi::Device* pDevice,
                               Effect** ppEffect, std::string* pErrors = nullptr);

}  // namespace fx
