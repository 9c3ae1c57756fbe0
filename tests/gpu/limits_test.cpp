// D3D11's bounds on the counts of context calls: a call over one is dropped
// and the reason reported (the debug layer's role), a call at the bound runs.
#include <functional>
#include <vector>

#include "gpu_helpers.h"

namespace rhi_test {
namespace {

using namespace rhi;

struct LimitCase {
  const char* name;
  UINT limit;
  // Makes the call with `count` (the limit, then one more); all arrays hold count nulls.
  std::function<void(DeviceContext*, UINT count)> call;
  const char* reason;  // a fragment of the refusal of count = limit + 1
};

class CallLimitTest : public RhiGpuTest, public ::testing::WithParamInterface<LimitCase> {};

TEST_P(CallLimitTest, AtTheLimitRunsAndOverItIsRefused) {
  const LimitCase& limit = GetParam();
  limit.call(context.Get(), limit.limit);
  EXPECT_TRUE(Refusals().empty()) << Refusals().front();
  limit.call(context.Get(), limit.limit + 1);
  EXPECT_TRUE(RefusedWith(limit.reason)) << (Refusals().empty() ? "no refusal" : Refusals().front());
}

// Arrays of `count` nulls / zeros for the calls.
std::vector<void*> Nulls(UINT count) { return std::vector<void*>(count, nullptr); }
std::vector<UINT> Zeros(UINT count) { return std::vector<UINT>(count, 0); }

template <class T>
T* const* NullArray(const std::vector<void*>& nulls) {
  return reinterpret_cast<T* const*>(nulls.data());
}

const LimitCase kLimits[] = {
    {"IASetVertexBuffers", IA_VERTEX_INPUT_RESOURCE_SLOT_COUNT,
     [](DeviceContext* c, UINT n) {
       auto nulls = Nulls(n);
       auto zeros = Zeros(n);
       c->IASetVertexBuffers(0, n, NullArray<Buffer>(nulls), zeros.data(), zeros.data());
     },
     "IASetVertexBuffers: StartSlot (0) + the count (33) exceeds the 32 slots; the call is ignored"},
    {"VSSetConstantBuffers", COMMONSHADER_CONSTANT_BUFFER_API_SLOT_COUNT,
     [](DeviceContext* c, UINT n) {
       auto nulls = Nulls(n);
       c->VSSetConstantBuffers(0, n, NullArray<Buffer>(nulls));
     },
     "VSSetConstantBuffers: StartSlot (0) + the count (15) exceeds the 14 slots"},
    {"PSSetShaderResources", COMMONSHADER_INPUT_RESOURCE_SLOT_COUNT,
     [](DeviceContext* c, UINT n) {
       auto nulls = Nulls(n);
       c->PSSetShaderResources(0, n, NullArray<ShaderResourceView>(nulls));
     },
     "PSSetShaderResources: StartSlot (0) + the count (129) exceeds the 128 slots"},
    {"CSSetSamplers", COMMONSHADER_SAMPLER_SLOT_COUNT,
     [](DeviceContext* c, UINT n) {
       auto nulls = Nulls(n);
       c->CSSetSamplers(0, n, NullArray<SamplerState>(nulls));
     },
     "CSSetSamplers: StartSlot (0) + the count (17) exceeds the 16 slots"},
    {"CSSetUnorderedAccessViews", PS_CS_UAV_REGISTER_COUNT,
     [](DeviceContext* c, UINT n) {
       auto nulls = Nulls(n);
       c->CSSetUnorderedAccessViews(0, n, NullArray<UnorderedAccessView>(nulls), nullptr);
     },
     "CSSetUnorderedAccessViews: StartSlot (0) + NumUAVs (9) exceeds the 8"},
    {"SOSetTargets", SO_BUFFER_SLOT_COUNT,
     [](DeviceContext* c, UINT n) {
       auto nulls = Nulls(n);
       auto zeros = Zeros(n);
       c->SOSetTargets(n, NullArray<Buffer>(nulls), zeros.data());
     },
     "SOSetTargets: NumBuffers (5) exceeds 4; the call is ignored"},
    {"RSSetViewports", VIEWPORT_AND_SCISSORRECT_OBJECT_COUNT_PER_PIPELINE,
     [](DeviceContext* c, UINT n) {
       std::vector<VIEWPORT> viewports(n, VIEWPORT{0, 0, 4, 4, 0, 1});
       c->RSSetViewports(n, viewports.data());
     },
     "RSSetViewports: NumViewports (17) exceeds 16; the call is ignored"},
    {"RSSetScissorRects", VIEWPORT_AND_SCISSORRECT_OBJECT_COUNT_PER_PIPELINE,
     [](DeviceContext* c, UINT n) {
       std::vector<RECT> rects(n, RECT{0, 0, 4, 4});
       c->RSSetScissorRects(n, rects.data());
     },
     "RSSetScissorRects: NumRects (17) exceeds 16; the call is ignored"},
    {"OMSetRenderTargets", SIMULTANEOUS_RENDER_TARGET_COUNT,
     [](DeviceContext* c, UINT n) {
       auto nulls = Nulls(n);
       c->OMSetRenderTargets(n, NullArray<RenderTargetView>(nulls), nullptr);
     },
     "OMSetRenderTargets: NumRTVs (9) exceeds SIMULTANEOUS_RENDER_TARGET_COUNT (8)"},
};

INSTANTIATE_TEST_SUITE_P(D3D11Bounds, CallLimitTest, ::testing::ValuesIn(kLimits),
                         [](const ::testing::TestParamInfo<LimitCase>& info) { return info.param.name; });

// Dispatch: 65,535 groups per dimension (D3D11_CS_DISPATCH_MAX_THREAD_GROUPS_PER_DIMENSION).
// The shader marks a buffer, so the test sees whether a dispatch ran.
class DispatchLimitTest : public RhiGpuTest, public ::testing::WithParamInterface<int> {};

TEST_P(DispatchLimitTest, AtTheLimitRunsAndOverItIsSkipped) {
  const int dimension = GetParam();
  ComPtr<ComputeShader> cs = CS(R"(
    RWByteAddressBuffer marks : register(u0);
    [numthreads(1, 1, 1)] void main(uint3 group : SV_GroupID) { if (all(group == 0)) marks.Store(0, 1); })");
  const UINT zero = 0;
  ComPtr<Buffer> buffer =
      MakeBuffer(BIND_UNORDERED_ACCESS, &zero, 4, USAGE_DEFAULT, RESOURCE_MISC_BUFFER_ALLOW_RAW_VIEWS);
  UNORDERED_ACCESS_VIEW_DESC desc{};
  desc.Format = DXGI_FORMAT_R32_TYPELESS;
  desc.ViewDimension = UAV_DIMENSION_BUFFER;
  desc.Buffer = {0, 1, BUFFER_UAV_FLAG_RAW};
  ComPtr<UnorderedAccessView> uav;
  ASSERT_EQ(device->CreateUnorderedAccessView(buffer.Get(), &desc, uav.GetAddressOf()), S_OK);
  context->CSSetShader(cs.Get(), nullptr, 0);
  context->CSSetUnorderedAccessViews(0, 1, uav.GetAddressOf(), nullptr);

  auto groups = [&](UINT count) {
    UINT g[3] = {1, 1, 1};
    g[dimension] = count;
    context->Dispatch(g[0], g[1], g[2]);
  };
  groups(CS_DISPATCH_MAX_THREAD_GROUPS_PER_DIMENSION + 1);
  EXPECT_TRUE(RefusedWith("exceeds D3D11_CS_DISPATCH_MAX_THREAD_GROUPS_PER_DIMENSION (65535); the dispatch is skipped"));
  context->CSSetUnorderedAccessViews(0, 1, std::vector<UnorderedAccessView*>{nullptr}.data(), nullptr);
  EXPECT_EQ(ReadBufferAs<UINT>(buffer.Get())[0], 0u) << "the refused dispatch ran";

  ClearMessages();
  context->CSSetUnorderedAccessViews(0, 1, uav.GetAddressOf(), nullptr);
  groups(CS_DISPATCH_MAX_THREAD_GROUPS_PER_DIMENSION);
  context->CSSetUnorderedAccessViews(0, 1, std::vector<UnorderedAccessView*>{nullptr}.data(), nullptr);
  EXPECT_TRUE(Refusals().empty()) << Refusals().front();
  EXPECT_EQ(ReadBufferAs<UINT>(buffer.Get())[0], 1u);
}

INSTANTIATE_TEST_SUITE_P(D3D11Bounds, DispatchLimitTest, ::testing::Values(0, 1, 2),
                         [](const ::testing::TestParamInfo<int>& info) { return std::string(1, "XYZ"[info.param]); });

}  // namespace
}  // namespace rhi_test
