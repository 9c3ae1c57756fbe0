// The context's getters: each returns what its setter bound, with a reference
// (D3D11's getters AddRef), and imgui_impl_dx11's save / change / restore of
// the whole pipeline state leaves the state, and what a draw produces, as before.
#include "gpu_helpers.h"
#include "rhi/stage_methods.h"

namespace rhi_test {
namespace {

using namespace rhi;

// The application's reference count of `object` (AddRef then Release returns it).
UINT References(Unknown* object) {
  object->AddRef();
  return object->Release();
}

// One test covers all six stages through rhi/stage_methods.h.
using StageApi = rhi::StageMethods;

class ContextGettersTest : public RhiGpuTest {
 protected:
  ComPtr<ShaderResourceView> TextureView() {
    ComPtr<Texture2D> texture = MakeTexture(4, 4, DXGI_FORMAT_R8G8B8A8_UNORM, BIND_SHADER_RESOURCE);
    ComPtr<ShaderResourceView> srv;
    EXPECT_EQ(device->CreateShaderResourceView(texture.Get(), nullptr, srv.GetAddressOf()), S_OK);
    return srv;
  }
};

class StageGettersTest : public ContextGettersTest, public ::testing::WithParamInterface<StageApi> {};

TEST_P(StageGettersTest, StageBindingsRoundTripWithAReferenceEach) {
  const StageApi& api = GetParam();
  const float constants[4] = {};
  ComPtr<Buffer> cb = MakeBuffer(BIND_CONSTANT_BUFFER, constants, sizeof constants);
  ComPtr<ShaderResourceView> srv = TextureView();
  ComPtr<SamplerState> sampler = PointSampler();
  Buffer* cbs[] = {cb.Get()};
  ShaderResourceView* srvs[] = {srv.Get()};
  SamplerState* samplers[] = {sampler.Get()};
  // Slot 2 of each; slots 1 and 3 stay empty.
  (context.Get()->*api.setConstantBuffers)(2, 1, cbs);
  (context.Get()->*api.setShaderResources)(2, 1, srvs);
  (context.Get()->*api.setSamplers)(2, 1, samplers);
  const UINT cbRefs = References(cb.Get()), srvRefs = References(srv.Get()), samplerRefs = References(sampler.Get());

  Buffer* gotCbs[3] = {};
  ShaderResourceView* gotSrvs[3] = {};
  SamplerState* gotSamplers[3] = {};
  (context.Get()->*api.getConstantBuffers)(1, 3, gotCbs);
  (context.Get()->*api.getShaderResources)(1, 3, gotSrvs);
  (context.Get()->*api.getSamplers)(1, 3, gotSamplers);
  EXPECT_EQ(gotCbs[0], nullptr);
  EXPECT_EQ(gotCbs[1], cb.Get());
  EXPECT_EQ(gotCbs[2], nullptr);
  EXPECT_EQ(gotSrvs[0], nullptr);
  EXPECT_EQ(gotSrvs[1], srv.Get());
  EXPECT_EQ(gotSrvs[2], nullptr);
  EXPECT_EQ(gotSamplers[0], nullptr);
  EXPECT_EQ(gotSamplers[1], sampler.Get());
  EXPECT_EQ(gotSamplers[2], nullptr);
  EXPECT_EQ(References(cb.Get()), cbRefs + 1) << "the getter AddRefs";
  EXPECT_EQ(References(srv.Get()), srvRefs + 1);
  EXPECT_EQ(References(sampler.Get()), samplerRefs + 1);
  gotCbs[1]->Release();
  gotSrvs[1]->Release();
  gotSamplers[1]->Release();

  // Slots past the last one read as empty rather than out of bounds.
  Buffer* pastEnd = cb.Get();
  (context.Get()->*api.getConstantBuffers)(COMMONSHADER_CONSTANT_BUFFER_API_SLOT_COUNT, 1, &pastEnd);
  EXPECT_EQ(pastEnd, nullptr);
  context->ClearState();
  (context.Get()->*api.getConstantBuffers)(2, 1, gotCbs);
  EXPECT_EQ(gotCbs[0], nullptr) << "ClearState empties the slot";
}

INSTANTIATE_TEST_SUITE_P(AllStages, StageGettersTest, ::testing::ValuesIn(rhi::kStageMethods),
                         [](const auto& info) { return std::string(info.param.name); });

TEST_F(ContextGettersTest, ShaderGettersReturnTheBoundShaderOfEachStageAndNoClassInstances) {
  constexpr const char* kHS = R"(
    struct P { float4 pos : POSITION; };
    struct C { float edges[3] : SV_TessFactor; float inside : SV_InsideTessFactor; };
    C Constants(InputPatch<P, 3> patch) { C c; c.edges[0] = c.edges[1] = c.edges[2] = 1; c.inside = 1; return c; }
    [domain("tri")] [partitioning("integer")] [outputtopology("triangle_cw")] [outputcontrolpoints(3)]
    [patchconstantfunc("Constants")]
    P main(InputPatch<P, 3> patch, uint i : SV_OutputControlPointID) { return patch[i]; })";
  constexpr const char* kDS = R"(
    struct P { float4 pos : POSITION; };
    struct C { float edges[3] : SV_TessFactor; float inside : SV_InsideTessFactor; };
    [domain("tri")]
    float4 main(C c, float3 uvw : SV_DomainLocation, const OutputPatch<P, 3> patch) : SV_Position {
      return patch[0].pos * uvw.x + patch[1].pos * uvw.y + patch[2].pos * uvw.z;
    })";
  constexpr const char* kGS = R"(
    struct V { float4 pos : SV_Position; };
    [maxvertexcount(1)] void main(point V v[1], inout PointStream<V> s) { s.Append(v[0]); })";
  UseColorPipeline();
  const std::vector<uint32_t> hsCode = CompileHlsl(kHS, "main", "hs_5_0");
  const std::vector<uint32_t> dsCode = CompileHlsl(kDS, "main", "ds_5_0");
  ComPtr<HullShader> hs;
  ComPtr<DomainShader> ds;
  ASSERT_EQ(device->CreateHullShader(hsCode.data(), hsCode.size() * 4, nullptr, hs.GetAddressOf()), S_OK);
  ASSERT_EQ(device->CreateDomainShader(dsCode.data(), dsCode.size() * 4, nullptr, ds.GetAddressOf()), S_OK);
  ComPtr<GeometryShader> gs = GS(kGS);
  ComPtr<ComputeShader> cs = CS("[numthreads(1, 1, 1)] void main() {}");
  context->HSSetShader(hs.Get(), nullptr, 0);
  context->DSSetShader(ds.Get(), nullptr, 0);
  context->GSSetShader(gs.Get(), nullptr, 0);
  context->CSSetShader(cs.Get(), nullptr, 0);

  // Each getter: the bound object, one more reference, and no class instances.
  auto check = [](auto get, auto* bound) {
    const UINT before = References(bound);
    decltype(bound) got = nullptr;
    UINT instances = 99;
    get(&got, &instances);
    EXPECT_EQ(got, bound);
    EXPECT_EQ(instances, 0u);
    EXPECT_EQ(References(bound), before + 1);
    if (got) got->Release();
  };
  check([&](VertexShader** s, UINT* n) { context->VSGetShader(s, nullptr, n); }, colorVS_.Get());
  check([&](HullShader** s, UINT* n) { context->HSGetShader(s, nullptr, n); }, hs.Get());
  check([&](DomainShader** s, UINT* n) { context->DSGetShader(s, nullptr, n); }, ds.Get());
  check([&](GeometryShader** s, UINT* n) { context->GSGetShader(s, nullptr, n); }, gs.Get());
  check([&](PixelShader** s, UINT* n) { context->PSGetShader(s, nullptr, n); }, colorPS_.Get());
  check([&](ComputeShader** s, UINT* n) { context->CSGetShader(s, nullptr, n); }, cs.Get());
  context->ClearState();
  PixelShader* none = colorPS_.Get();
  context->PSGetShader(&none, nullptr, nullptr);
  EXPECT_EQ(none, nullptr);
}

TEST_F(ContextGettersTest, ComputeUavsRoundTripWithAReferenceEach) {
  ComPtr<Texture2D> texture = MakeTexture(4, 4, DXGI_FORMAT_R32_FLOAT, BIND_UNORDERED_ACCESS);
  ComPtr<UnorderedAccessView> uav;
  ASSERT_EQ(device->CreateUnorderedAccessView(texture.Get(), nullptr, uav.GetAddressOf()), S_OK);
  UnorderedAccessView* uavs[] = {uav.Get()};
  context->CSSetUnorderedAccessViews(3, 1, uavs, nullptr);
  const UINT before = References(uav.Get());
  UnorderedAccessView* got[2] = {};
  context->CSGetUnorderedAccessViews(2, 2, got);
  EXPECT_EQ(got[0], nullptr);
  EXPECT_EQ(got[1], uav.Get());
  EXPECT_EQ(References(uav.Get()), before + 1);
  got[1]->Release();
}

TEST_F(ContextGettersTest, DefaultStateReadsAsD3D11Defaults) {
  BlendState* blend = nullptr;
  FLOAT factor[4] = {};
  UINT mask = 0;
  context->OMGetBlendState(&blend, factor, &mask);
  EXPECT_EQ(blend, nullptr);
  EXPECT_EQ(mask, DEFAULT_SAMPLE_MASK);
  for (FLOAT f : factor) EXPECT_EQ(f, 1.0f);
  DepthStencilState* depth = nullptr;
  UINT ref = 7;
  context->OMGetDepthStencilState(&depth, &ref);
  EXPECT_EQ(depth, nullptr);
  EXPECT_EQ(ref, 0u);
  PRIMITIVE_TOPOLOGY topology = PRIMITIVE_TOPOLOGY_TRIANGLELIST;
  context->IAGetPrimitiveTopology(&topology);
  EXPECT_EQ(topology, PRIMITIVE_TOPOLOGY_UNDEFINED);
  UINT count = 5;
  context->RSGetViewports(&count, nullptr);
  EXPECT_EQ(count, 0u);
  count = 5;
  context->RSGetScissorRects(&count, nullptr);
  EXPECT_EQ(count, 0u);
}

// The state imgui_impl_dx11.cpp backs up around its draw (BACKUP_DX11_STATE),
// with the references its getters hand out.
struct SavedState {
  UINT scissorCount = VIEWPORT_AND_SCISSORRECT_OBJECT_COUNT_PER_PIPELINE, viewportCount = scissorCount;
  RECT scissors[VIEWPORT_AND_SCISSORRECT_OBJECT_COUNT_PER_PIPELINE];
  VIEWPORT viewports[VIEWPORT_AND_SCISSORRECT_OBJECT_COUNT_PER_PIPELINE];
  ComPtr<RasterizerState> rasterizer;
  ComPtr<BlendState> blend;
  FLOAT blendFactor[4];
  UINT sampleMask;
  UINT stencilRef;
  ComPtr<DepthStencilState> depthStencil;
  ComPtr<ShaderResourceView> psResource;
  ComPtr<SamplerState> psSampler;
  ComPtr<PixelShader> ps;
  ComPtr<VertexShader> vs;
  ComPtr<GeometryShader> gs;
  ComPtr<Buffer> vsConstants;
  PRIMITIVE_TOPOLOGY topology;
  ComPtr<Buffer> indexBuffer, vertexBuffer;
  UINT vertexStride, vertexOffset, indexOffset;
  DXGI_FORMAT indexFormat;
  ComPtr<InputLayout> inputLayout;
  ComPtr<RenderTargetView> renderTarget;
  ComPtr<DepthStencilView> depthTarget;

  void Save(DeviceContext* c) {
    viewportCount = scissorCount = VIEWPORT_AND_SCISSORRECT_OBJECT_COUNT_PER_PIPELINE;
    c->RSGetScissorRects(&scissorCount, nullptr);
    c->RSGetScissorRects(&scissorCount, scissors);
    c->RSGetViewports(&viewportCount, nullptr);
    c->RSGetViewports(&viewportCount, viewports);
    c->RSGetState(rasterizer.ReleaseAndGetAddressOf());
    c->OMGetBlendState(blend.ReleaseAndGetAddressOf(), blendFactor, &sampleMask);
    c->OMGetDepthStencilState(depthStencil.ReleaseAndGetAddressOf(), &stencilRef);
    c->PSGetShaderResources(0, 1, psResource.ReleaseAndGetAddressOf());
    c->PSGetSamplers(0, 1, psSampler.ReleaseAndGetAddressOf());
    c->PSGetShader(ps.ReleaseAndGetAddressOf(), nullptr, nullptr);
    c->VSGetShader(vs.ReleaseAndGetAddressOf(), nullptr, nullptr);
    c->VSGetConstantBuffers(0, 1, vsConstants.ReleaseAndGetAddressOf());
    c->GSGetShader(gs.ReleaseAndGetAddressOf(), nullptr, nullptr);
    c->IAGetPrimitiveTopology(&topology);
    c->IAGetIndexBuffer(indexBuffer.ReleaseAndGetAddressOf(), &indexFormat, &indexOffset);
    c->IAGetVertexBuffers(0, 1, vertexBuffer.ReleaseAndGetAddressOf(), &vertexStride, &vertexOffset);
    c->IAGetInputLayout(inputLayout.ReleaseAndGetAddressOf());
    c->OMGetRenderTargets(1, renderTarget.ReleaseAndGetAddressOf(), depthTarget.ReleaseAndGetAddressOf());
  }

  void Restore(DeviceContext* c) const {
    c->RSSetScissorRects(scissorCount, scissors);
    c->RSSetViewports(viewportCount, viewports);
    c->RSSetState(rasterizer.Get());
    c->OMSetBlendState(blend.Get(), blendFactor, sampleMask);
    c->OMSetDepthStencilState(depthStencil.Get(), stencilRef);
    ShaderResourceView* srv = psResource.Get();
    c->PSSetShaderResources(0, 1, &srv);
    SamplerState* sampler = psSampler.Get();
    c->PSSetSamplers(0, 1, &sampler);
    c->PSSetShader(ps.Get(), nullptr, 0);
    c->VSSetShader(vs.Get(), nullptr, 0);
    Buffer* constants = vsConstants.Get();
    c->VSSetConstantBuffers(0, 1, &constants);
    c->GSSetShader(gs.Get(), nullptr, 0);
    c->IASetPrimitiveTopology(topology);
    c->IASetIndexBuffer(indexBuffer.Get(), indexFormat, indexOffset);
    Buffer* vb = vertexBuffer.Get();
    c->IASetVertexBuffers(0, 1, &vb, &vertexStride, &vertexOffset);
    c->IASetInputLayout(inputLayout.Get());
    RenderTargetView* rtv = renderTarget.Get();
    c->OMSetRenderTargets(1, &rtv, depthTarget.Get());
  }
};

bool Same(const VIEWPORT& a, const VIEWPORT& b) {
  return a.TopLeftX == b.TopLeftX && a.TopLeftY == b.TopLeftY && a.Width == b.Width && a.Height == b.Height &&
         a.MinDepth == b.MinDepth && a.MaxDepth == b.MaxDepth;
}
bool Same(const RECT& a, const RECT& b) {
  return a.left == b.left && a.top == b.top && a.right == b.right && a.bottom == b.bottom;
}

TEST_F(ContextGettersTest, ImguiStyleSaveChangeRestoreGivesBackTheStateAndTheImage) {
  // State A: the colour pipeline into an 8x8 target, a blend factor, a
  // scissor cutting the right half, a stencil reference, an SRV and sampler.
  Target target = MakeRenderTarget(8, 8);
  Clear(target.rtv.Get(), kBlack);
  BindTarget(target.rtv.Get(), 8, 8);
  UseColorPipeline();
  RASTERIZER_DESC scissorOn;
  scissorOn.ScissorEnable = TRUE;
  ComPtr<RasterizerState> rasterizer = Rasterizer(scissorOn);
  context->RSSetState(rasterizer.Get());
  const RECT scissor{0, 0, 4, 8};
  context->RSSetScissorRects(1, &scissor);
  BLEND_DESC blendFactorDesc;
  blendFactorDesc.RenderTarget[0].BlendEnable = TRUE;
  blendFactorDesc.RenderTarget[0].SrcBlend = BLEND_BLEND_FACTOR;
  blendFactorDesc.RenderTarget[0].DestBlend = BLEND_ZERO;
  ComPtr<BlendState> blend = Blend(blendFactorDesc);
  const FLOAT factor[4] = {0, 1, 0, 1};  // keeps only green
  context->OMSetBlendState(blend.Get(), factor, 0xffu);
  ComPtr<DepthStencilState> depth = DepthStencil(DEPTH_STENCIL_DESC{});
  context->OMSetDepthStencilState(depth.Get(), 3);
  ComPtr<ShaderResourceView> srv = TextureView();
  ShaderResourceView* srvs[] = {srv.Get()};
  context->PSSetShaderResources(0, 1, srvs);
  ComPtr<SamplerState> sampler = PointSampler();
  SamplerState* samplers[] = {sampler.Get()};
  context->PSSetSamplers(0, 1, samplers);
  const std::vector<Vertex> quad = Quad(0, 0, 8, 8, kWhite, 8, 8);
  ComPtr<Buffer> vb = VertexBuffer(quad);
  const UINT stride = sizeof(Vertex), offset = 0;
  Buffer* vbs[] = {vb.Get()};
  context->IASetVertexBuffers(0, 1, vbs, &stride, &offset);
  context->Draw(6, 0);
  const std::vector<uint8_t> before = ReadTexture(target.texture.Get());
  EXPECT_EQ(Picture(before, 8, 8, kLegend), Rows(8, "GGGG...."));

  SavedState saved;
  saved.Save(context.Get());
  // State B: everything cleared, then other objects bound (as imgui's own draw does).
  context->ClearState();
  Target other = MakeRenderTarget(8, 8);
  BindTarget(other.rtv.Get(), 8, 8);
  UseColorPipeline();
  DrawVertices(Quad(0, 0, 8, 8, kRed, 8, 8));
  saved.Restore(context.Get());

  SavedState restored;
  restored.Save(context.Get());
  EXPECT_EQ(restored.scissorCount, 1u);
  EXPECT_TRUE(Same(restored.scissors[0], scissor));
  EXPECT_EQ(restored.viewportCount, 1u);
  EXPECT_TRUE(Same(restored.viewports[0], saved.viewports[0]));
  EXPECT_EQ(restored.rasterizer.Get(), rasterizer.Get());
  EXPECT_EQ(restored.blend.Get(), blend.Get());
  EXPECT_EQ(std::vector<FLOAT>(restored.blendFactor, restored.blendFactor + 4), std::vector<FLOAT>(factor, factor + 4));
  EXPECT_EQ(restored.sampleMask, 0xffu);
  EXPECT_EQ(restored.depthStencil.Get(), depth.Get());
  EXPECT_EQ(restored.stencilRef, 3u);
  EXPECT_EQ(restored.psResource.Get(), srv.Get());
  EXPECT_EQ(restored.psSampler.Get(), sampler.Get());
  EXPECT_EQ(restored.ps.Get(), colorPS_.Get());
  EXPECT_EQ(restored.vs.Get(), colorVS_.Get());
  EXPECT_EQ(restored.gs.Get(), nullptr);
  EXPECT_EQ(restored.topology, PRIMITIVE_TOPOLOGY_TRIANGLELIST);
  EXPECT_EQ(restored.vertexBuffer.Get(), vb.Get());
  EXPECT_EQ(restored.vertexStride, stride);
  EXPECT_EQ(restored.inputLayout.Get(), colorLayout_.Get());
  EXPECT_EQ(restored.renderTarget.Get(), target.rtv.Get());
  EXPECT_EQ(restored.depthTarget.Get(), nullptr);

  // The restored state draws what state A drew.
  Clear(target.rtv.Get(), kBlack);
  context->Draw(6, 0);
  EXPECT_EQ(ReadTexture(target.texture.Get()), before);
}

}  // namespace
}  // namespace rhi_test
