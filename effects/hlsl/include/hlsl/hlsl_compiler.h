// HLSL (Shader Model 4/5) -> SPIR-V compiler on the linked glslang C++ API.
// By default each compile runs in a forked worker process of the caller (see
// CompileRequest::isolate), because glslang 12 crashes on some malformed HLSL.
//
// What the output looks like, so the Vulkan backend can rely on it:
//  * SPIR-V 1.5 for a Vulkan 1.3 client, legalized with the SPIRV-Tools HLSL
//    legalization recipe and checked with the SPIRV-Tools validator.
//  * The SPIR-V entry point is always named "main" (the HLSL function named by
//    CompileRequest::entryPoint is renamed), so pName is always "main".
//  * Every entry-point input/output variable carries its HLSL semantic as
//    `OpDecorateString %var UserSemantic "TEXCOORD0"` (SPV_GOOGLE_hlsl_functionality1).
//    glslang upper-cases it and keeps the index: "TexCoord1" -> "TEXCOORD1",
//    SV_Target1 -> "SV_TARGET1". Struct inputs/outputs become one variable
//    per member. Inputs the shader never reads may be left out. Locations are
//    auto-assigned per direction in declaration order: link stages and match
//    input layouts by semantic, not by Location.
//  * Every resource is in descriptor set 0 at
//    rhi::BindingFor(stage, register class, register slot); resources without a
//    register() get the lowest free slot of their class.
//  * Constant buffers use glslang's HLSL packing; reflected member offsets are
//    read back from the SPIR-V Offset decorations, so they are exactly what
//    the shader reads. They match fxc except: nothing packs into the padding
//    after an array or matrix (SPIR-V gives those whole 16-byte strides; fxc
//    puts `float a[2]; float b;` b at 20, here 32), and in "$Global" glslang
//    aligns vectors GLSL-style (`float a; float2 b;` b at 8; fxc: 4).
//  * glslang calls the buffer of globals declared outside any cbuffer
//    "$Global" (its SPIR-V OpName); reflection reports it as "$Globals", the
//    D3D name.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace hlsl {

// Same order and values as rhi::ShaderStage.
enum class Stage { Vertex, Hull, Domain, Geometry, Pixel, Compute };

// "#define name value"; an empty value defines the name as 1 (like fxc's /D NAME).
struct Define {
  std::string name, value;
};

struct CompileRequest {
  std::string source;    // HLSL text
  std::string fileName;  // used in diagnostics ("<memory>" when empty) and to resolve #include relative to it
  std::string entryPoint;
  std::string profile;  // "vs_5_0", "ps_4_0", "gs_4_1", "hs_5_0", "ds_5_0", "cs_5_0"
  std::vector<Define> defines;
  std::vector<std::string> includeDirs;  // searched after the including file's folder
  // Compile in a worker process so that a crash or hang inside glslang or
  // SPIRV-Tools becomes an error instead of killing the caller: glslang 12
  // segfaults on some malformed HLSL (e.g. an unnamed struct parameter of the
  // entry point). Each calling thread gets its own worker, forked on its first
  // compile and replaced after a crash; it costs the fork once and then well
  // under a millisecond per compile. Set false to compile in this process.
  // Ignored (always in-process) in sanitizer builds; see CrashIsolationAvailable().
  bool isolate = true;
};

// 1-based line and column. glslang 12 does not print columns, so the column is
// recovered by finding the message's quoted token ('foo' : ...) on the reported
// source line (the n-th error for the same token on a line gets its n-th
// occurrence); it is 0 when that is not possible. line is 0 for errors with no
// source position (link errors, validator failures).
struct Diagnostic {
  std::string file;
  int line = 0;
  int column = 0;
  std::string message;
  bool operator==(const Diagnostic&) const = default;
};

enum class BaseType { Float, Int, Uint, Bool, Double, Half, Struct, Other };

struct ConstantBufferMember {
  std::string name;  // nested struct fields are flattened: "light.color", "arr[0].x"
  uint32_t offset = 0;
  uint32_t size = 0;  // bytes under HLSL packing (arrays: all elements; last one unpadded)
  BaseType baseType = BaseType::Float;
  uint32_t rows = 1;           // HLSL rows: float4x3 -> 4, float3 -> 1
  uint32_t columns = 1;        // HLSL columns: float4x3 -> 3, float3 -> 3
  uint32_t arrayElements = 0;  // 0 when not an array
  bool operator==(const ConstantBufferMember&) const = default;
};

struct ConstantBufferInfo {
  std::string name;  // cbuffer name; "$Globals" for globals outside any cbuffer
  uint32_t binding = 0;
  uint32_t registerSlot = 0;  // the b# register
  uint32_t size = 0;          // bytes, rounded up to 16 as D3D reports it
  std::vector<ConstantBufferMember> members;
  bool operator==(const ConstantBufferInfo&) const = default;
};

struct ResourceInfo {
  // tbuffer reports as StructuredBuffer (glslang makes it a read-only storage
  // buffer). glslang 12 does not record which storage buffers were declared
  // (RW)ByteAddressBuffer, so those are recognized by their declaration in the
  // source text.
  enum class Kind {
    Texture,
    Sampler,
    Buffer,
    StructuredBuffer,
    ByteAddressBuffer,
    RWTexture,
    RWBuffer,
    RWStructuredBuffer,
    RWByteAddressBuffer
  };
  enum class Dimension {
    Unknown,
    Buffer,
    Tex1D,
    Tex1DArray,
    Tex2D,
    Tex2DArray,
    Tex2DMS,
    Tex2DMSArray,
    Tex3D,
    TexCube,
    TexCubeArray
  };

  std::string name;
  uint32_t binding = 0;
  uint32_t registerSlot = 0;  // the t#/s#/u# register
  Kind kind = Kind::Texture;
  Dimension dimension = Dimension::Unknown;
  uint32_t bindCount = 1;          // array size (one Vulkan binding with this descriptor count)
  bool comparisonSampler = false;  // SamplerComparisonState
  // glslang gives a RWStructuredBuffer that uses IncrementCounter/Append/Consume
  // a separate counter buffer named "<name>@count" (a RWStructuredBuffer<uint>
  // with the lowest free u# slot); it is reported with isCounter = true.
  bool isCounter = false;
  bool operator==(const ResourceInfo&) const = default;
};

struct CompileResult {
  bool ok = false;
  std::vector<uint32_t> spirv;
  Stage stage = Stage::Vertex;
  std::vector<Diagnostic> errors;    // parse/semantic/link/validator errors
  std::vector<Diagnostic> warnings;  // glslang warnings, same format
  std::vector<ConstantBufferInfo> constantBuffers;
  std::vector<ResourceInfo> resources;
  std::string FormatErrors() const;  // "file:line:column: error: message" lines
  bool operator==(const CompileResult&) const = default;
};

// Thread-safe; compiles may run concurrently. Never throws, never prints.
// Diagnostics without a position (link errors, validator failures, crashes)
// have line 0 and print as "file: error: message".
CompileResult CompileHlsl(const CompileRequest& request);

// CompileHlsl of the file at `path` (also the diagnostics' file name); a file
// that cannot be read is an error "path: error: cannot read the file".
CompileResult CompileHlslFile(const std::string& path, const std::string& entryPoint, const std::string& profile,
                              const std::vector<std::string>& includeDirs = {});

// Whether CompileRequest::isolate takes effect: false in ASan/TSan/MSan builds,
// whose allocators deadlock in a child forked from a multithreaded process.
bool CrashIsolationAvailable();

// Stage of a "xs_M_m" profile (4_0, 4_1, 5_0; hs/ds need 5_0). For an unknown
// profile it returns Stage::Vertex and sets *valid to false; CompileHlsl reports
// an unknown profile as an error.
Stage StageFromProfile(std::string_view profile, bool* valid = nullptr);

}  // namespace hlsl
