// D3D11's hazard rule: a resource is never bound for reading and writing at
// once. Binding it for writing (RTV, SO target, UAV) removes it from every read
// slot; binding it for reading while it is bound for writing binds NULL
// instead. A NULL SRV reads zero, a NULL vertex buffer reads zero.
#include "gpu_helpers.h"

namespace rhi_test {
namespace {

using namespace rhi;

class BindingRulesTest : public RhiGpuTest {
 protected:
  void SetUp() override {
    RhiGpuTest::SetUp();
    if (HasFatalFailure()) return;
    texture_ = MakeRenderTarget(8, 8);
    Clear(texture_.rtv.Get(), kGreen);
    ASSERT_EQ(device->CreateShaderResourceView(texture_.texture.Get(), nullptr, srv_.GetAddressOf()), S_OK);
    other_ = MakeRenderTarget(8, 8);
    vs_ = VS(R"(float4 main(uint id : SV_VertexID) : SV_Position {
        return float4(float(id & 1) * 4 - 1, 1 - float(id & 2) * 2, 0.5, 1); })");
    ps_ = PS(R"(Texture2D t : register(t0);
                float4 main(float4 pos : SV_Position) : SV_Target { return t.Load(int3(pos.xy, 0)); })");
  }
  // Fills `other_` (cleared red first) with what the pixel shader reads from t0.
  std::vector<uint8_t> SampleIntoOther() {
    BindTarget(other_.rtv.Get(), 8, 8);
    Clear(other_.rtv.Get(), kRed);
    context->IASetInputLayout(nullptr);
    context->IASetPrimitiveTopology(PRIMITIVE_TOPOLOGY_TRIANGLELIST);
    context->VSSetShader(vs_.Get(), nullptr, 0);
    context->PSSetShader(ps_.Get(), nullptr, 0);
    context->Draw(3, 0);
    return ReadTexture(other_.texture.Get());
  }
  void BindSrv() {
    ShaderResourceView* srvs[] = {srv_.Get()};
    context->PSSetShaderResources(0, 1, srvs);
  }

  Target texture_, other_;
  ComPtr<ShaderResourceView> srv_;
  ComPtr<VertexShader> vs_;
  ComPtr<PixelShader> ps_;
};

TEST_F(BindingRulesTest, BindingTextureAsRenderTargetUnbindsItFromPixelShaderSlots) {
  BindSrv();
  EXPECT_EQ(CountPixels(SampleIntoOther(), kGreenPx), 64) << "control: the SRV reads the green texture";
  BindTarget(texture_.rtv.Get(), 8, 8);  // unbinds srv_ from PS t0 ...
  // ... and it stays unbound after the texture leaves the output merger: t0 reads zero.
  EXPECT_EQ(CountPixels(SampleIntoOther(), RGBA(0, 0, 0, 0)), 64);
}

TEST_F(BindingRulesTest, BindingSrvOfTextureBoundAsRenderTargetBindsNull) {
  BindTarget(texture_.rtv.Get(), 8, 8);
  BindSrv();  // the texture is an RTV: t0 becomes NULL
  EXPECT_EQ(CountPixels(SampleIntoOther(), RGBA(0, 0, 0, 0)), 64);
  BindSrv();  // no longer an RTV: now it binds
  EXPECT_EQ(CountPixels(SampleIntoOther(), kGreenPx), 64);
}

class StreamOutBindingTest : public RhiGpuTest {
 protected:
  void SetUp() override {
    RhiGpuTest::SetUp();
    if (HasFatalFailure()) return;
    target_ = MakeRenderTarget(8, 8);
    BindTarget(target_.rtv.Get(), 8, 8);
    UseColorPipeline();
    // A red quad over columns 0-3 in a buffer that can be a vertex buffer and an SO target.
    std::vector<Vertex> quad = Quad(0, 0, 4, 8, kRed, 8, 8);
    buffer_ = MakeBuffer(BIND_VERTEX_BUFFER | BIND_STREAM_OUTPUT, quad.data(),
                         static_cast<UINT>(quad.size() * sizeof(Vertex)));
  }
  void BindAsVertexBuffer() {
    const UINT stride = sizeof(Vertex), offset = 0;
    Buffer* vbs[] = {buffer_.Get()};
    context->IASetVertexBuffers(0, 1, vbs, &stride, &offset);
  }
  void BindAsSoTarget() {
    const UINT offset = 0;
    Buffer* targets[] = {buffer_.Get()};
    context->SOSetTargets(1, targets, &offset);
  }
  Buffer* SoTarget0() {
    Buffer* bound[1] = {nullptr};
    context->SOGetTargets(1, bound);
    if (bound[0]) bound[0]->Release();  // SOGetTargets adds a reference
    return bound[0];
  }
  std::vector<std::string> DrawQuad() {
    Clear(target_.rtv.Get(), kBlack);
    context->Draw(6, 0);
    return Picture(ReadTexture(target_.texture.Get()), 8, 8, kLegend);
  }

  Target target_;
  ComPtr<Buffer> buffer_;
};

TEST_F(StreamOutBindingTest, BindingBufferAsSoTargetUnbindsItFromInputAssembler) {
  BindAsVertexBuffer();
  EXPECT_EQ(DrawQuad(), Rows(8, "RRRR....")) << "control: the vertex buffer holds the red quad";
  BindAsSoTarget();  // unbinds the buffer from IA slot 0
  EXPECT_EQ(SoTarget0(), buffer_.Get());
  context->SOSetTargets(0, nullptr, nullptr);
  EXPECT_EQ(SoTarget0(), nullptr);
  // IA slot 0 is NULL: every vertex reads zero, the triangles are degenerate.
  EXPECT_EQ(DrawQuad(), Rows(8, "........"));
}

TEST_F(StreamOutBindingTest, BindingCurrentSoTargetAsVertexBufferBindsNull) {
  BindAsSoTarget();
  BindAsVertexBuffer();  // still an SO target: IA slot 0 becomes NULL
  EXPECT_EQ(SoTarget0(), buffer_.Get()) << "the SO binding is kept";
  context->SOSetTargets(0, nullptr, nullptr);
  EXPECT_EQ(DrawQuad(), Rows(8, "........"));
  BindAsVertexBuffer();  // no longer an SO target: now it binds
  EXPECT_EQ(DrawQuad(), Rows(8, "RRRR...."));
}

TEST_F(RhiGpuTest, BindingBufferAsComputeUavUnbindsItsComputeSrv) {
  // Word 0 holds 5. The shader writes u0[0] = t0[0] + 1 with t0 and u0 views of
  // the same buffer: binding the UAV removed the SRV, so t0 reads 0 and u0[0] = 1.
  const uint32_t initial[4] = {5, 0, 0, 0};
  ComPtr<Buffer> buffer = MakeBuffer(BIND_SHADER_RESOURCE | BIND_UNORDERED_ACCESS, initial, sizeof initial,
                                     USAGE_DEFAULT, RESOURCE_MISC_BUFFER_ALLOW_RAW_VIEWS);
  SHADER_RESOURCE_VIEW_DESC srvDesc{};
  srvDesc.Format = DXGI_FORMAT_R32_TYPELESS;
  srvDesc.ViewDimension = SRV_DIMENSION_BUFFEREX;
  srvDesc.BufferEx = {0, 4, BUFFEREX_SRV_FLAG_RAW};
  ComPtr<ShaderResourceView> srv;
  ASSERT_EQ(device->CreateShaderResourceView(buffer.Get(), &srvDesc, srv.GetAddressOf()), S_OK);
  UNORDERED_ACCESS_VIEW_DESC uavDesc{};
  uavDesc.Format = DXGI_FORMAT_R32_TYPELESS;
  uavDesc.ViewDimension = UAV_DIMENSION_BUFFER;
  uavDesc.Buffer = {0, 4, BUFFER_UAV_FLAG_RAW};
  ComPtr<UnorderedAccessView> uav;
  ASSERT_EQ(device->CreateUnorderedAccessView(buffer.Get(), &uavDesc, uav.GetAddressOf()), S_OK);
  auto cs = CS(R"(ByteAddressBuffer src : register(t0); RWByteAddressBuffer dst : register(u0);
                  [numthreads(1, 1, 1)] void main() { dst.Store(0, src.Load(0) + 1); })");
  context->CSSetShader(cs.Get(), nullptr, 0);
  ShaderResourceView* srvs[] = {srv.Get()};
  context->CSSetShaderResources(0, 1, srvs);
  UnorderedAccessView* uavs[] = {uav.Get()};
  context->CSSetUnorderedAccessViews(0, 1, uavs, nullptr);
  context->Dispatch(1, 1, 1);
  EXPECT_EQ(ReadBufferAs<uint32_t>(buffer.Get())[0], 1u);
}

// D3D11 lifetimes: the context's bindings keep objects alive but not the
// device. A view bound only by the context holds its resource; neither may
// keep the device alive, or device -> context -> view -> resource -> device
// would never be released (this leaked every device that drew into a target).
TEST(DeviceLifetimeTest, ObjectsKeptOnlyByBindingsDoNotKeepTheDeviceAlive) {
  DEVICE_OPTIONS options;
  options.EnableValidation = TRUE;
  std::vector<std::string> validation;
  options.OnMessage = [&](MESSAGE_CATEGORY category, MESSAGE_SEVERITY, const char* text) {
    if (category == MESSAGE_CATEGORY_VULKAN_VALIDATION) validation.push_back(text);
  };
  Device* device = nullptr;
  DeviceContext* context = nullptr;
  ASSERT_EQ(CreateDevice(&options, &device, &context), S_OK);
  {
    TEXTURE2D_DESC desc{};
    desc.Width = desc.Height = 4;
    desc.MipLevels = desc.ArraySize = 1;
    desc.Format = DXGI_FORMAT_R8G8B8A8_UNORM;
    desc.SampleDesc.Count = 1;
    desc.BindFlags = BIND_RENDER_TARGET | BIND_SHADER_RESOURCE;
    ComPtr<Texture2D> texture, sampled;
    ASSERT_EQ(device->CreateTexture2D(&desc, nullptr, texture.GetAddressOf()), S_OK);
    ASSERT_EQ(device->CreateTexture2D(&desc, nullptr, sampled.GetAddressOf()), S_OK);
    ComPtr<RenderTargetView> rtv;
    ComPtr<ShaderResourceView> srv;
    ASSERT_EQ(device->CreateRenderTargetView(texture.Get(), nullptr, rtv.GetAddressOf()), S_OK);
    ASSERT_EQ(device->CreateShaderResourceView(sampled.Get(), nullptr, srv.GetAddressOf()), S_OK);
    RenderTargetView* rtvs[] = {rtv.Get()};
    context->OMSetRenderTargets(1, rtvs, nullptr);
    ShaderResourceView* srvs[] = {srv.Get()};
    context->PSSetShaderResources(0, 1, srvs);
    const FLOAT red[4] = {1, 0, 0, 1};
    context->ClearRenderTargetView(rtv.Get(), red);
  }  // the application's references go; the bindings stay
  EXPECT_EQ(context->Release(), 1u);  // the immediate context's reference was one on the device
  EXPECT_EQ(device->Release(), 0u) << "a bound view kept the device alive";
  EXPECT_TRUE(validation.empty()) << validation.front();
}

}  // namespace
}  // namespace rhi_test
