// DrawAuto after stream output, through both implementations: the default
// GPU-written indirect arguments and the native vkCmdDrawIndirectByteCountEXT.
//
// The particles are counted exactly: every particle is drawn as a point onto
// one R32_FLOAT pixel with ONE/ONE blending and writes 1.0, so the pixel holds
// the number of vertices DrawAuto drew.
#include "gpu_test.h"

namespace rhi_test {
namespace {

using namespace rhi;

// A particle is (age, kind, unused, unused); kind 0 is the emitter.
// Update rule: the emitter survives and spawns one child per frame; a child
// lives while its age is below 3.
constexpr const char* kShaders = R"(
struct Particle { float4 state : STATE; };
Particle VSPass(Particle p) { return p; }
[maxvertexcount(2)]
void GSUpdate(point Particle input[1], inout PointStream<Particle> stream) {
  Particle p = input[0];
  p.state.x += 1;
  if (p.state.y == 0) {
    stream.Append(p);
    Particle child;
    child.state = float4(0, 1, 0, 0);
    stream.Append(child);
  } else if (p.state.x < 3) {
    stream.Append(p);
  }
}
float4 VSPoint(Particle p) : SV_Position { return float4(0, 0, 0.5, 1); }
float4 PSOne() : SV_Target { return 1; }
)";

// Expected live particles after each update, from the rule above:
// 1 emitter; +1 child per frame; children of age 0, 1, 2 survive.
int ExpectedCount(int updates) { return 1 + std::min(updates, 3); }

class DrawAutoTest : public GpuTest, public ::testing::WithParamInterface<bool> {
 protected:
  void SetUp() override {
    GpuTest::SetUp();
    if (GetParam()) RecreateWithNativeDrawAuto();
    auto vsCode = CompileHlsl(kShaders, "VSPass", "vs_5_0");
    auto gsCode = CompileHlsl(kShaders, "GSUpdate", "gs_5_0");
    auto pointCode = CompileHlsl(kShaders, "VSPoint", "vs_5_0");
    ASSERT_EQ(device->CreateVertexShader(vsCode.data(), vsCode.size() * 4, nullptr, pass.GetAddressOf()), S_OK);
    ASSERT_EQ(device->CreateVertexShader(pointCode.data(), pointCode.size() * 4, nullptr, point.GetAddressOf()), S_OK);
    SO_DECLARATION_ENTRY decl{0, "STATE", 0, 0, 4, 0};
    UINT stride = 16;
    ASSERT_EQ(device->CreateGeometryShaderWithStreamOutput(gsCode.data(), gsCode.size() * 4, &decl, 1, &stride, 1,
                                                           SO_NO_RASTERIZED_STREAM, nullptr, update.GetAddressOf()),
              S_OK);
    INPUT_ELEMENT_DESC element{"STATE", 0, DXGI_FORMAT_R32G32B32A32_FLOAT, 0, 0, INPUT_PER_VERTEX_DATA, 0};
    ASSERT_EQ(device->CreateInputLayout(&element, 1, vsCode.data(), vsCode.size() * 4, layout.GetAddressOf()), S_OK);
    ps = PS(kShaders, "PSOne");
    float emitter[4] = {0, 0, 0, 0};
    init = MakeBuffer(BIND_VERTEX_BUFFER, emitter, sizeof emitter);
    for (auto& b : pingPong) b = MakeBuffer(BIND_VERTEX_BUFFER | BIND_STREAM_OUTPUT, nullptr, 64 * 16);
    counter = MakeRenderTarget(1, 1, DXGI_FORMAT_R32_FLOAT);
    BLEND_DESC add{};
    add.RenderTarget[0] = {TRUE, BLEND_ONE, BLEND_ONE, BLEND_OP_ADD, BLEND_ONE, BLEND_ONE, BLEND_OP_ADD,
                           COLOR_WRITE_ENABLE_ALL};
    ASSERT_EQ(device->CreateBlendState(&add, additive.GetAddressOf()), S_OK);
  }

  void RecreateWithNativeDrawAuto() {
    context.Reset();
    device.Reset();
    DEVICE_OPTIONS options;
    options.EnableValidation = TRUE;
    options.NativeDrawAuto = TRUE;
    options.OnMessage = [this](MESSAGE_CATEGORY category, MESSAGE_SEVERITY severity, const char* text) {
      messages_.push_back({category, severity, text});
    };
    ASSERT_EQ(CreateDevice(&options, device.GetAddressOf(), context.GetAddressOf()), S_OK);
  }

  // One update pass: `source` drawn with Draw(1) (first frame) or DrawAuto into `target`.
  void Update(Buffer* source, Buffer* target, bool first) {
    context->IASetInputLayout(layout.Get());
    UINT stride = 16, offset = 0;
    context->IASetVertexBuffers(0, 1, &source, &stride, &offset);
    context->IASetPrimitiveTopology(PRIMITIVE_TOPOLOGY_POINTLIST);
    context->VSSetShader(pass.Get(), nullptr, 0);
    context->GSSetShader(update.Get(), nullptr, 0);
    context->PSSetShader(nullptr, nullptr, 0);
    context->OMSetRenderTargets(0, nullptr, nullptr);
    context->SOSetTargets(1, &target, &offset);
    if (first)
      context->Draw(1, 0);
    else
      context->DrawAuto();
    context->SOSetTargets(0, nullptr, nullptr);
  }

  // Draws `source` with DrawAuto and returns how many vertices were drawn.
  float CountWithDrawAuto(Buffer* source) {
    float zero[4] = {0, 0, 0, 0};
    context->ClearRenderTargetView(counter.rtv.Get(), zero);
    context->IASetInputLayout(layout.Get());
    UINT stride = 16, offset = 0;
    context->IASetVertexBuffers(0, 1, &source, &stride, &offset);
    context->VSSetShader(point.Get(), nullptr, 0);
    context->GSSetShader(nullptr, nullptr, 0);
    context->PSSetShader(ps.Get(), nullptr, 0);
    context->OMSetBlendState(additive.Get(), nullptr, DEFAULT_SAMPLE_MASK);
    RenderTargetView* rtv = counter.rtv.Get();
    context->OMSetRenderTargets(1, &rtv, nullptr);
    SetViewport(1, 1);
    context->DrawAuto();
    context->OMSetBlendState(nullptr, nullptr, DEFAULT_SAMPLE_MASK);
    context->OMSetRenderTargets(0, nullptr, nullptr);
    auto bytes = ReadTexture(counter.texture.Get());
    float count;
    std::memcpy(&count, bytes.data(), 4);
    return count;
  }

  ComPtr<VertexShader> pass, point;
  ComPtr<GeometryShader> update;
  ComPtr<PixelShader> ps;
  ComPtr<InputLayout> layout;
  ComPtr<Buffer> init, pingPong[2];
  Target counter;
  ComPtr<BlendState> additive;
};

TEST_P(DrawAutoTest, PingPongSpawnsAndKillsExactly) {
  Update(init.Get(), pingPong[0].Get(), true);
  EXPECT_EQ(CountWithDrawAuto(pingPong[0].Get()), ExpectedCount(1));
  for (int frame = 2; frame <= 8; ++frame) {
    Buffer* source = pingPong[frame % 2 == 0 ? 0 : 1].Get();
    Buffer* target = pingPong[frame % 2 == 0 ? 1 : 0].Get();
    Update(source, target, false);
    EXPECT_EQ(CountWithDrawAuto(target), ExpectedCount(frame)) << "after update " << frame;
  }
}

TEST_P(DrawAutoTest, DrawsOnlyWhatFitAfterOverflow) {
  // Room for 2 particles: the third update needs 3 and overflows.
  ComPtr<Buffer> small = MakeBuffer(BIND_VERTEX_BUFFER | BIND_STREAM_OUTPUT, nullptr, 2 * 16);
  Update(init.Get(), pingPong[0].Get(), true);   // 2 particles
  Update(pingPong[0].Get(), small.Get(), false);  // needs 3, 2 fit
  EXPECT_EQ(CountWithDrawAuto(small.Get()), 2.0f);
}

TEST_P(DrawAutoTest, NeverWrittenBufferDrawsNothing) {
  EXPECT_EQ(CountWithDrawAuto(pingPong[1].Get()), 0.0f);
}

INSTANTIATE_TEST_SUITE_P(BothPaths, DrawAutoTest, ::testing::Values(false, true),
                         [](const auto& info) { return info.param ? "NativeByteCount" : "GpuIndirectArgs"; });

}  // namespace
}  // namespace rhi_test
