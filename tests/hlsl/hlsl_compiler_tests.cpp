// Tests for the HLSL -> SPIR-V compiler: profiles, D3D register mapping,
// semantics, diagnostics, #include/#define, cbuffer reflection, legalization.
#include <gtest/gtest.h>

#include <rhi/shader_bindings.h>
#include <unistd.h>
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <spirv-tools/libspirv.hpp>
#include <string>
#include <thread>
#include <vector>

#include "hlsl/hlsl_compiler.h"

namespace {

namespace fs = std::filesystem;
using hlsl::CompileHlsl;
using hlsl::CompileRequest;
using hlsl::CompileResult;
using hlsl::Stage;
using rhi::RegisterClass;
using rhi::ShaderStage;

// ---------------------------------------------------------------------------
// A tiny SPIR-V reader: just the instructions these tests look at.

constexpr uint32_t kOpName = 5, kOpMemberName = 6, kOpMemberDecorate = 72, kOpEntryPoint = 15, kOpExecutionMode = 16,
                   kOpTypePointer = 32, kOpVariable = 59, kOpDecorate = 71, kOpDecorateString = 5632;
constexpr uint32_t kDecorationOffset = 35, kDecorationBinding = 33, kDecorationDescriptorSet = 34,
                   kDecorationUserSemantic = 5635;
constexpr uint32_t kStorageInput = 1, kStorageOutput = 3;

std::string ReadString(const uint32_t* words, size_t count) {
  std::string s;
  for (size_t i = 0; i < count; ++i) {
    for (int b = 0; b < 4; ++b) {
      const char c = static_cast<char>((words[i] >> (8 * b)) & 0xff);
      if (c == 0) return s;
      s += c;
    }
  }
  return s;
}

struct Module {
  std::map<uint32_t, std::string> names;
  std::map<uint32_t, uint32_t> binding, set, storage, varPointer, pointee;
  std::map<uint32_t, std::string> semantic;
  std::vector<std::pair<uint32_t, std::string>> entryPoints;  // execution model, name
  std::vector<std::vector<uint32_t>> executionModes;          // mode, operands...
  std::map<uint32_t, std::map<uint32_t, std::string>> memberNames;
  std::map<uint32_t, std::map<uint32_t, uint32_t>> memberOffsets;

  explicit Module(const std::vector<uint32_t>& spirv) {
    for (size_t at = 5; at < spirv.size();) {
      const uint32_t count = spirv[at] >> 16, op = spirv[at] & 0xffff;
      const uint32_t* w = &spirv[at];
      if (count == 0 || at + count > spirv.size()) break;
      if (op == kOpName) names[w[1]] = ReadString(w + 2, count - 2);
      if (op == kOpEntryPoint) entryPoints.emplace_back(w[1], ReadString(w + 3, count - 3));
      if (op == kOpExecutionMode) executionModes.emplace_back(w + 2, w + count);
      if (op == kOpMemberName) memberNames[w[1]][w[2]] = ReadString(w + 3, count - 3);
      if (op == kOpMemberDecorate && w[3] == kDecorationOffset) memberOffsets[w[1]][w[2]] = w[4];
      if (op == kOpTypePointer) pointee[w[1]] = w[3];
      if (op == kOpVariable) varPointer[w[2]] = w[1], storage[w[2]] = w[3];
      if (op == kOpDecorate && w[2] == kDecorationBinding) binding[w[1]] = w[3];
      if (op == kOpDecorate && w[2] == kDecorationDescriptorSet) set[w[1]] = w[3];
      if (op == kOpDecorateString && w[2] == kDecorationUserSemantic) semantic[w[1]] = ReadString(w + 3, count - 3);
      at += count;
    }
  }

  // A resource variable's name, or its type's name for anonymous cbuffer blocks.
  std::string ResourceName(uint32_t var) const {
    if (auto n = names.find(var); n != names.end() && !n->second.empty()) return n->second;
    const auto ptr = varPointer.find(var);
    if (ptr == varPointer.end()) return {};
    const auto type = pointee.find(ptr->second);
    if (type == pointee.end()) return {};
    const auto n = names.find(type->second);
    return n == names.end() ? std::string{} : n->second;
  }

  // Member name -> Offset decoration of the struct type with this OpName.
  std::map<std::string, uint32_t> MemberOffsets(const std::string& structName) const {
    std::map<std::string, uint32_t> out;
    for (const auto& [id, name] : names) {
      if (name != structName || !memberOffsets.count(id)) continue;
      for (const auto& [index, offset] : memberOffsets.at(id)) out[memberNames.at(id).at(index)] = offset;
    }
    return out;
  }

  std::map<std::string, uint32_t> BindingsByName() const {
    std::map<std::string, uint32_t> out;
    for (const auto& [id, b] : binding) out[ResourceName(id)] = b;
    return out;
  }

  std::multiset<std::string> Semantics(uint32_t storageClass) const {
    std::multiset<std::string> out;
    for (const auto& [id, s] : semantic) {
      if (auto st = storage.find(id); st != storage.end() && st->second == storageClass) out.insert(s);
    }
    return out;
  }
};

bool SpirvValid(const std::vector<uint32_t>& spirv) { return spvtools::SpirvTools(SPV_ENV_VULKAN_1_3).Validate(spirv); }

CompileResult Compile(const std::string& source, const std::string& entry, const std::string& profile,
                      const std::string& fileName = "test.hlsl") {
  CompileRequest request;
  request.source = source;
  request.fileName = fileName;
  request.entryPoint = entry;
  request.profile = profile;
  return CompileHlsl(request);
}

#define ASSERT_COMPILED(result) ASSERT_TRUE((result).ok) << (result).FormatErrors()

uint32_t Binding(Stage stage, RegisterClass c, uint32_t slot) {
  return rhi::BindingFor(static_cast<ShaderStage>(stage), c, slot);
}

const hlsl::ResourceInfo* FindResource(const CompileResult& r, const std::string& name) {
  for (const auto& res : r.resources) {
    if (res.name == name) return &res;
  }
  return nullptr;
}

const hlsl::ConstantBufferInfo* FindCbuffer(const CompileResult& r, const std::string& name) {
  for (const auto& cb : r.constantBuffers) {
    if (cb.name == name) return &cb;
  }
  return nullptr;
}

// A temporary folder per test, removed afterwards.
class TempDir {
 public:
  TempDir() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    path_ = fs::temp_directory_path() / ("hlsl_compiler_tests_" + std::to_string(::getpid())) / info->name();
    fs::remove_all(path_);
    fs::create_directories(path_);
  }
  ~TempDir() { fs::remove_all(path_); }
  fs::path Write(const std::string& relative, const std::string& text) const {
    const fs::path p = path_ / relative;
    fs::create_directories(p.parent_path());
    std::ofstream(p) << text;
    return p;
  }
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

// ---------------------------------------------------------------------------
// Shaders

constexpr char kVertexShader[] = R"(
float4 main(float3 p : POSITION) : SV_Position { return float4(p, 1); }
)";
constexpr char kPixelShader[] = R"(
float4 main(float4 p : SV_Position) : SV_Target { return p * 0.5; }
)";
constexpr char kGeometryShader[] = R"(
struct V { float4 pos : SV_Position; };
[maxvertexcount(3)]
void main(triangle V input[3], inout TriangleStream<V> stream) {
  for (int i = 0; i < 3; ++i) stream.Append(input[i]);
  stream.RestartStrip();
}
)";
constexpr char kHullShader[] = R"(
struct CP { float4 pos : POSITION; };
struct PatchConstants { float edges[3] : SV_TessFactor; float inside : SV_InsideTessFactor; };
PatchConstants Constants(InputPatch<CP, 3> patch) {
  PatchConstants c;
  c.edges[0] = c.edges[1] = c.edges[2] = 4;
  c.inside = 4;
  return c;
}
[domain("tri")]
[partitioning("integer")]
[outputtopology("triangle_cw")]
[outputcontrolpoints(3)]
[patchconstantfunc("Constants")]
CP main(InputPatch<CP, 3> patch, uint id : SV_OutputControlPointID) { return patch[id]; }
)";
constexpr char kDomainShader[] = R"(
struct CP { float4 pos : POSITION; };
struct PatchConstants { float edges[3] : SV_TessFactor; float inside : SV_InsideTessFactor; };
[domain("tri")]
float4 main(PatchConstants c, float3 uvw : SV_DomainLocation, const OutputPatch<CP, 3> patch) : SV_Position {
  return patch[0].pos * uvw.x + patch[1].pos * uvw.y + patch[2].pos * uvw.z;
}
)";
constexpr char kComputeShader[] = R"(
RWStructuredBuffer<uint> output : register(u0);
[numthreads(8, 4, 1)]
void main(uint3 id : SV_DispatchThreadID) { output[id.x + id.y * 8] = id.x; }
)";

// SPIR-V execution models.
constexpr uint32_t kVertexModel = 0, kTessControlModel = 1, kTessEvalModel = 2, kGeometryModel = 3, kFragmentModel = 4,
                   kGLComputeModel = 5;
constexpr uint32_t kModeLocalSize = 17, kModeOutputVertices = 26;

// ---------------------------------------------------------------------------

TEST(HlslProfiles, StageFromProfile) {
  bool valid = false;
  EXPECT_EQ(hlsl::StageFromProfile("vs_5_0", &valid), Stage::Vertex);
  EXPECT_TRUE(valid);
  EXPECT_EQ(hlsl::StageFromProfile("ps_4_0", &valid), Stage::Pixel);
  EXPECT_TRUE(valid);
  EXPECT_EQ(hlsl::StageFromProfile("gs_4_1", &valid), Stage::Geometry);
  EXPECT_TRUE(valid);
  EXPECT_EQ(hlsl::StageFromProfile("hs_5_0", &valid), Stage::Hull);
  EXPECT_TRUE(valid);
  EXPECT_EQ(hlsl::StageFromProfile("ds_5_0", &valid), Stage::Domain);
  EXPECT_TRUE(valid);
  EXPECT_EQ(hlsl::StageFromProfile("cs_5_0", &valid), Stage::Compute);
  EXPECT_TRUE(valid);
  hlsl::StageFromProfile("hs_4_0", &valid);  // tessellation needs Shader Model 5
  EXPECT_FALSE(valid);
  hlsl::StageFromProfile("vs_6_0", &valid);
  EXPECT_FALSE(valid);
  hlsl::StageFromProfile("xs_5_0", &valid);
  EXPECT_FALSE(valid);
  hlsl::StageFromProfile("", &valid);
  EXPECT_FALSE(valid);
  static_assert(static_cast<int>(Stage::Compute) == static_cast<int>(ShaderStage::Compute));
  static_assert(static_cast<int>(Stage::Geometry) == static_cast<int>(ShaderStage::Geometry));
}

struct ProfileCase {
  const char* source;
  const char* profile;
  Stage stage;
  uint32_t executionModel;
};

TEST(HlslProfiles, EveryProfileCompilesToValidSpirvWithEntryPointMain) {
  const ProfileCase cases[] = {
      {kVertexShader, "vs_4_0", Stage::Vertex, kVertexModel},
      {kVertexShader, "vs_5_0", Stage::Vertex, kVertexModel},
      {kPixelShader, "ps_4_0", Stage::Pixel, kFragmentModel},
      {kPixelShader, "ps_4_1", Stage::Pixel, kFragmentModel},
      {kPixelShader, "ps_5_0", Stage::Pixel, kFragmentModel},
      {kGeometryShader, "gs_4_0", Stage::Geometry, kGeometryModel},
      {kGeometryShader, "gs_5_0", Stage::Geometry, kGeometryModel},
      {kHullShader, "hs_5_0", Stage::Hull, kTessControlModel},
      {kDomainShader, "ds_5_0", Stage::Domain, kTessEvalModel},
      {kComputeShader, "cs_5_0", Stage::Compute, kGLComputeModel},
  };
  for (const ProfileCase& c : cases) {
    SCOPED_TRACE(c.profile);
    const CompileResult r = Compile(c.source, "main", c.profile);
    ASSERT_COMPILED(r);
    EXPECT_EQ(r.stage, c.stage);
    ASSERT_GT(r.spirv.size(), 5u);
    EXPECT_EQ(r.spirv[0], 0x07230203u);
    EXPECT_EQ(r.spirv[1], 0x00010500u);  // SPIR-V 1.5
    EXPECT_TRUE(SpirvValid(r.spirv));
    const Module m(r.spirv);
    ASSERT_EQ(m.entryPoints.size(), 1u);
    EXPECT_EQ(m.entryPoints[0].first, c.executionModel);
    EXPECT_EQ(m.entryPoints[0].second, "main");
  }
}

TEST(HlslProfiles, EntryPointIsRenamedToMain) {
  const CompileResult r = Compile("float4 VSMain(float4 p : POSITION) : SV_Position { return p; }", "VSMain", "vs_5_0");
  ASSERT_COMPILED(r);
  const Module m(r.spirv);
  ASSERT_EQ(m.entryPoints.size(), 1u);
  EXPECT_EQ(m.entryPoints[0].second, "main");
}

TEST(HlslProfiles, UnknownProfileIsAnError) {
  const CompileResult r = Compile(kVertexShader, "main", "vs_9_9");
  EXPECT_FALSE(r.ok);
  ASSERT_EQ(r.errors.size(), 1u);
  EXPECT_EQ(r.errors[0].message, "unknown profile 'vs_9_9' (expected vs/hs/ds/gs/ps/cs_4_0, _4_1 or _5_0)");
  EXPECT_TRUE(r.spirv.empty());
}

TEST(HlslProfiles, MissingEntryPointIsAnError) {
  const CompileResult r = Compile(kVertexShader, "NotThere", "vs_5_0");
  EXPECT_FALSE(r.ok);
  ASSERT_FALSE(r.errors.empty());
  EXPECT_EQ(r.FormatErrors(), "test.hlsl: error: entry point 'NotThere' not found\n");
}

// glslang drops an SV_Coverage input declared as a plain parameter (the shader
// would read an undefined value): that is an error naming the workaround; the
// same input as a struct member compiles and reaches the SampleMask built-in.
TEST(HlslProfiles, CoverageInputAsAParameterIsAnErrorAndAsAStructMemberCompiles) {
  const CompileResult param = Compile(
      "float4 main(float4 p : SV_Position, uint c : SV_Coverage) : SV_Target { return c; }", "main", "ps_5_0");
  EXPECT_FALSE(param.ok);
  EXPECT_EQ(param.FormatErrors(),
            "test.hlsl: error: SV_Coverage input declared as a parameter of 'main': glslang's HLSL front end drops "
            "it (the shader would read an undefined value); declare it as a member of the input struct\n");
  const CompileResult member = Compile(
      "struct In { float4 p : SV_Position; uint c : SV_Coverage; };\n"
      "struct Out { float4 color : SV_Target; uint c : SV_Coverage; };\n"
      "Out main(In i) { Out o; o.color = i.c; o.c = i.c; return o; }",
      "main", "ps_5_0");
  ASSERT_COMPILED(member);
}

// glslang has no GetRenderTargetSamplePosition; the compiler supplies it, with
// the sample count as the specialization constant the backend sets.
TEST(HlslProfiles, GetRenderTargetSamplePositionReadsTheSampleCountSpecializationConstant) {
  const CompileResult r = Compile(
      "float4 main() : SV_Target { return float4(GetRenderTargetSamplePosition(1), 0, 1); }", "main", "ps_5_0");
  ASSERT_COMPILED(r);
  constexpr uint32_t kOpDecorate = 71, kDecorationSpecId = 1;
  bool found = false;
  for (size_t at = 5; at < r.spirv.size(); at += r.spirv[at] >> 16) {
    const uint32_t words = r.spirv[at] >> 16;
    if (words == 0) break;
    found |= (r.spirv[at] & 0xffff) == kOpDecorate && words == 4 && r.spirv[at + 2] == kDecorationSpecId &&
             r.spirv[at + 3] == rhi::kRenderTargetSampleCountSpecId;
  }
  EXPECT_TRUE(found) << "no SpecId " << rhi::kRenderTargetSampleCountSpecId << " decoration";
}

TEST(HlslProfiles, GeometryShaderKeepsMaxVertexCount) {
  const CompileResult r = Compile(kGeometryShader, "main", "gs_5_0");
  ASSERT_COMPILED(r);
  const Module m(r.spirv);
  EXPECT_NE(std::find(m.executionModes.begin(), m.executionModes.end(), std::vector<uint32_t>{kModeOutputVertices, 3}),
            m.executionModes.end());
}

// The particle update GS declares as many output vertices as its loader's rule
// spawns (MAX_SPAWN_PER_UPDATE: renderer::MaxSpawnPerUpdateDefine) plus the emitter
// itself, and the most the rule allows (16 + 1) when nothing defines it.
TEST(HlslProfiles, ParticleUpdateDeclaresTheOutputItsLoaderDefines) {
  // What an effect holding the update pass (shaders_hlsl/particles.fx) compiles.
  constexpr char kUpdate[] = R"(
#include "particle.hlsli"
#include "particle_rule.hlsli"
cbuffer UpdateParams : register(b0) {
  uint Frame, SpawnPerFrame, MinLife, LifeRange;
  float3 Spread;
  float SpeedUp;
};
#include "particle_update.hlsli"
)";
  auto outputVertices = [&](const std::vector<hlsl::Define>& defines) {
    hlsl::CompileRequest request;
    request.source = kUpdate;
    request.entryPoint = "GSUpdate";
    request.profile = "gs_5_0";
    request.includeDirs = {PROJECT_SOURCE_ROOT "/shaders_hlsl"};
    request.defines = defines;
    const CompileResult r = hlsl::CompileHlsl(request);
    EXPECT_TRUE(r.ok) << r.FormatErrors();
    for (const std::vector<uint32_t>& mode : Module(r.spirv).executionModes)
      if (mode.size() == 2 && mode[0] == kModeOutputVertices) return mode[1];
    return 0u;
  };
  EXPECT_EQ(outputVertices({{"MAX_SPAWN_PER_UPDATE", "8"}}), 9u);
  EXPECT_EQ(outputVertices({{"MAX_SPAWN_PER_UPDATE", "2"}}), 3u);
  EXPECT_EQ(outputVertices({}), 17u);
}

TEST(HlslProfiles, ComputeShaderKeepsNumThreads) {
  const CompileResult r = Compile(kComputeShader, "main", "cs_5_0");
  ASSERT_COMPILED(r);
  const Module m(r.spirv);
  ASSERT_EQ(m.executionModes.size(), 1u);
  EXPECT_EQ(m.executionModes[0], (std::vector<uint32_t>{kModeLocalSize, 8, 4, 1}));
}

// fxc converts an integer literal given to a RWByteAddressBuffer atomic;
// glslang passes it as an int to a uint atomic, which SPIR-V validation
// rejects unless the compiler retypes it.
TEST(HlslProfiles, ByteAddressBufferAtomicsTakeIntegerLiterals) {
  const CompileResult r = Compile(R"(
RWByteAddressBuffer raw : register(u1);
float4 main(float4 p : SV_Position) : SV_Target {
  uint old;
  raw.InterlockedAdd(0, 1);
  raw.InterlockedAdd(4, 2, old);
  raw.InterlockedMin(8, -3);
  raw.InterlockedCompareExchange(12, 0, uint(p.x), old);
  raw.InterlockedExchange(16, 5, old);
  return float4(old, 0, 0, 1);
})",
                                  "main", "ps_5_0");
  ASSERT_COMPILED(r);
}

// ---------------------------------------------------------------------------
// Register -> binding mapping

constexpr char kVertexResources[] = R"(
cbuffer PerObject : register(b3) { float4x4 world; };
Texture2D heightMap : register(t5);
SamplerState heightSampler : register(s2);
float4 main(float3 p : POSITION, float2 uv : TEXCOORD0) : SV_Position {
  float h = heightMap.SampleLevel(heightSampler, uv, 0).r;
  return mul(float4(p.x, h, p.z, 1), world);
}
)";

constexpr char kPixelResources[] = R"(
cbuffer Material : register(b1) { float4 tint; };
Texture2D albedo : register(t0);
SamplerState linearSampler : register(s7);
RWTexture2D<float4> debugOut : register(u1);
float4 main(float4 pos : SV_Position, float2 uv : TEXCOORD0) : SV_Target {
  float4 c = albedo.Sample(linearSampler, uv) * tint;
  debugOut[uint2(pos.xy)] = c;
  return c;
}
)";

TEST(HlslRegisters, VertexShaderRegistersMapToVertexWindow) {
  const CompileResult r = Compile(kVertexResources, "main", "vs_5_0");
  ASSERT_COMPILED(r);
  const Module m(r.spirv);
  const std::map<std::string, uint32_t> expected = {
      {"PerObject", Binding(Stage::Vertex, RegisterClass::ConstantBuffer, 3)},
      {"heightMap", Binding(Stage::Vertex, RegisterClass::ShaderResource, 5)},
      {"heightSampler", Binding(Stage::Vertex, RegisterClass::Sampler, 2)},
  };
  EXPECT_EQ(m.BindingsByName(), expected);
  EXPECT_EQ(expected.at("PerObject"), 3u);
  EXPECT_EQ(expected.at("heightMap"), 21u);
  EXPECT_EQ(expected.at("heightSampler"), 146u);
  for (const auto& [id, b] : m.binding) {
    (void)b;
    ASSERT_TRUE(m.set.count(id));
    EXPECT_EQ(m.set.at(id), 0u);
  }
}

TEST(HlslRegisters, PixelShaderRegistersMapToPixelWindow) {
  const CompileResult r = Compile(kPixelResources, "main", "ps_5_0");
  ASSERT_COMPILED(r);
  const Module m(r.spirv);
  const std::map<std::string, uint32_t> expected = {
      {"Material", Binding(Stage::Pixel, RegisterClass::ConstantBuffer, 1)},
      {"albedo", Binding(Stage::Pixel, RegisterClass::ShaderResource, 0)},
      {"linearSampler", Binding(Stage::Pixel, RegisterClass::Sampler, 7)},
      {"debugOut", Binding(Stage::Pixel, RegisterClass::UnorderedAccess, 1)},
  };
  EXPECT_EQ(m.BindingsByName(), expected);
  EXPECT_EQ(expected.at("Material"), 4u * 256 + 1);
  EXPECT_EQ(expected.at("debugOut"), 4u * 256 + 161);
  for (const auto& [id, s] : m.set) {
    (void)id;
    EXPECT_EQ(s, 0u);
  }
}

TEST(HlslRegisters, ReflectionReportsBindingsSlotsAndKinds) {
  const CompileResult r = Compile(kPixelResources, "main", "ps_5_0");
  ASSERT_COMPILED(r);
  const auto* material = FindCbuffer(r, "Material");
  ASSERT_NE(material, nullptr);
  EXPECT_EQ(material->binding, Binding(Stage::Pixel, RegisterClass::ConstantBuffer, 1));
  EXPECT_EQ(material->registerSlot, 1u);
  EXPECT_EQ(material->size, 16u);
  ASSERT_EQ(r.resources.size(), 3u);
  const auto* albedo = FindResource(r, "albedo");
  ASSERT_NE(albedo, nullptr);
  EXPECT_EQ(albedo->kind, hlsl::ResourceInfo::Kind::Texture);
  EXPECT_EQ(albedo->dimension, hlsl::ResourceInfo::Dimension::Tex2D);
  EXPECT_EQ(albedo->registerSlot, 0u);
  EXPECT_EQ(albedo->binding, Binding(Stage::Pixel, RegisterClass::ShaderResource, 0));
  const auto* sampler = FindResource(r, "linearSampler");
  ASSERT_NE(sampler, nullptr);
  EXPECT_EQ(sampler->kind, hlsl::ResourceInfo::Kind::Sampler);
  EXPECT_EQ(sampler->registerSlot, 7u);
  EXPECT_FALSE(sampler->comparisonSampler);
  const auto* uav = FindResource(r, "debugOut");
  ASSERT_NE(uav, nullptr);
  EXPECT_EQ(uav->kind, hlsl::ResourceInfo::Kind::RWTexture);
  EXPECT_EQ(uav->registerSlot, 1u);
  EXPECT_EQ(uav->binding, Binding(Stage::Pixel, RegisterClass::UnorderedAccess, 1));
}

TEST(HlslRegisters, UnregisteredResourcesTakeFreeSlotsOfTheirClass) {
  constexpr char source[] = R"(
cbuffer Fixed : register(b0) { float4 a; };
cbuffer Floating { float4 b; };
Texture2D fixedTex : register(t0);
Texture2D floatingTex;
SamplerState floatingSampler;
float4 main(float4 pos : SV_Position) : SV_Target {
  return fixedTex.Sample(floatingSampler, pos.xy) + floatingTex.Sample(floatingSampler, pos.xy) + a + b;
}
)";
  const CompileResult r = Compile(source, "main", "ps_5_0");
  ASSERT_COMPILED(r);
  const auto* floating = FindCbuffer(r, "Floating");
  ASSERT_NE(floating, nullptr);
  EXPECT_EQ(floating->registerSlot, 1u);
  EXPECT_EQ(floating->binding, Binding(Stage::Pixel, RegisterClass::ConstantBuffer, 1));
  const auto* tex = FindResource(r, "floatingTex");
  ASSERT_NE(tex, nullptr);
  EXPECT_EQ(tex->registerSlot, 1u);
  EXPECT_EQ(tex->binding, Binding(Stage::Pixel, RegisterClass::ShaderResource, 1));
  const auto* sampler = FindResource(r, "floatingSampler");
  ASSERT_NE(sampler, nullptr);
  EXPECT_EQ(sampler->registerSlot, 0u);
  EXPECT_EQ(sampler->binding, Binding(Stage::Pixel, RegisterClass::Sampler, 0));
  // The reflected bindings are the ones in the SPIR-V.
  const auto bindings = Module(r.spirv).BindingsByName();
  EXPECT_EQ(bindings.at("Floating"), floating->binding);
  EXPECT_EQ(bindings.at("floatingTex"), tex->binding);
  EXPECT_EQ(bindings.at("floatingSampler"), sampler->binding);
}

TEST(HlslRegisters, ComputeBuffersMapToShaderResourceAndUnorderedAccessWindows) {
  constexpr char source[] = R"(
struct Particle { float3 position; float life; };
StructuredBuffer<Particle> particlesIn : register(t2);
ByteAddressBuffer raw : register(t3);
Buffer<float4> typed : register(t4);
RWStructuredBuffer<Particle> particlesOut : register(u0);
RWByteAddressBuffer rawOut : register(u2);
RWBuffer<float> typedOut : register(u3);
[numthreads(64, 1, 1)]
void main(uint3 id : SV_DispatchThreadID) {
  Particle p = particlesIn[id.x];
  p.life -= asfloat(raw.Load(id.x * 4)) + typed[id.x].x;
  particlesOut[id.x] = p;
  rawOut.Store(id.x * 4, asuint(p.life));
  typedOut[id.x] = p.life;
}
)";
  const CompileResult r = Compile(source, "main", "cs_5_0");
  ASSERT_COMPILED(r);
  using K = hlsl::ResourceInfo::Kind;
  struct Expect {
    const char* name;
    K kind;
    RegisterClass c;
    uint32_t slot;
  };
  const Expect expected[] = {
      {"particlesIn", K::StructuredBuffer, RegisterClass::ShaderResource, 2},
      {"raw", K::ByteAddressBuffer, RegisterClass::ShaderResource, 3},
      {"typed", K::Buffer, RegisterClass::ShaderResource, 4},
      {"particlesOut", K::RWStructuredBuffer, RegisterClass::UnorderedAccess, 0},
      {"rawOut", K::RWByteAddressBuffer, RegisterClass::UnorderedAccess, 2},
      {"typedOut", K::RWBuffer, RegisterClass::UnorderedAccess, 3},
  };
  ASSERT_EQ(r.resources.size(), std::size(expected));
  const auto bindings = Module(r.spirv).BindingsByName();
  for (const Expect& e : expected) {
    SCOPED_TRACE(e.name);
    const auto* res = FindResource(r, e.name);
    ASSERT_NE(res, nullptr);
    EXPECT_EQ(res->kind, e.kind);
    EXPECT_EQ(res->registerSlot, e.slot);
    EXPECT_EQ(res->binding, Binding(Stage::Compute, e.c, e.slot));
    EXPECT_EQ(res->dimension, hlsl::ResourceInfo::Dimension::Buffer);
    EXPECT_EQ(bindings.at(e.name), res->binding);
  }
}

// ---------------------------------------------------------------------------
// Semantics

TEST(HlslSemantics, VertexShaderStructInputsAndOutputsKeepSemantics) {
  constexpr char source[] = R"(
struct VSIn {
  float3 position : POSITION;
  float2 uv0 : TEXCOORD0;
  float2 uv1 : TEXCOORD1;
  float4 color : COLOR;
};
struct VSOut {
  float4 position : SV_Position;
  float2 uv0 : TEXCOORD0;
  float2 uv1 : TEXCOORD1;
  float4 color : COLOR;
};
VSOut main(VSIn input) {
  VSOut o;
  o.position = float4(input.position, 1);
  o.uv0 = input.uv0;
  o.uv1 = input.uv1;
  o.color = input.color;
  return o;
}
)";
  const CompileResult r = Compile(source, "main", "vs_5_0");
  ASSERT_COMPILED(r);
  const Module m(r.spirv);
  EXPECT_EQ(m.Semantics(kStorageInput), (std::multiset<std::string>{"POSITION", "TEXCOORD0", "TEXCOORD1", "COLOR"}));
  EXPECT_EQ(m.Semantics(kStorageOutput),
            (std::multiset<std::string>{"SV_POSITION", "TEXCOORD0", "TEXCOORD1", "COLOR"}));
}

TEST(HlslSemantics, PixelShaderMultipleRenderTargets) {
  constexpr char source[] = R"(
struct PSOut { float4 color : SV_Target0; float4 normal : SV_Target1; };
PSOut main(float4 pos : SV_Position, float3 n : NORMAL) {
  PSOut o;
  o.color = pos;
  o.normal = float4(n, 0);
  return o;
}
)";
  const CompileResult r = Compile(source, "main", "ps_5_0");
  ASSERT_COMPILED(r);
  const Module m(r.spirv);
  EXPECT_EQ(m.Semantics(kStorageOutput), (std::multiset<std::string>{"SV_TARGET0", "SV_TARGET1"}));
  EXPECT_EQ(m.Semantics(kStorageInput), (std::multiset<std::string>{"SV_POSITION", "NORMAL"}));
}

// ---------------------------------------------------------------------------
// Diagnostics

TEST(HlslDiagnostics, UndeclaredIdentifierHasFileLineColumnAndMessage) {
  constexpr char source[] =
      "float4 main(float4 p : POSITION) : SV_Position\n"
      "{\n"
      "    float4 x = p * undeclaredThing;\n"
      "    return x;\n"
      "}\n";
  const CompileResult r = Compile(source, "main", "vs_5_0", "shaders/broken.hlsl");
  EXPECT_FALSE(r.ok);
  EXPECT_TRUE(r.spirv.empty());
  ASSERT_FALSE(r.errors.empty());
  const hlsl::Diagnostic& d = r.errors[0];
  EXPECT_EQ(d.file, "shaders/broken.hlsl");
  EXPECT_EQ(d.line, 3);
  EXPECT_EQ(d.column, 20);
  EXPECT_EQ(d.message, "'undeclaredThing' : unknown variable");
  EXPECT_EQ(r.FormatErrors().substr(0, r.FormatErrors().find('\n')),
            "shaders/broken.hlsl:3:20: error: 'undeclaredThing' : unknown variable");
}

TEST(HlslDiagnostics, LineDirectiveIsRespected) {
  constexpr char source[] =
      "#line 40 \"generated.hlsl\"\n"
      "float4 main(float4 p : POSITION) : SV_Position\n"
      "{\n"
      "    return missing;\n"
      "}\n";
  const CompileResult r = Compile(source, "main", "vs_5_0");
  EXPECT_FALSE(r.ok);
  ASSERT_FALSE(r.errors.empty());
  EXPECT_EQ(r.errors[0].file, "generated.hlsl");
  EXPECT_EQ(r.errors[0].line, 42);
  EXPECT_EQ(r.errors[0].message, "'missing' : unknown variable");
}

TEST(HlslDiagnostics, GarbageInputFailsWithoutCrashing) {
  const std::string inputs[] = {
      "",
      "}}}}{{{{",
      "float4 main( : SV_Target",
      "/* unterminated comment",
      "#if 1\n#include",
      "#define A A A\nA",
      std::string("\x00\xff\xfe\x01garbage\x80", 13),
      std::string(10000, '('),
      "cbuffer { float4 x : register(b99999999999); }",
      "float4 main() : SV_Target { return tex2D(s, 0); }",
  };
  for (const std::string& input : inputs) {
    const CompileResult r = Compile(input, "main", "ps_5_0");
    EXPECT_FALSE(r.ok) << input;
    EXPECT_FALSE(r.errors.empty()) << input;
    EXPECT_TRUE(r.spirv.empty());
    EXPECT_FALSE(r.FormatErrors().empty());
  }
}

TEST(HlslDiagnostics, FormatErrorsListsEveryError) {
  constexpr char source[] = "float4 main() : SV_Target {\n  return a +\n b;\n}\n";
  const CompileResult r = Compile(source, "main", "ps_5_0", "two.hlsl");
  ASSERT_GE(r.errors.size(), 2u);
  // glslang's HLSL parser gives up on the expression after the unknown name; the
  // follow-up error quotes no source token, so it gets the column where glslang
  // says the parse stopped (after "return a +").
  const std::string text = r.FormatErrors();
  EXPECT_EQ(text.substr(0, text.find('\n', text.find('\n') + 1) + 1),
            "two.hlsl:2:10: error: 'a' : unknown variable\n"
            "two.hlsl:2:13: error: 'expression' : Expected\n");
  EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), static_cast<long>(r.errors.size()));
}

TEST(HlslDiagnostics, SwizzleErrorPointsAtTheSwizzle) {
  constexpr char source[] =
      "float4 main() : SV_Target {\n"
      "  float2 v = float2(1, 2);\n"
      "  return v.xyzw;\n"
      "}\n";
  const CompileResult r = Compile(source, "main", "ps_5_0", "swizzle.hlsl");
  ASSERT_FALSE(r.errors.empty());
  EXPECT_EQ(r.errors[0].line, 3);
  EXPECT_EQ(r.errors[0].column, 12);
  EXPECT_EQ(r.errors[0].message, "'xyzw' : vector swizzle selection out of range");
}

// ---------------------------------------------------------------------------
// Preprocessor

TEST(HlslPreprocessor, IncludeRelativeToIncludingFile) {
  TempDir dir;
  dir.Write("shaders/common/math.h", "#include \"consts.h\"\nfloat4 Scale(float4 v) { return v * SCALE; }\n");
  dir.Write("shaders/common/consts.h", "static const float SCALE = 2.0;\n");
  const fs::path main = dir.Write("shaders/main.hlsl", "");
  const CompileResult r =
      Compile("#include \"common/math.h\"\nfloat4 main(float4 p : POSITION) : SV_Position { return Scale(p); }\n",
              "main", "vs_5_0", main.string());
  ASSERT_COMPILED(r);
}

TEST(HlslPreprocessor, IncludeThroughIncludeDirs) {
  TempDir dir;
  dir.Write("lib/lighting.h", "float3 Lambert(float3 n, float3 l) { return saturate(dot(n, l)); }\n");
  CompileRequest request;
  request.source =
      "#include \"lighting.h\"\n"
      "float4 main(float3 n : NORMAL) : SV_Target { return float4(Lambert(n, float3(0, 1, 0)), 1); }\n";
  request.fileName = (dir.path() / "src" / "ps.hlsl").string();
  request.entryPoint = "main";
  request.profile = "ps_5_0";
  EXPECT_FALSE(CompileHlsl(request).ok);  // not found next to ps.hlsl
  request.includeDirs = {(dir.path() / "lib").string()};
  const CompileResult r = CompileHlsl(request);
  ASSERT_COMPILED(r);
}

TEST(HlslPreprocessor, ErrorsInIncludedFilesNameThatFile) {
  TempDir dir;
  const fs::path header = dir.Write("bad.h", "float Helper()\n{\n  return nope;\n}\n");
  const fs::path main = dir.Write("main.hlsl", "");
  const CompileResult r =
      Compile("#include \"bad.h\"\nfloat4 main() : SV_Target { return Helper(); }\n", "main", "ps_5_0", main.string());
  EXPECT_FALSE(r.ok);
  ASSERT_FALSE(r.errors.empty());
  EXPECT_EQ(r.errors[0].file, header.lexically_normal().string());
  EXPECT_EQ(r.errors[0].line, 3);
  EXPECT_EQ(r.errors[0].column, 10);
  EXPECT_EQ(r.errors[0].message, "'nope' : unknown variable");
}

TEST(HlslPreprocessor, MissingIncludeIsAClearError) {
  TempDir dir;
  const fs::path main = dir.Write("main.hlsl", "");
  const CompileResult r = Compile("\n#include \"does_not_exist.h\"\nfloat4 main() : SV_Target { return 0; }\n", "main",
                                  "ps_5_0", main.string());
  EXPECT_FALSE(r.ok);
  ASSERT_FALSE(r.errors.empty());
  EXPECT_EQ(r.errors[0].file, main.string());
  EXPECT_EQ(r.errors[0].line, 2);
  EXPECT_NE(r.errors[0].message.find("cannot open include file"), std::string::npos) << r.errors[0].message;
  EXPECT_NE(r.errors[0].message.find("does_not_exist.h"), std::string::npos) << r.errors[0].message;
}

TEST(HlslCompileFile, ReadsTheFileResolvesIncludesAndNamesAMissingFile) {
  TempDir dir;
  dir.Write("colour.h", "#define COLOUR float4(1, 0, 0, 1)\n");
  const fs::path main = dir.Write("main.hlsl", "#include \"colour.h\"\nfloat4 main() : SV_Target { return COLOUR; }\n");
  const CompileResult ok = hlsl::CompileHlslFile(main.string(), "main", "ps_5_0");
  EXPECT_TRUE(ok.ok) << ok.FormatErrors();
  EXPECT_FALSE(ok.spirv.empty());

  const std::string missing = (dir.path() / "missing.hlsl").string();
  const CompileResult r = hlsl::CompileHlslFile(missing, "main", "ps_5_0");
  EXPECT_FALSE(r.ok);
  EXPECT_EQ(r.FormatErrors(), missing + ": error: cannot read the file\n");
}

TEST(HlslPreprocessor, DefinesAreApplied) {
  constexpr char source[] = R"(
#if !defined(USE_COLOR) || BRIGHTNESS != 3
#error defines missing
#endif
float4 main() : SV_Target { return COLOR_VALUE * BRIGHTNESS; }
)";
  CompileRequest request{source, "defines.hlsl", "main", "ps_5_0", {}, {}};
  const CompileResult without = CompileHlsl(request);
  ASSERT_FALSE(without.errors.empty());
  EXPECT_EQ(without.errors[0].line, 3);
  EXPECT_EQ(without.errors[0].message, "'#error' : defines missing");
  request.defines = {{"USE_COLOR", ""}, {"BRIGHTNESS", "3"}, {"COLOR_VALUE", "float4(1, 0, 0, 1)"}};
  const CompileResult r = CompileHlsl(request);
  ASSERT_COMPILED(r);
}

TEST(HlslPreprocessor, InvalidDefinesAreRejected) {
  CompileRequest request{kPixelShader, "defines.hlsl", "main", "ps_5_0", {{"1BAD", ""}}, {}};
  CompileResult r = CompileHlsl(request);
  EXPECT_FALSE(r.ok);
  EXPECT_EQ(r.FormatErrors(),
            "defines.hlsl: error: invalid define '1BAD': the name must be an identifier and the value one line\n");
  request.defines = {{"A", "1\n#error injected"}};
  r = CompileHlsl(request);
  EXPECT_FALSE(r.ok);
  EXPECT_EQ(r.errors.size(), 1u);
}

// ---------------------------------------------------------------------------
// Reflection

TEST(HlslReflection, CbufferMembersFollowHlslPacking) {
  constexpr char source[] = R"(
cbuffer Params : register(b2) {
  float4x4 m;
  float3 a;
  float b;
  float2 c;
};
float4 main(float4 p : POSITION) : SV_Position { return mul(p, m) + float4(a, b) + c.xyxy; }
)";
  const CompileResult r = Compile(source, "main", "vs_5_0");
  ASSERT_COMPILED(r);
  ASSERT_EQ(r.constantBuffers.size(), 1u);
  const hlsl::ConstantBufferInfo& cb = r.constantBuffers[0];
  EXPECT_EQ(cb.name, "Params");
  EXPECT_EQ(cb.binding, Binding(Stage::Vertex, RegisterClass::ConstantBuffer, 2));
  EXPECT_EQ(cb.registerSlot, 2u);
  EXPECT_EQ(cb.size, 96u);
  ASSERT_EQ(cb.members.size(), 4u);
  struct Expect {
    const char* name;
    uint32_t offset, size, rows, columns;
  };
  const Expect expected[] = {{"m", 0, 64, 4, 4}, {"a", 64, 12, 1, 3}, {"b", 76, 4, 1, 1}, {"c", 80, 8, 1, 2}};
  for (size_t i = 0; i < std::size(expected); ++i) {
    SCOPED_TRACE(expected[i].name);
    EXPECT_EQ(cb.members[i].name, expected[i].name);
    EXPECT_EQ(cb.members[i].offset, expected[i].offset);
    EXPECT_EQ(cb.members[i].size, expected[i].size);
    EXPECT_EQ(cb.members[i].rows, expected[i].rows);
    EXPECT_EQ(cb.members[i].columns, expected[i].columns);
    EXPECT_EQ(cb.members[i].baseType, hlsl::BaseType::Float);
    EXPECT_EQ(cb.members[i].arrayElements, 0u);
  }
}

// Offsets are the SPIR-V Offset decorations, i.e. what the shader reads. They
// follow fxc except that nothing packs into the padding after an array or a
// matrix (SPIR-V arrays and matrices own whole 16-byte strides): fxc would put
// `after` at 164 and `tail` at 236.
TEST(HlslReflection, ArraysMatricesAndStructsFollowSpirvLayout) {
  constexpr char source[] = R"(
struct Light { float3 color; float intensity; float2 dir; };
cbuffer Mixed {
  float scalar;            // 0
  float2 packed;           // 4: shares the first register, as in fxc
  float4x3 m43;            // 16: 3 registers (column_major)
  row_major float4x3 r43;  // 64: 4 registers of 3
  float weights[3];        // 128: stride 16, 36 bytes as D3D counts it
  int after;               // 176 (fxc: 164)
  Light light;             // 192
  Light lights[2];         // 224, 256
  float3x3 m33;            // 288: 44 bytes
  uint tail;               // 336 (fxc: 332)
};
float4 main() : SV_Target {
  return scalar + packed.x + m43[0].x + r43[0].x + weights[2] + after + light.intensity + lights[1].dir.y +
         m33[1].x + tail;
}
)";
  const CompileResult r = Compile(source, "main", "ps_5_0");
  ASSERT_COMPILED(r);
  const auto* cb = FindCbuffer(r, "Mixed");
  ASSERT_NE(cb, nullptr);
  struct Expect {
    const char* name;
    uint32_t offset, size, rows, columns, array;
    hlsl::BaseType type;
  };
  using B = hlsl::BaseType;
  const Expect expected[] = {
      {"scalar", 0, 4, 1, 1, 0, B::Float},
      {"packed", 4, 8, 1, 2, 0, B::Float},
      {"m43", 16, 48, 4, 3, 0, B::Float},
      {"r43", 64, 60, 4, 3, 0, B::Float},
      {"weights", 128, 36, 1, 1, 3, B::Float},
      {"after", 176, 4, 1, 1, 0, B::Int},
      {"light.color", 192, 12, 1, 3, 0, B::Float},
      {"light.intensity", 204, 4, 1, 1, 0, B::Float},
      {"light.dir", 208, 8, 1, 2, 0, B::Float},
      {"lights[0].color", 224, 12, 1, 3, 0, B::Float},
      {"lights[0].intensity", 236, 4, 1, 1, 0, B::Float},
      {"lights[0].dir", 240, 8, 1, 2, 0, B::Float},
      {"lights[1].color", 256, 12, 1, 3, 0, B::Float},
      {"lights[1].intensity", 268, 4, 1, 1, 0, B::Float},
      {"lights[1].dir", 272, 8, 1, 2, 0, B::Float},
      {"m33", 288, 44, 3, 3, 0, B::Float},
      {"tail", 336, 4, 1, 1, 0, B::Uint},
  };
  ASSERT_EQ(cb->members.size(), std::size(expected));
  for (size_t i = 0; i < std::size(expected); ++i) {
    SCOPED_TRACE(expected[i].name);
    EXPECT_EQ(cb->members[i].name, expected[i].name);
    EXPECT_EQ(cb->members[i].offset, expected[i].offset);
    EXPECT_EQ(cb->members[i].size, expected[i].size);
    EXPECT_EQ(cb->members[i].rows, expected[i].rows);
    EXPECT_EQ(cb->members[i].columns, expected[i].columns);
    EXPECT_EQ(cb->members[i].arrayElements, expected[i].array);
    EXPECT_EQ(cb->members[i].baseType, expected[i].type);
  }
  EXPECT_EQ(cb->size, 352u);
  // Top-level members agree with the SPIR-V the backend will fill.
  const auto spirvOffsets = Module(r.spirv).MemberOffsets("Mixed");
  for (const char* name : {"scalar", "packed", "m43", "r43", "weights", "after", "light", "lights", "m33", "tail"}) {
    SCOPED_TRACE(name);
    ASSERT_TRUE(spirvOffsets.count(name));
  }
  EXPECT_EQ(spirvOffsets.at("packed"), 4u);
  EXPECT_EQ(spirvOffsets.at("after"), 176u);
  EXPECT_EQ(spirvOffsets.at("lights"), 224u);
  EXPECT_EQ(spirvOffsets.at("tail"), 336u);
}

TEST(HlslReflection, GlobalsOutsideCbuffersFormGlobalsBuffer) {
  constexpr char source[] = R"(
float4 gTint;
float gScale;
float2 gOffset;
float4 main() : SV_Target { return gTint * gScale + gOffset.xyxy; }
)";
  const CompileResult r = Compile(source, "main", "ps_5_0");
  ASSERT_COMPILED(r);
  ASSERT_EQ(r.constantBuffers.size(), 1u);
  const hlsl::ConstantBufferInfo& cb = r.constantBuffers[0];
  EXPECT_EQ(cb.name, "$Globals");
  EXPECT_EQ(cb.registerSlot, 0u);
  EXPECT_EQ(cb.binding, Binding(Stage::Pixel, RegisterClass::ConstantBuffer, 0));
  EXPECT_EQ(cb.size, 32u);
  ASSERT_EQ(cb.members.size(), 3u);
  EXPECT_EQ(cb.members[0].name, "gTint");
  EXPECT_EQ(cb.members[0].offset, 0u);
  EXPECT_EQ(cb.members[1].name, "gScale");
  EXPECT_EQ(cb.members[1].offset, 16u);
  // glslang 12 keeps GLSL vector alignment for "$Global" (fxc would say 20).
  EXPECT_EQ(cb.members[2].name, "gOffset");
  EXPECT_EQ(cb.members[2].offset, 24u);
  const auto spirvOffsets = Module(r.spirv).MemberOffsets("$Global");
  EXPECT_EQ(spirvOffsets.at("gOffset"), 24u);
}

// ---------------------------------------------------------------------------
// Legalization

TEST(HlslLegalization, TexturesAndSamplersPassedToFunctionsValidate) {
  constexpr char source[] = R"(
Texture2D diffuseMap : register(t0);
Texture2D normalMap : register(t1);
SamplerState wrapSampler : register(s0);
SamplerComparisonState shadowSampler : register(s1);
Texture2D shadowMap : register(t2);

static const float2 kOffsets[4] = { float2(-1, -1), float2(1, -1), float2(-1, 1), float2(1, 1) };

float4 SampleBlurred(Texture2D tex, SamplerState s, float2 uv) {
  float4 sum = 0;
  [unroll] for (int i = 0; i < 4; ++i) sum += tex.Sample(s, uv + kOffsets[i] * 0.001);
  return sum * 0.25;
}

float Shadow(Texture2D map, SamplerComparisonState s, float3 pos) {
  return map.SampleCmpLevelZero(s, pos.xy, pos.z);
}

float4 main(float4 pos : SV_Position, float2 uv : TEXCOORD0, float3 shadowPos : TEXCOORD1) : SV_Target {
  float4 c = SampleBlurred(diffuseMap, wrapSampler, uv);
  float4 n = SampleBlurred(normalMap, wrapSampler, uv);
  return c * n.z * Shadow(shadowMap, shadowSampler, shadowPos);
}
)";
  const CompileResult r = Compile(source, "main", "ps_4_0");
  ASSERT_COMPILED(r);
  EXPECT_TRUE(SpirvValid(r.spirv));
  const auto* shadow = FindResource(r, "shadowSampler");
  ASSERT_NE(shadow, nullptr);
  EXPECT_TRUE(shadow->comparisonSampler);
  EXPECT_EQ(shadow->binding, Binding(Stage::Pixel, RegisterClass::Sampler, 1));
  const auto bindings = Module(r.spirv).BindingsByName();
  EXPECT_EQ(bindings.at("diffuseMap"), Binding(Stage::Pixel, RegisterClass::ShaderResource, 0));
  EXPECT_EQ(bindings.at("normalMap"), Binding(Stage::Pixel, RegisterClass::ShaderResource, 1));
  EXPECT_EQ(bindings.at("shadowMap"), Binding(Stage::Pixel, RegisterClass::ShaderResource, 2));
  EXPECT_EQ(bindings.at("wrapSampler"), Binding(Stage::Pixel, RegisterClass::Sampler, 0));
}

// ---------------------------------------------------------------------------
// Crash isolation

// Each of these crashes glslang 12 or the SPIRV-Tools legalization passes
// (found by fuzzing); in the worker process that becomes an error.
constexpr const char* kCrashingSources[] = {
    "static const float k[3I = {1, 2, 3};\nfloat4 main() : SV_Target { return k[0]; }\n",
    "struct I { float4 p : POSITION; };\nfloat4 main(I) : SV_Position { return 0; }\n",
    "float4 H(Texture2D [t) { return 0; }\nfloat4 main() : SV_Target { return 0; }\n",
    "Texture2D tex : register(t0)plerState s : register(s0);\n"
    "float4 H(Texture2D t, SamplerState ss) { return t.SampleLevel(ss, 0, 0); }\n"
    "float4 main() : SV_Position { return H(tex, s); }\n",
};

TEST(HlslIsolation, CompilerCrashesBecomeErrors) {
  if (!hlsl::CrashIsolationAvailable()) GTEST_SKIP() << "sanitizer build: compiles run in-process";
  for (const char* source : kCrashingSources) {
    const CompileResult r = Compile(source, "main", "vs_5_0", "crash.hlsl");
    EXPECT_FALSE(r.ok) << source;
    ASSERT_EQ(r.errors.size(), 1u) << r.FormatErrors();
    EXPECT_EQ(r.errors[0].file, "crash.hlsl");
    EXPECT_EQ(r.errors[0].message,
              "internal compiler error: glslang/SPIRV-Tools crashed on this source (Segmentation fault)");
    EXPECT_TRUE(r.spirv.empty());
  }
  // The worker was replaced: the next compile works.
  ASSERT_COMPILED(Compile(kVertexShader, "main", "vs_5_0"));
}

TEST(HlslIsolation, IsolatedAndInProcessResultsAreIdentical) {
  const std::pair<const char*, const char*> shaders[] = {
      {kPixelResources, "ps_5_0"},
      {kVertexResources, "vs_5_0"},
      {kComputeShader, "cs_5_0"},
      {"float4 gTint; float4 main() : SV_Target { return gTint * missing; }", "ps_5_0"},
  };
  for (const auto& [source, profile] : shaders) {
    CompileRequest request{source, "same.hlsl", "main", profile, {{"A", "1"}}, {"/nonexistent"}};
    const CompileResult isolated = CompileHlsl(request);
    request.isolate = false;
    const CompileResult inProcess = CompileHlsl(request);
    EXPECT_TRUE(isolated == inProcess) << profile << "\n" << isolated.FormatErrors() << inProcess.FormatErrors();
  }
}

TEST(HlslIsolation, RelativeIncludesFollowTheCallersCurrentDirectory) {
  TempDir dir;
  dir.Write("inc/value.h", "static const float VALUE = 3;\n");
  const fs::path previous = fs::current_path();
  fs::current_path(dir.path());  // after the worker was started by earlier tests
  CompileRequest request{"#include \"value.h\"\nfloat4 main() : SV_Target { return VALUE; }\n",
                         "main.hlsl",
                         "main",
                         "ps_5_0",
                         {},
                         {"inc"}};
  const CompileResult r = CompileHlsl(request);
  fs::current_path(previous);
  ASSERT_COMPILED(r);
}

TEST(HlslIsolation, NothingIsPrinted) {
  ::testing::internal::CaptureStdout();
  ::testing::internal::CaptureStderr();
  if (hlsl::CrashIsolationAvailable()) {
    for (const char* source : kCrashingSources) Compile(source, "main", "vs_5_0");
  }
  for (bool isolate : {true, false}) {
    CompileRequest request{"float4 main() : SV_Target { return undefined; }", "quiet.hlsl", "main", "ps_5_0", {}, {}};
    request.isolate = isolate;
    EXPECT_FALSE(CompileHlsl(request).ok);
    request.source = kPixelResources;
    EXPECT_TRUE(CompileHlsl(request).ok);
  }
  EXPECT_EQ(::testing::internal::GetCapturedStdout(), "");
  EXPECT_EQ(::testing::internal::GetCapturedStderr(), "");
}

// ---------------------------------------------------------------------------
// Threads

TEST(HlslThreads, ConcurrentCompilesAgree) {
  const CompileResult reference = Compile(kPixelResources, "main", "ps_5_0");
  ASSERT_COMPILED(reference);
  constexpr int kThreads = 8, kRepeats = 5;
  std::vector<CompileResult> results(kThreads * kRepeats);
  std::vector<std::thread> threads;
  for (int t = 0; t < kThreads; ++t) {
    threads.emplace_back([&results, t] {
      for (int repeat = 0; repeat < kRepeats; ++repeat) {
        CompileRequest request{kPixelResources, "test.hlsl", "main", "ps_5_0", {}, {}};
        request.isolate = t % 2 == 0;  // in-process compiles and worker forks interleave
        results[t * kRepeats + repeat] = CompileHlsl(request);
      }
    });
  }
  for (auto& t : threads) t.join();
  for (const auto& result : results) EXPECT_TRUE(result == reference) << result.FormatErrors();
}

}  // namespace
