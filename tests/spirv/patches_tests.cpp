// StripHlslDecorations, RemapLocations, RebaseInstanceIndex, AddPointSizeOutput.
#include <gtest/gtest.h>

#include <bit>
#include <map>
#include <set>
#include <spirv/unified1/spirv.hpp11>

#include "shaders.h"
#include "spirv/patches.h"
#include "spirv/reflection.h"
#include "test_compiler.h"
#include "test_util.h"

namespace {

using namespace rhi::spirv;
using spirv_test::Compile;
using spirv_test::CountOpcode;
using spirv_test::InstructionsWithOpcode;
namespace shaders = spirv_test::shaders;

constexpr uint32_t Op(spv::Op op) { return static_cast<uint32_t>(op); }
constexpr uint32_t Dec(spv::Decoration d) { return static_cast<uint32_t>(d); }

std::vector<uint32_t> Ok(const WordsResult& result) {
  EXPECT_TRUE(result.ok()) << result.error;
  return result.value;
}

Reflection ReflectOrDie(const std::vector<uint32_t>& words) {
  Result<Reflection> r = Reflect(words);
  EXPECT_TRUE(r.ok()) << r.error;
  return std::move(r.value);
}

// Modules both as glslang emits them and after the legalization the product compiler runs.
class PatchesOnBothForms : public ::testing::TestWithParam<bool> {
 protected:
  std::vector<uint32_t> Build(const char* source, spirv_test::Stage stage) {
    std::vector<uint32_t> words = Compile(source, stage);
    return GetParam() ? spirv_test::Legalize(words) : words;
  }
};
INSTANTIATE_TEST_SUITE_P(Spirv, PatchesOnBothForms, ::testing::Values(false, true),
                         [](const auto& info) { return info.param ? "Legalized" : "Glslang"; });

// --- StripHlslDecorations ----------------------------------------------------

TEST_P(PatchesOnBothForms, StripRemovesSemanticsAndExtension) {
  const std::vector<uint32_t> words = Build(shaders::kVertex, spirv_test::Stage::Vertex);
  ASSERT_GT(CountOpcode(words, Op(spv::Op::OpDecorateString)), 0u);
  const std::vector<uint32_t> stripped = Ok(StripHlslDecorations(words));
  EXPECT_EQ(CountOpcode(stripped, Op(spv::Op::OpDecorateString)), 0u);
  EXPECT_EQ(CountOpcode(stripped, Op(spv::Op::OpMemberDecorateString)), 0u);
  EXPECT_EQ(CountOpcode(stripped, Op(spv::Op::OpExtension)), 0u);
  EXPECT_EQ(CountOpcode(stripped, Op(spv::Op::OpDecorate)), CountOpcode(words, Op(spv::Op::OpDecorate)))
      << "Location and BuiltIn decorations stay";
  EXPECT_VALID_SPIRV(stripped);
  // Reflection afterwards still knows built-ins, but not the user semantics.
  const Reflection r = ReflectOrDie(stripped);
  EXPECT_NE(r.FindOutput("SV_POSITION", 0), nullptr);
  EXPECT_EQ(r.FindOutput("TEXCOORD", 0), nullptr);
}

TEST(SpirvStrip, RemovesCounterBuffer) {
  const char* source = R"(
AppendStructuredBuffer<float4> queue : register(u1);
float4 main(float4 c : COLOR0) : SV_Target { queue.Append(c); return c; })";
  const std::vector<uint32_t> words = Compile(source, spirv_test::Stage::Pixel);
  ASSERT_EQ(CountOpcode(words, Op(spv::Op::OpDecorateId)), 1u) << "glslang links the counter buffer";
  const std::vector<uint32_t> stripped = Ok(StripHlslDecorations(words));
  EXPECT_EQ(CountOpcode(stripped, Op(spv::Op::OpDecorateId)), 0u);
  EXPECT_VALID_SPIRV(stripped);
}

// glslang puts a hidden counter at the lowest free binding; the backend finds
// it by its UAV's binding instead.
TEST(SpirvHiddenCounters, MoveToTheirUavBindingPlusTheOffset) {
  const char* source = R"(
AppendStructuredBuffer<float4> queue : register(u3);
RWStructuredBuffer<uint> slots : register(u1);
RWStructuredBuffer<uint> plain : register(u2);
float4 main(float4 c : COLOR0) : SV_Target { queue.Append(c); slots[slots.IncrementCounter()] = plain[0]; return c; })";
  const std::vector<uint32_t> words = Compile(source, spirv_test::Stage::Pixel);
  const std::vector<uint32_t> moved = Ok(MoveHiddenCounters(words, 100));
  EXPECT_VALID_SPIRV(moved);
  const Reflection r = ReflectOrDie(moved);
  const auto named = [&r](std::string_view name) {
    for (const DescriptorBinding& b : r.bindings)
      if (b.name == name) return b;
    ADD_FAILURE() << "no binding " << name;
    return DescriptorBinding{};
  };
  for (const char* uav : {"queue", "slots"}) {
    const DescriptorBinding counted = named(uav);
    const DescriptorBinding counter = named(std::string(uav) + "@count");
    EXPECT_EQ(counter.counterOf, counted.variableId) << uav;
    EXPECT_EQ(counter.binding, counted.binding + 100) << uav;
    EXPECT_EQ(counted.counterOf, 0u) << uav;
  }
  EXPECT_EQ(named("plain").counterOf, 0u);
  // A module without counters comes back unchanged.
  const std::vector<uint32_t> none = Compile("float4 main(float4 c : COLOR0) : SV_Target { return c; }",
                                             spirv_test::Stage::Pixel);
  EXPECT_EQ(Ok(MoveHiddenCounters(none, 100)), none);
}

TEST(SpirvStrip, RemovesUserTypeAndGoogleExtensions) {
  const std::vector<uint32_t> words = spirv_test::Assemble(R"(
               OpCapability Shader
               OpExtension "SPV_GOOGLE_decorate_string"
               OpExtension "SPV_GOOGLE_hlsl_functionality1"
               OpExtension "SPV_GOOGLE_user_type"
               OpMemoryModel Logical GLSL450
               OpEntryPoint Fragment %main "main" %out %tex
               OpExecutionMode %main OriginUpperLeft
               OpDecorate %out Location 0
               OpDecorateString %out UserSemantic "SV_TARGET"
               OpDecorate %tex DescriptorSet 0
               OpDecorate %tex Binding 0
               OpDecorateString %tex UserTypeGOOGLE "texture2d:<float4>"
       %void = OpTypeVoid
         %fn = OpTypeFunction %void
      %float = OpTypeFloat 32
    %v4float = OpTypeVector %float 4
      %image = OpTypeImage %float 2D 0 0 0 1 Unknown
  %ptr_image = OpTypePointer UniformConstant %image
        %tex = OpVariable %ptr_image UniformConstant
    %ptr_out = OpTypePointer Output %v4float
        %out = OpVariable %ptr_out Output
       %main = OpFunction %void None %fn
      %label = OpLabel
               OpReturn
               OpFunctionEnd
)");
  const std::vector<uint32_t> stripped = Ok(StripHlslDecorations(words));
  EXPECT_EQ(CountOpcode(stripped, Op(spv::Op::OpExtension)), 0u);
  EXPECT_EQ(CountOpcode(stripped, Op(spv::Op::OpDecorateString)), 0u);
  EXPECT_EQ(CountOpcode(stripped, Op(spv::Op::OpDecorate)), 3u);
  EXPECT_VALID_SPIRV(stripped);
}

// --- RemapLocations ----------------------------------------------------------

TEST(SpirvRemapLocations, RewritesOnlyTheRequestedStorageClass) {
  const std::vector<uint32_t> words = Compile(shaders::kVertex, spirv_test::Stage::Vertex);
  const Reflection before = ReflectOrDie(words);
  // Outputs TEXCOORD0 @0 and COLOR1 @1 swap and move; inputs stay.
  const std::vector<uint32_t> remapped = Ok(RemapLocations(words, StorageClass::Output, {{0, 4}, {1, 0}}));
  const Reflection after = ReflectOrDie(remapped);
  EXPECT_EQ(after.FindOutput("TEXCOORD", 0)->location, 4u);
  EXPECT_EQ(after.FindOutput("COLOR", 1)->location, 0u);
  for (size_t i = 0; i < before.inputs.size(); ++i) EXPECT_EQ(after.inputs[i].location, before.inputs[i].location);
  EXPECT_VALID_SPIRV(remapped);

  const std::vector<uint32_t> inputs = Ok(RemapLocations(words, StorageClass::Input, {{3, 9}}));
  const Reflection in = ReflectOrDie(inputs);
  EXPECT_EQ(in.FindInput("TEXCOORD", 1)->location, 9u);
  EXPECT_EQ(in.FindInput("POSITION", 0)->location, 0u);
  EXPECT_EQ(in.FindOutput("COLOR", 1)->location, 1u) << "outputs untouched";
}

TEST(SpirvRemapLocations, EmptyMapIsIdentity) {
  const std::vector<uint32_t> words = Compile(shaders::kPixel, spirv_test::Stage::Pixel);
  EXPECT_EQ(Ok(RemapLocations(words, StorageClass::Output, {})), words);
}

// --- RebaseInstanceIndex ----------------------------------------------------

TEST_P(PatchesOnBothForms, RebaseInstanceIndexSubtractsBaseInstance) {
  const std::vector<uint32_t> words = Build(shaders::kVertexInstanced, spirv_test::Stage::Vertex);
  const std::vector<uint32_t> patched = Ok(RebaseInstanceIndex(words));
  EXPECT_VALID_SPIRV(patched);

  uint32_t instanceIndex = 0, baseInstance = 0;
  for (const auto& d : InstructionsWithOpcode(patched, Op(spv::Op::OpDecorate))) {
    if (d.operand(1) != Dec(spv::Decoration::BuiltIn)) continue;
    if (d.operand(2) == static_cast<uint32_t>(spv::BuiltIn::InstanceIndex)) instanceIndex = d.operand(0);
    if (d.operand(2) == static_cast<uint32_t>(spv::BuiltIn::BaseInstance)) baseInstance = d.operand(0);
  }
  ASSERT_NE(instanceIndex, 0u);
  ASSERT_NE(baseInstance, 0u);
  const auto entry = InstructionsWithOpcode(patched, Op(spv::Op::OpEntryPoint)).at(0);
  EXPECT_NE(std::find(entry.words.begin() + 3, entry.words.end(), baseInstance), entry.words.end())
      << "BaseInstance is in the entry point's interface";
  bool hasDrawParameters = false;
  for (const auto& c : InstructionsWithOpcode(patched, Op(spv::Op::OpCapability)))
    hasDrawParameters = hasDrawParameters || c.operand(0) == static_cast<uint32_t>(spv::Capability::DrawParameters);
  EXPECT_TRUE(hasDrawParameters);

  // Every load of InstanceIndex feeds an OpISub by a load of BaseInstance,
  // and the OpISub took over the original load's result id.
  std::map<uint32_t, uint32_t> loads;  // result -> pointer
  for (const auto& l : InstructionsWithOpcode(patched, Op(spv::Op::OpLoad))) loads[l.operand(1)] = l.operand(2);
  std::set<uint32_t> originalLoads;
  for (const auto& l : InstructionsWithOpcode(words, Op(spv::Op::OpLoad)))
    if (l.operand(2) == instanceIndex) originalLoads.insert(l.operand(1));
  ASSERT_FALSE(originalLoads.empty());
  size_t subtractions = 0;
  for (const auto& sub : InstructionsWithOpcode(patched, Op(spv::Op::OpISub))) {
    if (!originalLoads.count(sub.operand(1))) continue;
    EXPECT_EQ(loads[sub.operand(2)], instanceIndex);
    EXPECT_EQ(loads[sub.operand(3)], baseInstance);
    ++subtractions;
  }
  EXPECT_EQ(subtractions, originalLoads.size());
}

TEST(SpirvRebaseInstanceIndex, NoOpWithoutInstanceIndex) {
  const std::vector<uint32_t> words = Compile(shaders::kVertex, spirv_test::Stage::Vertex);
  EXPECT_EQ(Ok(RebaseInstanceIndex(words)), words);
}

// --- AddPointSizeOutput -------------------------------------------------------

// Stores of the float constant 1.0 into PointSize (a variable or a block member).
size_t PointSizeStoresOfOne(const std::vector<uint32_t>& words) {
  uint32_t one = 0;
  for (const auto& c : InstructionsWithOpcode(words, Op(spv::Op::OpConstant)))
    if (c.operand(2) == std::bit_cast<uint32_t>(1.0f)) one = c.operand(1);
  const Reflection r = ReflectOrDie(words);
  const InterfaceVariable* pointSize = nullptr;
  for (const InterfaceVariable& v : r.outputs)
    if (v.builtIn == static_cast<uint32_t>(spv::BuiltIn::PointSize)) pointSize = &v;
  if (!pointSize || !one) return 0;
  std::set<uint32_t> pointers = {pointSize->variableId};
  if (pointSize->member) {
    pointers.clear();
    for (const auto& chain : InstructionsWithOpcode(words, Op(spv::Op::OpAccessChain)))
      if (chain.operand(2) == pointSize->variableId && chain.operandCount() == 4) pointers.insert(chain.operand(1));
  }
  size_t stores = 0;
  for (const auto& s : InstructionsWithOpcode(words, Op(spv::Op::OpStore)))
    if (pointers.count(s.operand(0)) && s.operand(1) == one) ++stores;
  return stores;
}

TEST_P(PatchesOnBothForms, PointSizeForVertexShader) {
  const std::vector<uint32_t> words = Build(shaders::kVertex, spirv_test::Stage::Vertex);
  const std::vector<uint32_t> patched = Ok(AddPointSizeOutput(words));
  EXPECT_VALID_SPIRV(patched);
  const Reflection r = ReflectOrDie(patched);
  EXPECT_TRUE(r.hasPointSizeOutput);
  EXPECT_TRUE(r.writesPointSize);
  EXPECT_EQ(PointSizeStoresOfOne(patched), 1u);
  EXPECT_EQ(Ok(AddPointSizeOutput(patched)), patched) << "a written PointSize is left alone";
}

TEST_P(PatchesOnBothForms, PointSizeForGeometryShaderBeforeEveryEmit) {
  const std::vector<uint32_t> words = Build(shaders::kGeometry, spirv_test::Stage::Geometry);
  const std::vector<uint32_t> patched = Ok(AddPointSizeOutput(words));
  EXPECT_VALID_SPIRV(patched);
  const size_t emits = CountOpcode(patched, Op(spv::Op::OpEmitVertex));
  ASSERT_GT(emits, 0u);
  EXPECT_EQ(PointSizeStoresOfOne(patched), emits);
  // Each emit is directly preceded by the store.
  const auto parsed = Module::Parse(patched);
  for (size_t i = 1; i < parsed->size(); ++i) {
    if ((*parsed)[i].opcode() == Op(spv::Op::OpEmitVertex)) {
      EXPECT_EQ((*parsed)[i - 1].opcode(), Op(spv::Op::OpStore));
    }
  }
  bool geometryPointSize = false;
  for (const auto& c : InstructionsWithOpcode(patched, Op(spv::Op::OpCapability)))
    geometryPointSize = geometryPointSize || c.operand(0) == static_cast<uint32_t>(spv::Capability::GeometryPointSize);
  EXPECT_TRUE(geometryPointSize);
}

TEST(SpirvPointSize, WritesTheExistingBlockMember) {
  const std::vector<uint32_t> words =
      Compile(shaders::kGlslVertex, spirv_test::Stage::Vertex, "main", spirv_test::Language::Glsl);
  const std::vector<uint32_t> patched = Ok(AddPointSizeOutput(words));
  EXPECT_VALID_SPIRV(patched);
  EXPECT_EQ(CountOpcode(patched, Op(spv::Op::OpVariable)), CountOpcode(words, Op(spv::Op::OpVariable)))
      << "gl_PerVertex already has gl_PointSize";
  EXPECT_EQ(PointSizeStoresOfOne(patched), 1u);
  EXPECT_TRUE(ReflectOrDie(patched).writesPointSize);
}

TEST(SpirvPointSize, AppendsAMemberToABlockWithoutOne) {
  const std::vector<uint32_t> words =
      Compile(shaders::kGlslVertexPositionOnly, spirv_test::Stage::Vertex, "main", spirv_test::Language::Glsl);
  ASSERT_FALSE(ReflectOrDie(words).hasPointSizeOutput);
  const std::vector<uint32_t> patched = Ok(AddPointSizeOutput(words));
  EXPECT_VALID_SPIRV(patched);
  const Reflection r = ReflectOrDie(patched);
  const InterfaceVariable* pointSize = nullptr;
  for (const InterfaceVariable& v : r.outputs)
    if (v.builtIn == static_cast<uint32_t>(spv::BuiltIn::PointSize)) pointSize = &v;
  ASSERT_NE(pointSize, nullptr);
  EXPECT_EQ(pointSize->member, 1u) << "appended after gl_Position";
  EXPECT_EQ(pointSize->variableId, r.FindOutput("SV_POSITION", 0)->variableId);
  EXPECT_EQ(PointSizeStoresOfOne(patched), 1u);
}

TEST(SpirvPointSize, LeavesAWrittenPointSizeAlone) {
  const std::vector<uint32_t> words =
      Compile(shaders::kGlslVertexPointSize, spirv_test::Stage::Vertex, "main", spirv_test::Language::Glsl);
  EXPECT_EQ(Ok(AddPointSizeOutput(words)), words);
}

TEST(SpirvPointSize, RefusesPixelShaders) {
  const WordsResult result = AddPointSizeOutput(Compile(shaders::kPixel, spirv_test::Stage::Pixel));
  EXPECT_NE(result.error.find("PS"), std::string::npos) << result.error;
}

}  // namespace
