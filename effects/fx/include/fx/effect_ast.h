// What the effect front end extracts from an fx_5_0 effect: plain HLSL for
// the shader compiler, plus everything the effect runtime builds on (constant
// buffers with default values, resources, samplers and state objects with
// filled D3D11 descs, shaders, techniques and passes).
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "fx/diagnostics.h"
#include "fx/so_decl.h"
#include "rhi/d3d11_types.h"

namespace fx {

// `: register(b3)` -> {'b', 3}; `register(t1, space2)` -> {'t', 1, 2}.
struct Register {
  char kind = 0;
  uint32_t index = 0;
  uint32_t space = 0;
};

// ---------------------------------------------------------------------------
// Numeric variables and constant buffers

enum class ScalarType { Bool, Int, UInt, Float, Double };  // half and min16* pack as 32-bit like fxc

struct StructMember;

// The type of a variable that lives in a constant buffer, with its packed size
// under fxc's cbuffer rules: 16-byte registers; arrays and structs start on a
// new register; anything else (scalar, vector, matrix) moves to the next
// register only if it would straddle one; array elements are 16-byte aligned;
// a matrix takes one register per column (row with row_major); nothing pads
// the end of an array or struct (the next variable may use the rest of its
// last register).
struct VariableType {
  enum class Class { Scalar, Vector, Matrix, Struct };
  Class cls = Class::Scalar;
  ScalarType scalar = ScalarType::Float;
  uint32_t rows = 1;     // matrices
  uint32_t columns = 1;  // vector components, matrix columns
  bool rowMajor = false;  // matrices: row_major keyword or #pragma pack_matrix(row_major)
  std::string name;       // "float4", "float3x3", a struct's name (typedefs resolved)
  std::vector<uint32_t> arrayDims;    // float a[2][3] -> {2, 3}; empty when not an array
  std::vector<StructMember> members;  // Struct only
  uint32_t elementSize = 0;  // bytes of one element
  uint32_t size = 0;         // bytes of the whole variable (array stride is elementSize rounded up to 16)

  uint32_t ElementCount() const {
    uint32_t n = 1;
    for (uint32_t d : arrayDims) n *= d;
    return n;
  }
};

struct StructMember {
  std::string name;
  VariableType type;
  uint32_t offset = 0;  // from the start of the struct
};

// `< string UIName = "Color"; float UIMin = 0; >` on a variable, technique or pass.
struct Annotation {
  std::string type;         // as written: "string", "float", "float4", "int", "bool", ...
  std::string name;
  std::string stringValue;  // string annotations
  std::vector<double> values;  // numeric annotations, flattened (bools are 0 / 1)
  // Numeric annotations: the type resolved and laid out as a cbuffer variable
  // at offset 0, and its bytes in FX11's packing (what GetFloat & co. read).
  VariableType valueType;
  std::vector<uint8_t> bytes;
  SourceLocation where;
};

struct ConstantVariable {
  std::string name;
  VariableType type;
  uint32_t offset = 0;          // bytes from the start of its buffer
  bool hasInitializer = false;  // its bytes in ConstantBuffer::defaults come from the source
  std::string semantic;         // `float4x4 World : WORLD;` -> "WORLD"
  std::vector<Annotation> annotations;
  SourceLocation where;
};

struct ConstantBuffer {
  std::string name;  // "$Globals" holds the numeric variables declared outside any cbuffer
  bool isTBuffer = false;
  bool shared = false;
  std::optional<Register> reg;
  uint32_t size = 0;              // bytes, a multiple of 16
  std::vector<uint8_t> defaults;  // `size` bytes: initializer values, zero elsewhere (bool true is 0xFFFFFFFF, as FX11 stores it)
  std::vector<ConstantVariable> variables;
  SourceLocation where;
};

// ---------------------------------------------------------------------------
// Resources, samplers, state objects, strings

enum class ResourceKind {
  Texture,  // FX10's untyped `texture`
  Texture1D,
  Texture1DArray,
  Texture2D,
  Texture2DArray,
  Texture2DMS,
  Texture2DMSArray,
  Texture3D,
  TextureCube,
  TextureCubeArray,
  Buffer,
  ByteAddressBuffer,
  StructuredBuffer,
  RWTexture1D,
  RWTexture1DArray,
  RWTexture2D,
  RWTexture2DArray,
  RWTexture3D,
  RWBuffer,
  RWByteAddressBuffer,
  RWStructuredBuffer,
  AppendStructuredBuffer,
  ConsumeStructuredBuffer,
};

bool IsUnorderedAccess(ResourceKind kind);  // RW*, Append*, Consume*

struct ResourceVariable {
  std::string name;
  ResourceKind kind = ResourceKind::Texture2D;
  std::string templateArgs;  // "float4", "float4, 8", "Particle"; empty when none
  std::vector<uint32_t> arrayDims;
  std::optional<Register> reg;
  bool shared = false;
  std::vector<Annotation> annotations;
  SourceLocation where;
};

struct SamplerVariable {
  std::string name;
  bool comparison = false;                // SamplerComparisonState
  std::vector<rhi::SAMPLER_DESC> descs;   // one per element (one when not an array), from FX11's defaults
  std::vector<std::string> textures;      // FX10 `Texture = <t>;` per element, "" when absent
  std::vector<uint32_t> arrayDims;
  std::optional<Register> reg;
  bool shared = false;
  std::vector<Annotation> annotations;
  SourceLocation where;
};

template <class Desc>
struct StateObjectVariable {
  std::string name;
  std::vector<Desc> descs;  // one per element (one when not an array), from FX11's defaults
  std::vector<uint32_t> arrayDims;
  bool shared = false;
  std::vector<Annotation> annotations;
  SourceLocation where;
};
using BlendStateVariable = StateObjectVariable<rhi::BLEND_DESC>;
using DepthStencilStateVariable = StateObjectVariable<rhi::DEPTH_STENCIL_DESC>;
using RasterizerStateVariable = StateObjectVariable<rhi::RASTERIZER_DESC>;

struct StringVariable {
  std::string name;
  std::vector<std::string> values;  // one per element
  std::vector<Annotation> annotations;
  SourceLocation where;
};

// ---------------------------------------------------------------------------
// Shaders

enum class ShaderStage { Vertex, Hull, Domain, Geometry, Pixel, Compute };

// One CompileShader(profile, Function(args)), possibly inside ConstructGSWithSO;
// from a shader variable or written inline in a pass.
struct CompiledShader {
  ShaderStage stage = ShaderStage::Vertex;  // from the profile
  std::string profile;                      // "vs_5_0"
  std::string function;                     // the function named in the source
  // The arguments that bind the function's `uniform` parameters, in order, as
  // written (macro-expanded); parameter defaults fill in missing ones.
  std::vector<std::string> uniformArgs;
  // The entry point to compile `EffectAst::hlsl` with: `function` itself, or,
  // when it has uniform parameters, a generated `fx_variant_N` that takes the
  // other parameters (same semantics and attributes) and calls `function`
  // with the bound values. Equal argument lists share one variant.
  std::string entryPoint;

  bool hasStreamOutput = false;  // ConstructGSWithSO
  std::array<std::string, rhi::SO_STREAM_COUNT> soDeclarations;  // the strings as written
  StreamOutputDecl streamOutput;
  rhi::UINT rasterizedStream = 0;

  SourceLocation where;
};

struct ShaderVariable {
  std::string name;
  ShaderStage stage = ShaderStage::Vertex;  // the declared type (VertexShader, GeometryShader, ...)
  std::vector<int> shaders;  // per element: index into EffectAst::shaders, -1 for NULL
  std::vector<uint32_t> arrayDims;
  std::vector<Annotation> annotations;
  SourceLocation where;
};

// ---------------------------------------------------------------------------
// Techniques

// A state object named in a pass; `variable` is empty for NULL.
struct ObjectRef {
  std::string variable;
  uint32_t element = 0;
};

// SetVertexShader(...) ... SetComputeShader(...).
struct ShaderAssignment {
  ShaderStage stage = ShaderStage::Vertex;
  int shader = -1;       // index into EffectAst::shaders; -1 for NULL
  std::string variable;  // the shader variable named, empty when inline or NULL
  uint32_t element = 0;
};

// SetBlendState(state, blendFactor, sampleMask).
struct BlendStateAssignment {
  ObjectRef state;
  std::array<float, 4> blendFactor{};
  uint32_t sampleMask = rhi::DEFAULT_SAMPLE_MASK;
};

// SetDepthStencilState(state, stencilRef).
struct DepthStencilStateAssignment {
  ObjectRef state;
  uint32_t stencilRef = 0;
};

// SetRasterizerState(state).
struct RasterizerStateAssignment {
  ObjectRef state;
};

struct PassAssignment {
  std::variant<ShaderAssignment, BlendStateAssignment, DepthStencilStateAssignment, RasterizerStateAssignment> value;
  SourceLocation where;
};

struct Pass {
  std::string name;
  std::vector<Annotation> annotations;
  std::vector<PassAssignment> assignments;  // in source order
  SourceLocation where;
};

struct Technique {
  std::string name;
  std::string group;  // the enclosing fxgroup, empty when none
  int version = 11;   // 10 for technique10, 11 for technique11 and plain `technique`
  std::vector<Annotation> annotations;
  std::vector<Pass> passes;
  SourceLocation where;
};

// ---------------------------------------------------------------------------

struct EffectAst {
  // Plain HLSL for glslang: the preprocessed text with every effect-only
  // construct blanked out (techniques, state objects, shader variables,
  // strings, annotations, initializers of constant-buffer variables, `shared`,
  // semantics of global variables, sampler state blocks). Each kept token stays
  // at its preprocessed line and column, the #line directives stay, and the
  // generated fx_variant_N entry points follow at the end.
  std::string hlsl;

  std::vector<ConstantBuffer> cbuffers;  // "$Globals" first when present, then in source order
  std::vector<ResourceVariable> resources;
  std::vector<SamplerVariable> samplers;
  std::vector<BlendStateVariable> blendStates;
  std::vector<DepthStencilStateVariable> depthStencilStates;
  std::vector<RasterizerStateVariable> rasterizerStates;
  std::vector<StringVariable> strings;
  std::vector<CompiledShader> shaders;  // every CompileShader, from variables and inline
  std::vector<ShaderVariable> shaderVariables;
  std::vector<Technique> techniques;  // in source order, fxgroups included
};

// The element of `items` called `name`, or nullptr.
template <class T>
const T* FindByName(const std::vector<T>& items, std::string_view name) {
  auto it = std::find_if(items.begin(), items.end(), [&](const T& item) { return item.name == name; });
  return it == items.end() ? nullptr : &*it;
}

}  // namespace fx
