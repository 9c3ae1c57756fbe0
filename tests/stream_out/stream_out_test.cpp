// Stream output with D3D11's semantics: exact readback of what the
// declaration captures, where it lands, and what is refused.
#include "gpu_test.h"

namespace rhi_test {
namespace {

using namespace rhi;

// A pass-through VS and a GS that emits, per input point, one vertex with
// POSITION = p, TEXCOORD0 = (p.x + 100, p.y + 200), COLOR = p * 10.
constexpr const char* kShaders = R"(
struct VIn { float4 p : POSITION; };
struct GOut { float4 p : POSITION; float2 uv : TEXCOORD0; float4 c : COLOR; };
cbuffer Params : register(b0) { float4 bias; };
VIn VSMain(VIn v) { return v; }
[maxvertexcount(1)]
void GSMain(point VIn input[1], inout PointStream<GOut> stream) {
  GOut o;
  o.p = input[0].p + bias;
  o.uv = float2(o.p.x + 100, o.p.y + 200);
  o.c = o.p * 10;
  stream.Append(o);
}
)";

class StreamOutTest : public GpuTest {
 protected:
  void SetUp() override {
    GpuTest::SetUp();
    vsCode = CompileHlsl(kShaders, "VSMain", "vs_5_0");
    gsCode = CompileHlsl(kShaders, "GSMain", "gs_5_0");
    ASSERT_EQ(device->CreateVertexShader(vsCode.data(), vsCode.size() * 4, nullptr, vs.GetAddressOf()), S_OK);
    INPUT_ELEMENT_DESC element{"POSITION", 0, DXGI_FORMAT_R32G32B32A32_FLOAT, 0, 0, INPUT_PER_VERTEX_DATA, 0};
    ASSERT_EQ(device->CreateInputLayout(&element, 1, vsCode.data(), vsCode.size() * 4, layout.GetAddressOf()), S_OK);
    float points[4][4] = {{1, 2, 3, 4}, {5, 6, 7, 8}, {9, 10, 11, 12}, {13, 14, 15, 16}};
    input = MakeBuffer(BIND_VERTEX_BUFFER, points, sizeof points);
    float zero[4] = {0, 0, 0, 0};
    bias = MakeBuffer(BIND_CONSTANT_BUFFER, zero, sizeof zero);
  }

  HRESULT MakeSoShader(const std::vector<SO_DECLARATION_ENTRY>& decl, const std::vector<UINT>& strides,
                       ComPtr<GeometryShader>* out, UINT rasterized = SO_NO_RASTERIZED_STREAM) {
    return device->CreateGeometryShaderWithStreamOutput(gsCode.data(), gsCode.size() * 4, decl.data(),
                                                        static_cast<UINT>(decl.size()), strides.data(),
                                                        static_cast<UINT>(strides.size()), rasterized, nullptr,
                                                        out->GetAddressOf());
  }

  void BindPipeline(GeometryShader* gs) {
    context->IASetInputLayout(layout.Get());
    UINT stride = 16, offset = 0;
    Buffer* vb = input.Get();
    context->IASetVertexBuffers(0, 1, &vb, &stride, &offset);
    context->IASetPrimitiveTopology(PRIMITIVE_TOPOLOGY_POINTLIST);
    context->VSSetShader(vs.Get(), nullptr, 0);
    context->GSSetShader(gs, nullptr, 0);
    Buffer* cb = bias.Get();
    context->GSSetConstantBuffers(0, 1, &cb);
  }

  ComPtr<Buffer> MakeTarget(UINT size) { return MakeBuffer(BIND_STREAM_OUTPUT, nullptr, size); }

  std::vector<uint32_t> vsCode, gsCode;
  ComPtr<VertexShader> vs;
  ComPtr<InputLayout> layout;
  ComPtr<Buffer> input, bias;
};

TEST_F(StreamOutTest, CapturesComponentSubsetsGapsAndTwoSlots) {
  // Slot 0: POSITION.xyz, a one-component gap, TEXCOORD0.y  -> 5 floats, stride 20
  // Slot 1: COLOR.zw                                        -> 2 floats, stride 8
  std::vector<SO_DECLARATION_ENTRY> decl = {
      {0, "POSITION", 0, 0, 3, 0}, {0, nullptr, 0, 0, 1, 0}, {0, "TEXCOORD", 0, 1, 1, 0}, {0, "COLOR", 0, 2, 2, 1}};
  ComPtr<GeometryShader> gs;
  ASSERT_EQ(MakeSoShader(decl, {20, 8}, &gs), S_OK);
  auto slot0 = MakeTarget(4 * 20);
  auto slot1 = MakeTarget(4 * 8);
  // Pre-fill so the gap's untouched bytes are recognisable.
  std::vector<float> sentinel(20, -1.0f);
  context->UpdateSubresource(slot0.Get(), 0, nullptr, sentinel.data(), 0, 0);
  BindPipeline(gs.Get());
  Buffer* targets[] = {slot0.Get(), slot1.Get()};
  UINT offsets[] = {0, 0};
  context->SOSetTargets(2, targets, offsets);
  context->Draw(4, 0);
  context->SOSetTargets(0, nullptr, nullptr);

  auto a = ReadBufferAs<float>(slot0.Get());
  auto b = ReadBufferAs<float>(slot1.Get());
  for (int v = 0; v < 4; ++v) {
    const float p[4] = {1.0f + 4 * v, 2.0f + 4 * v, 3.0f + 4 * v, 4.0f + 4 * v};
    EXPECT_EQ(a[v * 5 + 0], p[0]);
    EXPECT_EQ(a[v * 5 + 1], p[1]);
    EXPECT_EQ(a[v * 5 + 2], p[2]);
    EXPECT_EQ(a[v * 5 + 3], -1.0f) << "a gap keeps the buffer's contents";
    EXPECT_EQ(a[v * 5 + 4], p[1] + 200) << "TEXCOORD0.y";
    EXPECT_EQ(b[v * 2 + 0], p[2] * 10) << "COLOR.z";
    EXPECT_EQ(b[v * 2 + 1], p[3] * 10) << "COLOR.w";
  }
}

TEST_F(StreamOutTest, AppendsAcrossDrawsAndHonoursOffsets) {
  std::vector<SO_DECLARATION_ENTRY> decl = {{0, "POSITION", 0, 0, 1, 0}};
  ComPtr<GeometryShader> gs;
  ASSERT_EQ(MakeSoShader(decl, {4}, &gs), S_OK);
  auto target = MakeTarget(16 * 4);
  std::vector<float> sentinel(16, -1.0f);
  context->UpdateSubresource(target.Get(), 0, nullptr, sentinel.data(), 0, 0);
  BindPipeline(gs.Get());
  Buffer* t = target.Get();
  UINT offset = 8;  // starts at float 2
  context->SOSetTargets(1, &t, &offset);
  context->Draw(2, 0);  // x = 1, 5
  // A constant buffer update and a normal draw state change in between must not disturb appending.
  float shift[4] = {1000, 0, 0, 0};
  context->UpdateSubresource(bias.Get(), 0, nullptr, shift, 0, 0);
  context->Draw(1, 2);  // x = 1009
  // Rebinding with -1 appends where the last stream-out stopped.
  UINT append = UINT(-1);
  context->SOSetTargets(1, &t, &append);
  context->Draw(1, 3);  // x = 1013
  context->SOSetTargets(0, nullptr, nullptr);

  auto x = ReadBufferAs<float>(target.Get());
  const std::vector<float> expected = {-1, -1, 1, 5, 1009, 1013, -1, -1};
  for (size_t i = 0; i < expected.size(); ++i) EXPECT_EQ(x[i], expected[i]) << "float " << i;
}

TEST_F(StreamOutTest, VertexShaderOnlyStreamOutput) {
  SO_DECLARATION_ENTRY decl{0, "POSITION", 0, 1, 2, 0};
  UINT stride = 8;
  ComPtr<GeometryShader> so;
  ASSERT_EQ(device->CreateGeometryShaderWithStreamOutput(vsCode.data(), vsCode.size() * 4, &decl, 1, &stride, 1,
                                                         SO_NO_RASTERIZED_STREAM, nullptr, so.GetAddressOf()),
            S_OK);
  auto target = MakeTarget(4 * 8);
  BindPipeline(so.Get());
  Buffer* t = target.Get();
  UINT offset = 0;
  context->SOSetTargets(1, &t, &offset);
  context->Draw(4, 0);
  context->SOSetTargets(0, nullptr, nullptr);
  auto yz = ReadBufferAs<float>(target.Get());
  for (int v = 0; v < 4; ++v) {
    EXPECT_EQ(yz[v * 2], 2.0f + 4 * v);
    EXPECT_EQ(yz[v * 2 + 1], 3.0f + 4 * v);
  }
}

TEST_F(StreamOutTest, RefusesBadDeclarationsWithTheReason) {
  ComPtr<GeometryShader> gs;
  EXPECT_EQ(MakeSoShader({{0, "NORMAL", 0, 0, 3, 0}}, {12}, &gs), E_INVALIDARG);
  EXPECT_TRUE(RefusedWith("NORMAL0")) << "unknown semantic named";
  ClearMessages();
  EXPECT_EQ(MakeSoShader({{0, "POSITION", 0, 0, 3, 0}, {0, "POSITION", 0, 2, 2, 0}}, {20}, &gs), E_INVALIDARG);
  EXPECT_FALSE(Refusals().empty()) << "overlapping components";
  ClearMessages();
  EXPECT_EQ(MakeSoShader({{0, "POSITION", 0, 0, 4, 0}}, {8}, &gs), E_INVALIDARG);
  EXPECT_FALSE(Refusals().empty()) << "stride too small";
  ClearMessages();
  EXPECT_EQ(MakeSoShader({{0, "TEXCOORD", 0, 1, 2, 0}}, {8}, &gs), E_INVALIDARG);
  EXPECT_FALSE(Refusals().empty()) << "TEXCOORD0 has two components: .yz is out of range";
  ClearMessages();
}

TEST_F(StreamOutTest, OverflowDropsWholePrimitivesAndQueriesReportIt) {
  std::vector<SO_DECLARATION_ENTRY> decl = {{0, "POSITION", 0, 0, 4, 0}};
  ComPtr<GeometryShader> gs;
  ASSERT_EQ(MakeSoShader(decl, {16}, &gs), S_OK);
  auto target = MakeTarget(3 * 16 + 8);  // room for 3 points and half of a fourth
  std::vector<float> sentinel(14, -1.0f);
  context->UpdateSubresource(target.Get(), 0, nullptr, sentinel.data(), 0, 0);
  BindPipeline(gs.Get());
  Buffer* t = target.Get();
  UINT offset = 0;
  context->SOSetTargets(1, &t, &offset);
  ComPtr<Query> stats, overflow, overflowAny;
  QUERY_DESC statsDesc{QUERY_SO_STATISTICS_STREAM0, 0}, overflowDesc{QUERY_SO_OVERFLOW_PREDICATE_STREAM0, 0},
      anyDesc{QUERY_SO_OVERFLOW_PREDICATE, 0};
  ASSERT_EQ(device->CreateQuery(&statsDesc, stats.GetAddressOf()), S_OK);
  ASSERT_EQ(device->CreateQuery(&overflowDesc, overflow.GetAddressOf()), S_OK);
  ASSERT_EQ(device->CreateQuery(&anyDesc, overflowAny.GetAddressOf()), S_OK);
  context->Begin(stats.Get());
  context->Begin(overflow.Get());
  context->Begin(overflowAny.Get());
  context->Draw(4, 0);
  context->End(overflowAny.Get());
  context->End(overflow.Get());
  context->End(stats.Get());
  context->SOSetTargets(0, nullptr, nullptr);

  auto s = WaitForData<QUERY_DATA_SO_STATISTICS>(stats.Get());
  EXPECT_EQ(s.NumPrimitivesWritten, 3u);
  EXPECT_EQ(s.PrimitivesStorageNeeded, 4u);
  EXPECT_EQ(WaitForData<BOOL>(overflow.Get()), TRUE);
  EXPECT_EQ(WaitForData<BOOL>(overflowAny.Get()), TRUE);
  auto values = ReadBufferAs<float>(target.Get());
  EXPECT_EQ(values[8], 9.0f) << "third point written";
  EXPECT_EQ(values[12], -1.0f) << "no partial fourth point";
  EXPECT_EQ(values[13], -1.0f) << "no partial fourth point";
}

TEST_F(StreamOutTest, NoOverflowWhenEverythingFits) {
  ComPtr<GeometryShader> gs;
  ASSERT_EQ(MakeSoShader({{0, "POSITION", 0, 0, 4, 0}}, {16}, &gs), S_OK);
  auto target = MakeTarget(4 * 16);
  BindPipeline(gs.Get());
  Buffer* t = target.Get();
  UINT offset = 0;
  context->SOSetTargets(1, &t, &offset);
  ComPtr<Query> overflow;
  QUERY_DESC desc{QUERY_SO_OVERFLOW_PREDICATE, 0};
  ASSERT_EQ(device->CreateQuery(&desc, overflow.GetAddressOf()), S_OK);
  context->Begin(overflow.Get());
  context->Draw(4, 0);
  context->End(overflow.Get());
  EXPECT_EQ(WaitForData<BOOL>(overflow.Get()), FALSE);
}

}  // namespace
}  // namespace rhi_test
