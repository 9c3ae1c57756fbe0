// D3D11 stream output: ValidateSoDeclaration's rules and messages, and the
// transform-feedback SPIR-V ApplyStreamOutput produces.
#include <gtest/gtest.h>

#include <map>
#include <set>
#include <spirv/unified1/spirv.hpp11>

#include "shaders.h"
#include "spirv/stream_output.h"
#include "test_compiler.h"
#include "test_util.h"

namespace {

using namespace rhi::spirv;
using rhi::SO_DECLARATION_ENTRY;
using rhi::UINT;
using spirv_test::Compile;
using spirv_test::CountOpcode;
using spirv_test::DecorationOf;
using spirv_test::InstructionsWithOpcode;
namespace shaders = spirv_test::shaders;

constexpr uint32_t Op(spv::Op op) { return static_cast<uint32_t>(op); }
constexpr uint32_t Dec(spv::Decoration d) { return static_cast<uint32_t>(d); }

Reflection ReflectOrDie(const std::vector<uint32_t>& words) {
  Result<Reflection> r = Reflect(words);
  EXPECT_TRUE(r.ok()) << r.error;
  return std::move(r.value);
}

// --- ValidateSoDeclaration ---------------------------------------------------

InterfaceVariable Output(const char* name, uint32_t index, uint32_t components, uint32_t stream = 0) {
  InterfaceVariable v;
  v.semanticName = name;
  v.semanticIndex = index;
  v.componentCount = components;
  v.scalarKind = ScalarKind::Float;
  v.scalarWidth = 32;
  v.stream = stream;
  return v;
}

// A GS with float4 SV_Position, float2 TEXCOORD0, float4 COLOR0 on stream 0
// and float3 NORMAL0 on stream 1.
Reflection GeometryOutputs() {
  Reflection r;
  r.stage = Stage::Geometry;
  r.outputs = {Output("SV_POSITION", 0, 4), Output("TEXCOORD", 0, 2), Output("COLOR", 0, 4), Output("NORMAL", 0, 3, 1)};
  return r;
}

std::string Validate(std::vector<SO_DECLARATION_ENTRY> entries, std::vector<UINT> strides,
                     UINT rasterizedStream = 0, const Reflection& shader = GeometryOutputs()) {
  return ValidateSoDeclaration(entries.data(), static_cast<UINT>(entries.size()), strides.data(),
                               static_cast<UINT>(strides.size()), rasterizedStream, shader);
}

TEST(SoValidation, AcceptsAValidDeclaration) {
  EXPECT_EQ(Validate({{0, "SV_Position", 0, 0, 4, 0},
                      {0, nullptr, 0, 0, 7, 0},  // gaps may exceed 4 components
                      {0, "texcoord", 0, 1, 1, 0},
                      {0, "COLOR", 0, 0, 4, 1},
                      {1, "NORMAL", 0, 0, 3, 2}},
                     {48, 16, 12}, rhi::SO_NO_RASTERIZED_STREAM),
            "");
  EXPECT_EQ(Validate({{0, "COLOR", 0, 0, 4, 0}}, {}, 3), "") << "NumStrides 0: strides are packed";
}

TEST(SoValidation, UnknownSemantic) {
  EXPECT_EQ(Validate({{0, "SV_Position", 0, 0, 4, 0}, {0, "FOO", 1, 0, 4, 0}}, {32}),
            "SO declaration entry 1: unknown semantic \"FOO1\" (not an output of the GS)");
  EXPECT_EQ(Validate({{0, "TEXCOORD", 1, 0, 2, 0}}, {8}),
            "SO declaration entry 0: unknown semantic \"TEXCOORD1\" (not an output of the GS)");
  EXPECT_EQ(Validate({{1, "COLOR", 0, 0, 4, 0}}, {16}),
            "SO declaration entry 0: unknown semantic \"COLOR0\" (not an output of the GS in stream 1)");
}

TEST(SoValidation, OverlappingComponents) {
  EXPECT_EQ(Validate({{0, "SV_POSITION", 0, 0, 3, 0}, {0, "SV_Position", 0, 2, 2, 1}}, {12, 8}),
            "SO declaration entry 1: component z of \"SV_POSITION0\" is already captured by entry 0");
  EXPECT_EQ(Validate({{0, "SV_POSITION", 0, 0, 2, 0}, {0, "SV_POSITION", 0, 2, 2, 0}}, {16}), "")
      << "disjoint components of one output are fine";
}

TEST(SoValidation, ComponentOutOfRange) {
  EXPECT_EQ(Validate({{0, "COLOR", 0, 3, 2, 0}}, {8}),
            "SO declaration entry 0: StartComponent (3) + ComponentCount (2) exceeds 4");
  EXPECT_EQ(Validate({{0, "TEXCOORD", 0, 1, 2, 0}}, {8}),
            "SO declaration entry 0: \"TEXCOORD0\" has 2 component(s); StartComponent (1) + ComponentCount (2) "
            "exceeds them");
  EXPECT_EQ(Validate({{0, "COLOR", 0, 0, 0, 0}}, {8}), "SO declaration entry 0: ComponentCount (0) must be 1..4");
  EXPECT_EQ(Validate({{0, "COLOR", 0, 0, 5, 0}}, {20}), "SO declaration entry 0: ComponentCount (5) must be 1..4");
}

TEST(SoValidation, Strides) {
  EXPECT_EQ(Validate({{0, "COLOR", 0, 0, 4, 0}}, {12}),
            "SO declaration: pBufferStrides[0] (12) is smaller than the 16 bytes the declaration writes per vertex "
            "to slot 0");
  EXPECT_EQ(Validate({{0, "COLOR", 0, 0, 4, 0}}, {18}), "SO declaration: pBufferStrides[0] (18) is not a multiple of 4");
  EXPECT_EQ(Validate({{0, "COLOR", 0, 0, 4, 0}}, {2052}),
            "SO declaration: pBufferStrides[0] (2052) exceeds 2048 (D3D11_SO_BUFFER_MAX_STRIDE_IN_BYTES)");
  EXPECT_EQ(Validate({{0, "COLOR", 0, 0, 4, 0}, {0, nullptr, 0, 0, 2, 0}}, {20}),
            "SO declaration: pBufferStrides[0] (20) is smaller than the 24 bytes the declaration writes per vertex "
            "to slot 0")
      << "gaps take room in the vertex record";
  EXPECT_EQ(Validate({{0, "COLOR", 0, 0, 4, 1}}, {16}), "SO declaration: OutputSlot 1 is used but NumStrides is 1");
}

TEST(SoValidation, OneStreamPerSlot) {
  EXPECT_EQ(Validate({{0, "COLOR", 0, 0, 4, 0}, {1, "NORMAL", 0, 0, 3, 0}}, {28}),
            "SO declaration entry 1: OutputSlot 0 already holds stream 0 (entry 0), not stream 1; an output slot "
            "takes one stream");
}

TEST(SoValidation, RasterizedStream) {
  EXPECT_EQ(Validate({{0, "COLOR", 0, 0, 4, 0}}, {16}, 4),
            "SO declaration: RasterizedStream (4) must be less than 4 (D3D11_SO_STREAM_COUNT) or "
            "D3D11_SO_NO_RASTERIZED_STREAM");
  EXPECT_EQ(Validate({{0, "COLOR", 0, 0, 4, 0}}, {16}, rhi::SO_NO_RASTERIZED_STREAM), "");
}

TEST(SoValidation, StreamAndSlotRanges) {
  EXPECT_EQ(Validate({{4, "COLOR", 0, 0, 4, 0}}, {16}),
            "SO declaration entry 0: Stream (4) must be less than 4 (D3D11_SO_STREAM_COUNT)");
  EXPECT_EQ(Validate({{0, "COLOR", 0, 0, 4, 4}}, {16}),
            "SO declaration entry 0: OutputSlot (4) must be less than 4 (D3D11_SO_BUFFER_SLOT_COUNT)");
  Reflection vs = GeometryOutputs();
  vs.stage = Stage::Vertex;
  EXPECT_EQ(Validate({{1, "NORMAL", 0, 0, 3, 0}}, {12}, 0, vs),
            "SO declaration entry 0: Stream (1) needs a geometry shader; a VS has only stream 0");
  Reflection ps = GeometryOutputs();
  ps.stage = Stage::Pixel;
  EXPECT_EQ(Validate({{0, "COLOR", 0, 0, 4, 0}}, {16}, 0, ps),
            "SO declaration: stream output needs a VS, DS or GS, not a PS");
}

TEST(SoValidation, Gaps) {
  EXPECT_EQ(Validate({{0, "COLOR", 0, 0, 4, 0}, {0, nullptr, 0, 1, 2, 0}}, {28}),
            "SO declaration entry 1: a gap (SemanticName NULL) must have StartComponent 0, not 1");
  EXPECT_EQ(Validate({{0, "COLOR", 0, 0, 4, 0}, {0, nullptr, 2, 0, 2, 0}}, {28}),
            "SO declaration entry 1: a gap (SemanticName NULL) must have SemanticIndex 0, not 2");
  EXPECT_EQ(Validate({{0, "COLOR", 0, 0, 4, 0}, {0, nullptr, 0, 0, 0, 0}}, {28}),
            "SO declaration entry 1: a gap (SemanticName NULL) must have ComponentCount >= 1");
  EXPECT_EQ(Validate({{0, "COLOR", 0, 0, 4, 0}, {0, nullptr, 0, 0, 2, 1}}, {16, 8}),
            "SO declaration: output slot 1 contains only gaps");
}

TEST(SoValidation, EntryCountLimit) {
  std::vector<SO_DECLARATION_ENTRY> entries(kSoMaxEntries + 1, SO_DECLARATION_ENTRY{0, nullptr, 0, 0, 1, 0});
  EXPECT_EQ(Validate(entries, {}),
            "SO declaration: NumEntries (513) exceeds 512 (D3D11_SO_STREAM_COUNT * D3D11_SO_OUTPUT_COMPONENT_COUNT)");
}

TEST(SoValidation, AgainstACompiledGeometryShader) {
  const Reflection gs = ReflectOrDie(Compile(shaders::kGeometry, spirv_test::Stage::Geometry));
  EXPECT_EQ(Validate({{0, "SV_POSITION", 0, 0, 4, 0}, {0, "COLOR", 0, 0, 4, 0}}, {32}, 0, gs), "");
  EXPECT_EQ(Validate({{0, "NORMAL", 0, 0, 3, 0}}, {12}, 0, gs),
            "SO declaration entry 0: unknown semantic \"NORMAL0\" (not an output of the GS)");
}

TEST(SoBufferStrides, GivenOrPacked) {
  const std::vector<SO_DECLARATION_ENTRY> entries = {
      {0, "A", 0, 0, 4, 0}, {0, nullptr, 0, 0, 3, 0}, {0, "B", 0, 0, 2, 2}};
  EXPECT_EQ(SoBufferStrides(entries, {}), (std::array<UINT, 4>{28, 0, 8, 0}));
  const std::vector<UINT> strides = {64, 4, 12};
  EXPECT_EQ(SoBufferStrides(entries, strides), (std::array<UINT, 4>{64, 4, 12, 0}));
}

// --- ApplyStreamOutput ---------------------------------------------------------

struct XfbVariable {
  uint32_t id = 0, buffer = 0, stride = 0, offset = 0, location = 0, components = 0;
  std::optional<uint32_t> stream;
};

// The transform-feedback variables of a module, keyed by (XfbBuffer, Offset).
std::map<std::pair<uint32_t, uint32_t>, XfbVariable> XfbVariables(const std::vector<uint32_t>& words) {
  const auto module = Module::Parse(words);
  std::map<std::pair<uint32_t, uint32_t>, XfbVariable> found;
  for (const auto& d : InstructionsWithOpcode(words, Op(spv::Op::OpDecorate))) {
    if (d.operand(1) != Dec(spv::Decoration::XfbBuffer)) continue;
    XfbVariable v;
    v.id = d.operand(0);
    v.buffer = d.operand(2);
    v.stride = DecorationOf(words, v.id, Dec(spv::Decoration::XfbStride)).value_or(~0u);
    v.offset = DecorationOf(words, v.id, Dec(spv::Decoration::Offset)).value_or(~0u);
    v.location = DecorationOf(words, v.id, Dec(spv::Decoration::Location)).value_or(~0u);
    v.stream = DecorationOf(words, v.id, Dec(spv::Decoration::Stream));
    const auto* pointer = module->Definition(module->Definition(v.id)->resultType());
    const auto* type = module->Definition(pointer->operand(2));
    v.components = type->opcode() == Op(spv::Op::OpTypeVector) ? type->operand(2) : 1;
    found[{v.buffer, v.offset}] = v;
  }
  return found;
}

size_t StoresTo(const std::vector<uint32_t>& words, uint32_t variable) {
  size_t n = 0;
  for (const auto& s : InstructionsWithOpcode(words, Op(spv::Op::OpStore))) n += s.operand(0) == variable;
  return n;
}

bool HasCapability(const std::vector<uint32_t>& words, spv::Capability capability) {
  for (const auto& c : InstructionsWithOpcode(words, Op(spv::Op::OpCapability)))
    if (c.operand(0) == static_cast<uint32_t>(capability)) return true;
  return false;
}

bool HasXfbMode(const std::vector<uint32_t>& words) {
  for (const auto& m : InstructionsWithOpcode(words, Op(spv::Op::OpExecutionMode)))
    if (m.operand(1) == static_cast<uint32_t>(spv::ExecutionMode::Xfb)) return true;
  return false;
}

// The component literals of every OpVectorShuffle, and the indices of every OpCompositeExtract.
std::vector<std::vector<uint32_t>> Shuffles(const std::vector<uint32_t>& words) {
  std::vector<std::vector<uint32_t>> out;
  for (const auto& s : InstructionsWithOpcode(words, Op(spv::Op::OpVectorShuffle)))
    out.emplace_back(s.operands().begin() + 4, s.operands().end());
  return out;
}

class StreamOutput : public ::testing::TestWithParam<bool> {
 protected:
  std::vector<uint32_t> Build(const char* source, spirv_test::Stage stage) {
    std::vector<uint32_t> words = Compile(source, stage);
    return GetParam() ? spirv_test::Legalize(words) : words;
  }
};
INSTANTIATE_TEST_SUITE_P(Spirv, StreamOutput, ::testing::Values(false, true),
                         [](const auto& info) { return info.param ? "Legalized" : "Glslang"; });

TEST_P(StreamOutput, GeometryShaderTwoSlotsGapAndSubsets) {
  const std::vector<uint32_t> words = Build(shaders::kGeometry, spirv_test::Stage::Geometry);
  const Reflection gs = ReflectOrDie(words);
  const std::vector<SO_DECLARATION_ENTRY> entries = {
      {0, "SV_POSITION", 0, 0, 4, 0},  // slot 0, bytes 0..15
      {0, nullptr, 0, 0, 2, 0},        // slot 0, gap 16..23
      {0, "TEXCOORD", 0, 1, 1, 0},     // slot 0, TEXCOORD0.y at 24
      {0, "COLOR", 0, 1, 2, 1},        // slot 1, COLOR0.yz at 0
      {0, "TEXCOORD", 0, 0, 1, 1},     // slot 1, TEXCOORD0.x at 8
  };
  const std::vector<UINT> strides = {32, 16};
  const WordsResult result = ApplyStreamOutput(words, gs, entries, strides);
  ASSERT_TRUE(result.ok()) << result.error;
  const std::vector<uint32_t>& out = result.value;
  EXPECT_VALID_SPIRV(out);

  const auto xfb = XfbVariables(out);
  ASSERT_EQ(xfb.size(), 4u);
  struct Expected { uint32_t buffer, offset, stride, components; };
  const Expected expected[] = {{0, 0, 32, 4}, {0, 24, 32, 1}, {1, 0, 16, 2}, {1, 8, 16, 1}};
  std::set<uint32_t> locations;
  const size_t emits = CountOpcode(out, Op(spv::Op::OpEmitVertex));
  ASSERT_GT(emits, 0u);
  for (const Expected& e : expected) {
    ASSERT_TRUE(xfb.count({e.buffer, e.offset})) << "buffer " << e.buffer << " offset " << e.offset;
    const XfbVariable& v = xfb.at({e.buffer, e.offset});
    EXPECT_EQ(v.stride, e.stride);
    EXPECT_EQ(v.components, e.components);
    EXPECT_FALSE(v.stream.has_value());
    EXPECT_GE(v.location, 2u) << "the GS's own outputs use locations 0 and 1";
    locations.insert(v.location);
    EXPECT_EQ(StoresTo(out, v.id), emits) << "one copy before every emit";
  }
  EXPECT_EQ(locations.size(), 4u) << "each capture has its own location";
  EXPECT_TRUE(HasCapability(out, spv::Capability::TransformFeedback));
  EXPECT_FALSE(HasCapability(out, spv::Capability::GeometryStreams));
  EXPECT_TRUE(HasXfbMode(out));
  const auto shuffles = Shuffles(out);
  EXPECT_NE(std::find(shuffles.begin(), shuffles.end(), std::vector<uint32_t>{1, 2}), shuffles.end()) << "COLOR0.yz";
  std::set<uint32_t> extracted;
  for (const auto& x : InstructionsWithOpcode(out, Op(spv::Op::OpCompositeExtract)))
    if (x.operandCount() == 4) extracted.insert(x.operand(3));
  EXPECT_TRUE(extracted.count(1) && extracted.count(0)) << "TEXCOORD0.y and TEXCOORD0.x";
  // The original outputs are still there for the rasterizer.
  EXPECT_EQ(ReflectOrDie(out).outputs.size(), gs.outputs.size() + 4);
}

TEST_P(StreamOutput, VertexShaderOnly) {
  const std::vector<uint32_t> words = Build(shaders::kVertex, spirv_test::Stage::Vertex);
  const Reflection vs = ReflectOrDie(words);
  const std::vector<SO_DECLARATION_ENTRY> entries = {
      {0, "SV_Position", 0, 0, 4, 0}, {0, "TEXCOORD", 0, 0, 2, 0}, {0, "COLOR", 1, 3, 1, 0}};
  const WordsResult result = ApplyStreamOutput(words, vs, entries, {});  // NumStrides 0: packed, 28 bytes
  ASSERT_TRUE(result.ok()) << result.error;
  const std::vector<uint32_t>& out = result.value;
  EXPECT_VALID_SPIRV(out);

  const auto xfb = XfbVariables(out);
  ASSERT_EQ(xfb.size(), 3u);
  EXPECT_EQ(xfb.at({0, 0}).components, 4u);
  EXPECT_EQ(xfb.at({0, 16}).components, 2u);
  EXPECT_EQ(xfb.at({0, 24}).components, 1u);
  for (const auto& [key, v] : xfb) {
    EXPECT_EQ(v.stride, 28u);
    EXPECT_GE(v.location, 2u);
    EXPECT_EQ(StoresTo(out, v.id), 1u) << "copied once, before the entry point's OpReturn";
  }
  // The copies sit right before the entry function's OpReturn.
  const auto module = Module::Parse(out);
  const size_t entryStart = module->Find([&](const Instruction& i) {
    return i.opcode() == Op(spv::Op::OpFunction) && i.resultId() == vs.entryFunctionId;
  });
  const size_t ret = module->FindOpcode(Op(spv::Op::OpReturn), entryStart);
  ASSERT_NE(ret, Module::npos);
  EXPECT_EQ((*module)[ret - 1].opcode(), Op(spv::Op::OpStore));
  EXPECT_EQ((*module)[ret - 1].operand(0), xfb.at({0, 24}).id);
  EXPECT_TRUE(HasXfbMode(out));
}

TEST(StreamOutputGlsl, CapturesAPerVertexBlockMember) {
  const std::vector<uint32_t> words =
      Compile(shaders::kGlslVertex, spirv_test::Stage::Vertex, "main", spirv_test::Language::Glsl);
  const Reflection vs = ReflectOrDie(words);
  const std::vector<SO_DECLARATION_ENTRY> entries = {{0, "SV_POSITION", 0, 1, 2, 0}};  // Position.yz
  const std::vector<UINT> strides = {8};
  const WordsResult result = ApplyStreamOutput(words, vs, entries, strides);
  ASSERT_TRUE(result.ok()) << result.error;
  EXPECT_VALID_SPIRV(result.value);
  const auto xfb = XfbVariables(result.value);
  ASSERT_EQ(xfb.size(), 1u);
  EXPECT_EQ(xfb.begin()->second.components, 2u);
  EXPECT_EQ(xfb.begin()->second.location, 1u) << "uv uses location 0";
  const uint32_t block = vs.FindOutput("SV_POSITION", 0)->variableId;
  size_t chains = 0;
  for (const auto& c : InstructionsWithOpcode(result.value, Op(spv::Op::OpAccessChain)))
    chains += c.operand(2) == block;
  EXPECT_EQ(chains, 2u) << "glslang's own store plus the capture's read";
}

TEST(StreamOutputGlsl, SecondStream) {
  const std::vector<uint32_t> words =
      Compile(shaders::kGlslGeometryStreams, spirv_test::Stage::Geometry, "main", spirv_test::Language::Glsl);
  Reflection gs = ReflectOrDie(words);
  // GLSL has no semantics: name the two location outputs for the declaration.
  for (InterfaceVariable& v : gs.outputs) {
    if (v.location == 0u) v.semanticName = "COLOR";
    if (v.location == 1u) v.semanticName = "EXTRA";
  }
  const std::vector<SO_DECLARATION_ENTRY> entries = {{0, "COLOR", 0, 0, 4, 0}, {1, "EXTRA", 0, 0, 3, 1}};
  const std::vector<UINT> strides = {16, 12};
  ASSERT_EQ(ValidateSoDeclaration(entries.data(), 2, strides.data(), 2, 1, gs), "");
  const WordsResult result = ApplyStreamOutput(words, gs, entries, strides);
  ASSERT_TRUE(result.ok()) << result.error;
  const std::vector<uint32_t>& out = result.value;
  EXPECT_VALID_SPIRV(out);
  EXPECT_TRUE(HasCapability(out, spv::Capability::GeometryStreams));
  const auto xfb = XfbVariables(out);
  ASSERT_EQ(xfb.size(), 2u);
  EXPECT_FALSE(xfb.at({0, 0}).stream.has_value());
  EXPECT_EQ(xfb.at({1, 0}).stream, 1u);
  EXPECT_EQ(xfb.at({1, 0}).stride, 12u);

  // Each capture is copied only before the emit of its own stream.
  const auto module = Module::Parse(out);
  std::vector<uint32_t> storedBeforeEmit;  // per emit: which capture was stored just before
  for (size_t i = 1; i < module->size(); ++i)
    if ((*module)[i].opcode() == Op(spv::Op::OpEmitStreamVertex)) storedBeforeEmit.push_back((*module)[i - 1].operand(0));
  ASSERT_EQ(storedBeforeEmit.size(), 2u);
  EXPECT_EQ(storedBeforeEmit[0], xfb.at({0, 0}).id);
  EXPECT_EQ(storedBeforeEmit[1], xfb.at({1, 0}).id);
  EXPECT_EQ(StoresTo(out, xfb.at({0, 0}).id), 1u);
  EXPECT_EQ(StoresTo(out, xfb.at({1, 0}).id), 1u);
}

TEST(StreamOutputErrors, InvalidDeclarationIsRefused) {
  const std::vector<uint32_t> words = Compile(shaders::kGeometry, spirv_test::Stage::Geometry);
  const Reflection gs = ReflectOrDie(words);
  const std::vector<SO_DECLARATION_ENTRY> entries = {{0, "FOO", 1, 0, 4, 0}};
  const WordsResult result = ApplyStreamOutput(words, gs, entries, {});
  EXPECT_EQ(result.error, "SO declaration entry 0: unknown semantic \"FOO1\" (not an output of the GS)");
}

TEST(StreamOutputErrors, NoEntriesLeavesTheShaderAlone) {
  const std::vector<uint32_t> words = Compile(shaders::kVertex, spirv_test::Stage::Vertex);
  const WordsResult result = ApplyStreamOutput(words, ReflectOrDie(words), {}, {});
  ASSERT_TRUE(result.ok()) << result.error;
  EXPECT_EQ(result.value, words);
}

}  // namespace
