// Every query type: exact counts where D3D11 defines them. GetData may return
// S_FALSE until the GPU is done; WaitForData loops until S_OK.
#include "gpu_helpers.h"

namespace rhi_test {
namespace {

using namespace rhi;

class QueryTest : public RhiGpuTest {
 protected:
  void SetUp() override {
    RhiGpuTest::SetUp();
    if (HasFatalFailure()) return;
    target_ = MakeRenderTarget(16, 16);
    BindTarget(target_.rtv.Get(), 16, 16);
    Clear(target_.rtv.Get(), kBlack);
    UseColorPipeline();
  }
  ComPtr<Query> MakeQuery(QUERY type) {
    QUERY_DESC desc{type, 0};
    ComPtr<Query> query;
    EXPECT_EQ(device->CreateQuery(&desc, query.GetAddressOf()), S_OK);
    return query;
  }
  // A 4x4-pixel quad at [2,6) x [3,7): 16 pixels, 2 triangles, 6 vertices.
  void DrawKnownQuad() { DrawVertices(Quad(2, 3, 6, 7, kWhite, 16, 16)); }

  Target target_;
};

TEST_F(QueryTest, OcclusionCountsExactlyTheSamplesThatPass) {
  auto query = MakeQuery(QUERY_OCCLUSION);
  context->Begin(query.Get());
  DrawKnownQuad();
  context->End(query.Get());
  EXPECT_EQ(WaitForData<UINT64>(query.Get()), 16u);

  // A counter-clockwise (culled) quad passes no samples.
  auto culled = MakeQuery(QUERY_OCCLUSION);
  context->Begin(culled.Get());
  DrawVertices(Quad(2, 3, 6, 7, kWhite, 16, 16, 0.5f, false));
  context->End(culled.Get());
  EXPECT_EQ(WaitForData<UINT64>(culled.Get()), 0u);
}

TEST_F(QueryTest, OcclusionPredicateIsTrueWhenAnySamplePassed) {
  auto visible = MakeQuery(QUERY_OCCLUSION_PREDICATE);
  context->Begin(visible.Get());
  DrawKnownQuad();
  context->End(visible.Get());
  EXPECT_EQ(WaitForData<BOOL>(visible.Get()), TRUE);

  auto hidden = MakeQuery(QUERY_OCCLUSION_PREDICATE);
  context->Begin(hidden.Get());
  DrawVertices(Quad(2, 3, 6, 7, kWhite, 16, 16, 0.5f, false));
  context->End(hidden.Get());
  EXPECT_EQ(WaitForData<BOOL>(hidden.Get()), FALSE);
}

TEST_F(QueryTest, TimestampsInsideDisjointQueryAreOrderedWithPositiveFrequency) {
  auto disjoint = MakeQuery(QUERY_TIMESTAMP_DISJOINT);
  auto t0 = MakeQuery(QUERY_TIMESTAMP);
  auto t1 = MakeQuery(QUERY_TIMESTAMP);
  context->Begin(disjoint.Get());
  context->End(t0.Get());
  DrawKnownQuad();
  context->End(t1.Get());
  context->End(disjoint.Get());
  const auto info = WaitForData<QUERY_DATA_TIMESTAMP_DISJOINT>(disjoint.Get());
  EXPECT_GT(info.Frequency, 0u);
  const UINT64 start = WaitForData<UINT64>(t0.Get());
  const UINT64 end = WaitForData<UINT64>(t1.Get());
  EXPECT_GE(end, start);
}

TEST_F(QueryTest, PipelineStatisticsCountInputAssemblyVertexAndPixelWork) {
  // Draw(6) of a triangle list: 6 vertices, 2 primitives, 6 vertex shader
  // invocations (no index reuse in a non-indexed draw); at least 16 pixel shader
  // invocations for the 16 covered pixels (helpers may add more).
  auto query = MakeQuery(QUERY_PIPELINE_STATISTICS);
  context->Begin(query.Get());
  DrawKnownQuad();
  context->End(query.Get());
  const auto stats = WaitForData<QUERY_DATA_PIPELINE_STATISTICS>(query.Get());
  EXPECT_EQ(stats.IAVertices, 6u);
  EXPECT_EQ(stats.IAPrimitives, 2u);
  EXPECT_EQ(stats.VSInvocations, 6u);
  EXPECT_EQ(stats.CInvocations, 2u);
  EXPECT_GE(stats.PSInvocations, 16u);
  EXPECT_EQ(stats.GSInvocations, 0u);
  EXPECT_EQ(stats.CSInvocations, 0u);
}

TEST_F(QueryTest, EventQueryCompletesAndPollingWithoutDataIsAllowed) {
  auto event = MakeQuery(QUERY_EVENT);
  DrawKnownQuad();
  context->End(event.Get());
  // D3D11 allows polling with no output buffer: S_FALSE until done, then S_OK.
  HRESULT hr;
  while ((hr = context->GetData(event.Get(), nullptr, 0, 0)) == S_FALSE) {
  }
  EXPECT_EQ(hr, S_OK);
  EXPECT_EQ(WaitForData<BOOL>(event.Get()), TRUE);
}

TEST_F(QueryTest, GetDataRefusesDataSizeThatDoesNotMatchTheQuery) {
  auto query = MakeQuery(QUERY_OCCLUSION);
  EXPECT_EQ(query->GetDataSize(), sizeof(UINT64));
  context->Begin(query.Get());
  DrawKnownQuad();
  context->End(query.Get());
  uint32_t tooSmall = 0;
  EXPECT_EQ(context->GetData(query.Get(), &tooSmall, sizeof tooSmall, 0), E_INVALIDARG);
  EXPECT_EQ(WaitForData<UINT64>(query.Get()), 16u);
}

// Stream output from the colour vertex shader (VS-only SO): COLOR of each
// vertex goes to the buffer, 16 bytes a vertex. Vertex i has colour (i, 0, 0, 1).
class StreamOutQueryTest : public QueryTest {
 protected:
  void SetUp() override {
    QueryTest::SetUp();
    if (HasFatalFailure()) return;
    std::vector<uint32_t> code = CompileHlsl(kColorVS, "main", "vs_5_0");
    const SO_DECLARATION_ENTRY decl[] = {{0, "COLOR", 0, 0, 4, 0}};
    const UINT stride = 16;
    ASSERT_EQ(device->CreateGeometryShaderWithStreamOutput(code.data(), code.size() * 4, decl, 1, &stride, 1, 0,
                                                           nullptr, so_.GetAddressOf()),
              S_OK);
    vertices_ = Quad(2, 3, 6, 7, kWhite, 16, 16);
    for (size_t i = 0; i < vertices_.size(); ++i) vertices_[i].color = {static_cast<float>(i), 0, 0, 1};
  }
  // Draws the 6 vertices (2 triangles) with stream output into `buffer`.
  void DrawWithStreamOut(Buffer* buffer) {
    const UINT offset = 0;
    context->SOSetTargets(1, &buffer, &offset);
    context->GSSetShader(so_.Get(), nullptr, 0);
    DrawVertices(vertices_);
    context->GSSetShader(nullptr, nullptr, 0);
    context->SOSetTargets(0, nullptr, nullptr);
  }
  ComPtr<GeometryShader> so_;
  std::vector<Vertex> vertices_;
};

TEST_F(StreamOutQueryTest, SoStatisticsCountWrittenPrimitivesAndTheBufferHoldsThem) {
  ComPtr<Buffer> buffer = MakeBuffer(BIND_STREAM_OUTPUT, nullptr, 6 * 16);
  auto stats = MakeQuery(QUERY_SO_STATISTICS);
  context->Begin(stats.Get());
  DrawWithStreamOut(buffer.Get());
  context->End(stats.Get());
  const auto data = WaitForData<QUERY_DATA_SO_STATISTICS>(stats.Get());
  EXPECT_EQ(data.NumPrimitivesWritten, 2u);
  EXPECT_EQ(data.PrimitivesStorageNeeded, 2u);
  std::vector<float> expected;
  for (int i = 0; i < 6; ++i) expected.insert(expected.end(), {static_cast<float>(i), 0, 0, 1});
  EXPECT_EQ(ReadBufferAs<float>(buffer.Get()), expected);
}

TEST_F(StreamOutQueryTest, SoOverflowPredicateIsTrueWhenTheBufferIsTooSmall) {
  // Room for one triangle (3 vertices, 48 bytes) of the two: 1 written, 2 needed.
  ComPtr<Buffer> buffer = MakeBuffer(BIND_STREAM_OUTPUT, nullptr, 3 * 16);
  auto stats = MakeQuery(QUERY_SO_STATISTICS);
  auto overflow = MakeQuery(QUERY_SO_OVERFLOW_PREDICATE);
  context->Begin(stats.Get());
  context->Begin(overflow.Get());
  DrawWithStreamOut(buffer.Get());
  context->End(overflow.Get());
  context->End(stats.Get());
  EXPECT_EQ(WaitForData<BOOL>(overflow.Get()), TRUE);
  const auto data = WaitForData<QUERY_DATA_SO_STATISTICS>(stats.Get());
  EXPECT_EQ(data.NumPrimitivesWritten, 1u);
  EXPECT_EQ(data.PrimitivesStorageNeeded, 2u);

  ComPtr<Buffer> large = MakeBuffer(BIND_STREAM_OUTPUT, nullptr, 6 * 16);
  auto noOverflow = MakeQuery(QUERY_SO_OVERFLOW_PREDICATE);
  context->Begin(noOverflow.Get());
  DrawWithStreamOut(large.Get());
  context->End(noOverflow.Get());
  EXPECT_EQ(WaitForData<BOOL>(noOverflow.Get()), FALSE);
}

}  // namespace
}  // namespace rhi_test
