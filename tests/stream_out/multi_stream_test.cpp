// Stream output from several geometry-shader streams at once.
//
// glslang's HLSL front end cannot emit to streams other than 0 (it drops the
// stream of PointStream objects), so this geometry shader is GLSL with
// EmitStreamVertex; the test then gives its outputs HLSL semantics the way
// glslang's HLSL front end marks them (UserSemantic decorations), so the
// D3D11 declaration can name them. That is the SPIR-V an HLSL compiler with
// multi-stream support would hand the RHI.
#include <glslang/Public/ResourceLimits.h>
#include <glslang/Public/ShaderLang.h>
#include <glslang/SPIRV/GlslangToSpv.h>

#include "gpu_test.h"
#include "spirv/spirv_module.h"

namespace rhi_test {
namespace {

using namespace rhi;

// Stream 0 gets A = (i, 0, 0, 0); stream 1 gets B = (0, 10 * i, 0, 0), twice per input.
constexpr const char* kGeometryShader = R"(#version 450
layout(points) in;
layout(points, max_vertices = 3) out;
layout(location = 0) in vec4 inValue[];
layout(location = 0, stream = 0) out vec4 A;
layout(location = 1, stream = 1) out vec4 B;
void main() {
  A = vec4(inValue[0].x, 0, 0, 0);
  EmitStreamVertex(0);
  B = vec4(0, 10 * inValue[0].x, 0, 0);
  EmitStreamVertex(1);
  B = vec4(0, 10 * inValue[0].x + 1, 0, 0);
  EmitStreamVertex(1);
}
)";

std::vector<uint32_t> CompileGlslGeometry(const char* source) {
  static bool initialized = glslang::InitializeProcess();
  (void)initialized;
  glslang::TShader shader(EShLangGeometry);
  shader.setStrings(&source, 1);
  shader.setEnvInput(glslang::EShSourceGlsl, EShLangGeometry, glslang::EShClientVulkan, 100);
  shader.setEnvClient(glslang::EShClientVulkan, glslang::EShTargetVulkan_1_3);
  shader.setEnvTarget(glslang::EShTargetSpv, glslang::EShTargetSpv_1_5);
  EXPECT_TRUE(shader.parse(GetDefaultResources(), 450, false, EShMsgDefault)) << shader.getInfoLog();
  glslang::TProgram program;
  program.addShader(&shader);
  EXPECT_TRUE(program.link(EShMsgDefault)) << program.getInfoLog();
  std::vector<uint32_t> spirv;
  glslang::GlslangToSpv(*program.getIntermediate(EShLangGeometry), spirv);
  return spirv;
}

// Marks the output and input variables at `location` with an HLSL semantic.
std::vector<uint32_t> AddSemantics(const std::vector<uint32_t>& words,
                                   const std::vector<std::pair<uint32_t, const char*>>& semantics) {
  constexpr uint32_t kOpExtension = 10, kOpDecorate = 71, kOpDecorateString = 5632;
  constexpr uint32_t kDecorationLocation = 30, kDecorationUserSemantic = 5635;
  auto module = *rhi::spirv::Module::Parse(words);
  std::vector<rhi::spirv::Instruction> added;
  for (const auto& inst : module) {
    if (inst.opcode() != kOpDecorate || inst.operand(1) != kDecorationLocation) continue;
    for (const auto& [location, name] : semantics) {
      if (inst.operand(2) != location) continue;
      std::vector<uint32_t> operands = {inst.operand(0), kDecorationUserSemantic};
      for (uint32_t word : rhi::spirv::EncodeString(name)) operands.push_back(word);
      added.emplace_back(kOpDecorateString, operands);
    }
  }
  size_t at = module.FindOpcode(kOpDecorate);
  module.Insert(at, added);
  module.Insert(module.FindOpcode(kOpExtension) == rhi::spirv::Module::npos ? module.FindOpcode(11) : module.FindOpcode(kOpExtension),
                rhi::spirv::Instruction(kOpExtension, rhi::spirv::EncodeString("SPV_GOOGLE_hlsl_functionality1")));
  return module.Assemble();
}

class MultiStreamTest : public GpuTest {
 protected:
  void SetUp() override {
    GpuTest::SetUp();
    gsCode = AddSemantics(CompileGlslGeometry(kGeometryShader), {{0, "VALUE"}, {1, "STREAM_B"}});
    vsCode = CompileHlsl("float4 main(float4 v : VALUE) : VALUE { return v; }", "main", "vs_5_0");
    ASSERT_EQ(device->CreateVertexShader(vsCode.data(), vsCode.size() * 4, nullptr, vs.GetAddressOf()), S_OK);
    INPUT_ELEMENT_DESC element{"VALUE", 0, DXGI_FORMAT_R32G32B32A32_FLOAT, 0, 0, INPUT_PER_VERTEX_DATA, 0};
    ASSERT_EQ(device->CreateInputLayout(&element, 1, vsCode.data(), vsCode.size() * 4, layout.GetAddressOf()), S_OK);
    float values[3][4] = {{1, 0, 0, 0}, {2, 0, 0, 0}, {3, 0, 0, 0}};
    input = MakeBuffer(BIND_VERTEX_BUFFER, values, sizeof values);
  }

  HRESULT MakeShader(UINT rasterizedStream) {
    const SO_DECLARATION_ENTRY decl[] = {{0, "VALUE", 0, 0, 1, 0}, {1, "STREAM_B", 0, 1, 1, 1}};
    const UINT strides[] = {4, 4};
    return device->CreateGeometryShaderWithStreamOutput(gsCode.data(), gsCode.size() * 4, decl, 2, strides, 2,
                                                        rasterizedStream, nullptr, gs.ReleaseAndGetAddressOf());
  }

  void Bind(Buffer* stream0, Buffer* stream1) {
    context->IASetInputLayout(layout.Get());
    Buffer* vb = input.Get();
    UINT stride = 16, offset = 0;
    context->IASetVertexBuffers(0, 1, &vb, &stride, &offset);
    context->IASetPrimitiveTopology(PRIMITIVE_TOPOLOGY_POINTLIST);
    context->VSSetShader(vs.Get(), nullptr, 0);
    context->GSSetShader(gs.Get(), nullptr, 0);
    Buffer* targets[] = {stream0, stream1};
    UINT offsets[] = {0, 0};
    context->SOSetTargets(2, targets, offsets);
  }

  ComPtr<Query> MakeQuery(QUERY kind) {
    QUERY_DESC desc{kind, 0};
    ComPtr<Query> query;
    EXPECT_EQ(device->CreateQuery(&desc, query.GetAddressOf()), S_OK);
    return query;
  }

  std::vector<uint32_t> gsCode, vsCode;
  ComPtr<GeometryShader> gs;
  ComPtr<VertexShader> vs;
  ComPtr<InputLayout> layout;
  ComPtr<Buffer> input;
};

TEST_F(MultiStreamTest, EachStreamFillsItsOwnBufferAndIsCountedSeparately) {
  ASSERT_EQ(MakeShader(0), S_OK) << (Refusals().empty() ? "" : Refusals()[0]);
  auto stream0 = MakeBuffer(BIND_STREAM_OUTPUT, nullptr, 16 * 4);
  auto stream1 = MakeBuffer(BIND_STREAM_OUTPUT, nullptr, 16 * 4);
  Bind(stream0.Get(), stream1.Get());
  ComPtr<Query> stats0 = MakeQuery(QUERY_SO_STATISTICS_STREAM0), stats1 = MakeQuery(QUERY_SO_STATISTICS_STREAM1);
  context->Begin(stats0.Get());
  context->Begin(stats1.Get());
  context->Draw(3, 0);
  context->End(stats1.Get());
  context->End(stats0.Get());
  context->SOSetTargets(0, nullptr, nullptr);

  auto a = ReadBufferAs<float>(stream0.Get());
  auto b = ReadBufferAs<float>(stream1.Get());
  EXPECT_EQ((std::vector<float>(a.begin(), a.begin() + 3)), (std::vector<float>{1, 2, 3}));
  EXPECT_EQ((std::vector<float>(b.begin(), b.begin() + 6)), (std::vector<float>{10, 11, 20, 21, 30, 31}));
  EXPECT_EQ(WaitForData<QUERY_DATA_SO_STATISTICS>(stats0.Get()).NumPrimitivesWritten, 3u);
  EXPECT_EQ(WaitForData<QUERY_DATA_SO_STATISTICS>(stats1.Get()).NumPrimitivesWritten, 6u);
}

TEST_F(MultiStreamTest, OverflowPredicatesPerStreamAndForAnyStream) {
  ASSERT_EQ(MakeShader(SO_NO_RASTERIZED_STREAM), S_OK);
  auto stream0 = MakeBuffer(BIND_STREAM_OUTPUT, nullptr, 3 * 4);  // exactly fits stream 0's 3 values
  auto stream1 = MakeBuffer(BIND_STREAM_OUTPUT, nullptr, 4 * 4);  // 4 of stream 1's 6
  Bind(stream0.Get(), stream1.Get());
  ComPtr<Query> over0 = MakeQuery(QUERY_SO_OVERFLOW_PREDICATE_STREAM0),
                over1 = MakeQuery(QUERY_SO_OVERFLOW_PREDICATE_STREAM1), any = MakeQuery(QUERY_SO_OVERFLOW_PREDICATE),
                stats1 = MakeQuery(QUERY_SO_STATISTICS_STREAM1);
  for (Query* q : {over0.Get(), over1.Get(), any.Get(), stats1.Get()}) context->Begin(q);
  context->Draw(3, 0);
  for (Query* q : {over0.Get(), over1.Get(), any.Get(), stats1.Get()}) context->End(q);
  context->SOSetTargets(0, nullptr, nullptr);
  EXPECT_EQ(WaitForData<BOOL>(over0.Get()), FALSE);
  EXPECT_EQ(WaitForData<BOOL>(over1.Get()), TRUE);
  EXPECT_EQ(WaitForData<BOOL>(any.Get()), TRUE);
  auto s = WaitForData<QUERY_DATA_SO_STATISTICS>(stats1.Get());
  EXPECT_EQ(s.NumPrimitivesWritten, 4u);
  EXPECT_EQ(s.PrimitivesStorageNeeded, 6u);
}

TEST_F(MultiStreamTest, RasterizedStreamBeyondWhatTheDeviceSelectsIsRefused) {
  HRESULT hr = MakeShader(1);
  if (hr == S_OK) GTEST_SKIP() << device->GetAdapterName() << " can rasterize stream 1";
  EXPECT_EQ(hr, E_INVALIDARG);
  EXPECT_TRUE(RefusedWith("cannot rasterize stream 1"));
}

}  // namespace
}  // namespace rhi_test
