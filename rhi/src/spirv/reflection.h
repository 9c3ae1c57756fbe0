// Reflection of a SPIR-V module as the D3D11 layer needs it: stage, entry
// point, the entry point's inputs/outputs by D3D semantic, descriptor
// bindings, geometry-shader and compute-shader execution modes, and whether
// Position / PointSize outputs exist and are written.
//
// Semantics come from SPV_GOOGLE_hlsl_functionality1 `UserSemantic`
// decorations (glslang with setEnvTargetHlslFunctionality1()); built-ins
// without one get their D3D name (Position -> "SV_POSITION", ...), so modules
// compiled from GLSL reflect too. Only the first OpEntryPoint is reflected.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "spirv/result.h"

namespace rhi::spirv {

enum class Stage { Vertex, Hull, Domain, Geometry, Pixel, Compute, Unknown };
const char* StageName(Stage stage);  // "VS", "HS", ...

enum class ScalarKind { Float, SInt, UInt, Bool, Unknown };

// One entry-point input or output. Members of an IO block (gl_PerVertex, as
// glslang emits for GLSL) are listed one per member, with `member` set.
//
// Shape: a scalar has componentCount 1, a vector N. A matrix has
// componentCount = its column size and locationCount = its column count.
// Arrays: for arrayed IO (GS inputs, HS inputs/outputs, DS inputs, not
// Patch) the outermost array is the per-vertex one: arraySize is the vertex
// count and perVertexArray is true; any other array is reported in arraySize
// when it is outermost and multiplies locationCount. A D3D semantic covers
// locationCount consecutive indices (float4x4 M : TEXCOORD0 = TEXCOORD0..3).
struct InterfaceVariable {
  uint32_t variableId = 0;
  std::optional<uint32_t> member;  // index in the IO block, when the variable is a block
  std::string semanticName;        // upper-cased, trailing digits removed ("TEXCOORD"); "" if unknown
  uint32_t semanticIndex = 0;      // trailing digits of the semantic, 0 when absent
  std::optional<uint32_t> location;
  std::optional<uint32_t> component;
  std::optional<uint32_t> builtIn;  // a spv::BuiltIn value
  uint32_t stream = 0;              // Stream decoration (GS outputs), 0 when absent
  bool patch = false;
  ScalarKind scalarKind = ScalarKind::Unknown;
  uint32_t scalarWidth = 0;  // bits
  uint32_t componentCount = 0;
  uint32_t locationCount = 1;
  uint32_t arraySize = 0;  // 0: not an array
  bool perVertexArray = false;

  std::string Semantic() const { return semanticName + std::to_string(semanticIndex); }  // "TEXCOORD0"
};

enum class DescriptorKind {
  UniformBuffer,
  StorageBuffer,
  SampledImage,
  StorageImage,
  Sampler,
  CombinedImageSampler,
  UniformTexelBuffer,
  StorageTexelBuffer,
  InputAttachment,
  AccelerationStructure,
  Unknown,
};
const char* DescriptorKindName(DescriptorKind kind);

struct DescriptorBinding {
  uint32_t variableId = 0;
  uint32_t set = 0;
  uint32_t binding = 0;
  DescriptorKind kind = DescriptorKind::Unknown;
  uint32_t arrayCount = 1;  // 0: runtime-sized array
  std::string name;         // the variable's OpName, else its type's (glslang names cbuffer blocks by type)
  bool nonWritable = false; // storage buffer/image the shader cannot write (StructuredBuffer, SRV buffers)
  // A hidden counter (glslang's "name@count" buffer of an Append/Consume or
  // counter UAV): the variable id of the UAV it counts for, 0 otherwise.
  uint32_t counterOf = 0;
};

enum class GsInputPrimitive { None, Points, Lines, LinesAdjacency, Triangles, TrianglesAdjacency };
enum class GsOutputPrimitive { None, Points, LineStrip, TriangleStrip };

struct Reflection {
  Stage stage = Stage::Unknown;
  std::string entryPoint;
  uint32_t entryFunctionId = 0;
  uint32_t spirvVersion = 0;  // header word, 0x00MMmm00

  std::vector<InterfaceVariable> inputs;
  std::vector<InterfaceVariable> outputs;
  std::vector<DescriptorBinding> bindings;  // in declaration order

  // Geometry shaders.
  GsInputPrimitive gsInput = GsInputPrimitive::None;
  GsOutputPrimitive gsOutput = GsOutputPrimitive::None;
  uint32_t gsMaxVertices = 0;  // OutputVertices
  uint32_t gsInvocations = 0;  // Invocations (glslang always emits it; 1 = not instanced)

  // Compute shaders: LocalSize (or LocalSizeId with constant operands).
  std::array<uint32_t, 3> localSize = {0, 0, 0};

  bool hasPositionOutput = false;
  bool writesPosition = false;      // some OpStore/OpCopyMemory targets the Position output
  bool hasPointSizeOutput = false;
  bool writesPointSize = false;

  // Case-insensitive look-up by D3D semantic; an output with locationCount n
  // answers indices semanticIndex .. semanticIndex + n - 1. With a stream,
  // outputs of that stream are preferred.
  const InterfaceVariable* FindInput(std::string_view semanticName, uint32_t semanticIndex) const;
  const InterfaceVariable* FindOutput(std::string_view semanticName, uint32_t semanticIndex,
                                      std::optional<uint32_t> stream = std::nullopt) const;
};

Result<Reflection> Reflect(std::span<const uint32_t> words);

// "TEXCOORD12" -> {"TEXCOORD", 12}; "POSITION" -> {"POSITION", 0}. Upper-cases.
struct SplitSemanticResult {
  std::string name;
  uint32_t index = 0;
};
SplitSemanticResult SplitSemantic(std::string_view semantic);
// D3D semantic name of a SPIR-V built-in in a stage ("SV_POSITION"), "" if none.
std::string BuiltInSemantic(uint32_t builtIn, Stage stage);
bool SemanticEquals(std::string_view a, std::string_view b);  // ASCII case-insensitive

}  // namespace rhi::spirv
