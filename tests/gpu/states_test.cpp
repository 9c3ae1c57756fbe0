// The effect of every state object on exact pixels, NULL states as the D3D11
// defaults, refusal of invalid descriptions, and deduplication.
//
// UNORM8 results: value * 255 rounded to nearest (0.25 -> 63.75 -> 64,
// 0.75 -> 191.25 -> 191, 0.875 -> 223.125 -> 223). Colours come from flat
// (nointerpolation) vertex attributes, so they reach the blender unchanged.
#include <cstdio>

#include "gpu_helpers.h"

namespace rhi_test {
namespace {

using namespace rhi;

class StateTest : public RhiGpuTest {
 protected:
  void SetUp() override {
    RhiGpuTest::SetUp();
    if (HasFatalFailure()) return;
    target_ = MakeRenderTarget(8, 8);
    BindTarget(target_.rtv.Get(), 8, 8);
    Clear(target_.rtv.Get(), kBlack);
    UseColorPipeline();
  }
  std::vector<uint8_t> Pixels() { return ReadTexture(target_.texture.Get()); }
  std::vector<std::string> Result() { return Picture(Pixels(), 8, 8, kLegend); }
  // Binds a depth-stencil target of `format` next to the colour target.
  void UseDepth(DXGI_FORMAT format) {
    depth_ = MakeDepthTarget(8, 8, format);
    BindTarget(target_.rtv.Get(), 8, 8, depth_.dsv.Get());
  }

  Target target_;
  DepthTarget depth_;
};

// ---------------------------------------------------------------------------
// Rasterizer

TEST_F(StateTest, CullModeAndFrontCounterClockwiseSelectWhichWindingIsDrawn) {
  // Left half: a triangle pair clockwise on screen (red); right half:
  // counter-clockwise (green). D3D11: with FrontCounterClockwise FALSE the
  // clockwise triangles are front-facing; with TRUE the counter-clockwise ones.
  struct Case {
    CULL_MODE cull;
    BOOL frontCounterClockwise;
    const char* row;
  };
  const Case cases[] = {
      {CULL_NONE, FALSE, "RRRRGGGG"}, {CULL_BACK, FALSE, "RRRR...."}, {CULL_FRONT, FALSE, "....GGGG"},
      {CULL_NONE, TRUE, "RRRRGGGG"},  {CULL_BACK, TRUE, "....GGGG"},  {CULL_FRONT, TRUE, "RRRR...."},
  };
  std::vector<Vertex> vertices = Quad(0, 0, 4, 8, kRed, 8, 8, 0.5f, true);
  std::vector<Vertex> ccw = Quad(4, 0, 8, 8, kGreen, 8, 8, 0.5f, false);
  vertices.insert(vertices.end(), ccw.begin(), ccw.end());
  for (const Case& c : cases) {
    SCOPED_TRACE(testing::Message() << "CullMode " << c.cull << ", FrontCounterClockwise " << c.frontCounterClockwise);
    RASTERIZER_DESC desc;
    desc.CullMode = c.cull;
    desc.FrontCounterClockwise = c.frontCounterClockwise;
    auto state = Rasterizer(desc);
    context->RSSetState(state.Get());
    Clear(target_.rtv.Get(), kBlack);
    DrawVertices(vertices);
    EXPECT_EQ(Result(), Rows(8, c.row));
  }
}

TEST_F(StateTest, NullRasterizerStateIsDefaultCullBackClockwiseFront) {
  RASTERIZER_DESC none;
  none.CullMode = CULL_NONE;
  auto state = Rasterizer(none);
  context->RSSetState(state.Get());
  context->RSSetState(nullptr);
  std::vector<Vertex> vertices = Quad(0, 0, 4, 8, kRed, 8, 8, 0.5f, true);
  std::vector<Vertex> ccw = Quad(4, 0, 8, 8, kGreen, 8, 8, 0.5f, false);
  vertices.insert(vertices.end(), ccw.begin(), ccw.end());
  DrawVertices(vertices);
  EXPECT_EQ(Result(), Rows(8, "RRRR...."));
}

TEST_F(StateTest, WireframeDrawsTriangleOutlineSolidFillsIt) {
  // A clockwise triangle with vertices at pixel centres (0.5,0.5), (7.5,0.5),
  // (0.5,7.5). Solid: centres with x+y <= 6 (the hypotenuse x+y = 7 in pixel
  // indices is a right edge, excluded; top and left edges included): 28 pixels.
  // Wireframe: the three edges as lines, 6 interior pixels each (18), plus the
  // vertex pixels (0,0), (7,0), (0,7) ('*'). D3D11's diamond-exit rule lights
  // each line's start pixel and not its end pixel, so all three vertices
  // (21 pixels). The vertex pixels are not asserted: where two wireframe lines
  // meet, lavapipe leaves (7,0) unlit (20 pixels); that is the device's line
  // rasterization, not something the backend controls.
  const std::vector<Vertex> quad = Quad(0.5f, 0.5f, 7.5f, 7.5f, kWhite, 8, 8);
  const std::vector<Vertex> triangle = {quad[0], quad[1], quad[2]};
  DrawVertices(triangle);
  auto solid = Pixels();
  EXPECT_EQ(CountPixels(solid, kWhitePx), 28);
  EXPECT_EQ(CoverageMap(solid, 8, 8, kWhitePx, kBlackPx),
            (std::vector<std::string>{"XXXXXXX.", "XXXXXX..", "XXXXX...", "XXXX....", "XXX.....", "XX......",
                                      "X.......", "........"}));

  RASTERIZER_DESC desc;
  desc.FillMode = FILL_WIREFRAME;
  auto wireframe = Rasterizer(desc);
  context->RSSetState(wireframe.Get());
  Clear(target_.rtv.Get(), kBlack);
  DrawVertices(triangle);
  std::vector<std::string> outline = CoverageMap(Pixels(), 8, 8, kWhitePx, kBlackPx);
  for (auto [x, y] : {std::pair{0, 0}, std::pair{7, 0}, std::pair{0, 7}}) {
    EXPECT_NE(outline[y][x], '?');
    outline[y][x] = '*';
  }
  EXPECT_EQ(outline, (std::vector<std::string>{"*XXXXXX*", "X.....X.", "X....X..", "X...X...", "X..X....",
                                               "X.X.....", "XX......", "*......."}));
}

TEST_F(StateTest, ScissorEnableClipsToScissorRectAndDisabledIgnoresIt) {
  const RECT rect{2, 1, 6, 5};
  context->RSSetScissorRects(1, &rect);
  RASTERIZER_DESC desc;
  desc.ScissorEnable = TRUE;
  auto scissor = Rasterizer(desc);
  context->RSSetState(scissor.Get());
  DrawVertices(Quad(0, 0, 8, 8, kWhite, 8, 8));
  EXPECT_EQ(CoverageMap(Pixels(), 8, 8, kWhitePx, kBlackPx),
            (std::vector<std::string>{"........", "..XXXX..", "..XXXX..", "..XXXX..", "..XXXX..", "........",
                                      "........", "........"}));

  context->RSSetState(nullptr);  // ScissorEnable FALSE: the rect stays set but is ignored
  Clear(target_.rtv.Get(), kBlack);
  DrawVertices(Quad(0, 0, 8, 8, kWhite, 8, 8));
  EXPECT_EQ(CountPixels(Pixels(), kWhitePx), 64);
}

TEST_F(StateTest, ViewportOffsetMovesClipSpaceIntoTheViewportRectangle) {
  // Clip space [-1,1]^2 maps onto the viewport x in [4,8), y in [2,6).
  const VIEWPORT viewport{4, 2, 4, 4, 0, 1};
  context->RSSetViewports(1, &viewport);
  DrawVertices(Quad(0, 0, 8, 8, kWhite, 8, 8));  // the whole clip square
  EXPECT_EQ(CoverageMap(Pixels(), 8, 8, kWhitePx, kBlackPx),
            (std::vector<std::string>{"........", "........", "....XXXX", "....XXXX", "....XXXX", "....XXXX",
                                      "........", "........"}));
}

// ---------------------------------------------------------------------------
// Depth

class DepthTest : public StateTest {
 protected:
  // Depth after setup: columns 0-2 hold 0.25, columns 3-5 hold 0.75 (both drawn
  // red with ALWAYS), columns 6-7 keep the clear value 0.5 (black).
  void SetUp() override {
    StateTest::SetUp();
    if (HasFatalFailure()) return;
    UseDepth(DXGI_FORMAT_D32_FLOAT);
    context->ClearDepthStencilView(depth_.dsv.Get(), CLEAR_DEPTH, 0.5f, 0);
    DEPTH_STENCIL_DESC always;
    always.DepthFunc = COMPARISON_ALWAYS;
    auto state = DepthStencil(always);
    context->OMSetDepthStencilState(state.Get(), 0);
    std::vector<Vertex> v = Quad(0, 0, 3, 8, kRed, 8, 8, 0.25f);
    std::vector<Vertex> far = Quad(3, 0, 6, 8, kRed, 8, 8, 0.75f);
    v.insert(v.end(), far.begin(), far.end());
    DrawVertices(v);
  }
};

TEST_F(DepthTest, DepthFuncComparesIncomingDepthWithStoredDepth) {
  // A green full-target quad at z = 0.5 passes where 0.5 <func> stored holds:
  // stored 0.25 | 0.75 | 0.5 in columns 0-2 | 3-5 | 6-7.
  struct Case {
    COMPARISON_FUNC func;
    const char* row;
  };
  const Case cases[] = {
      {COMPARISON_NEVER, "RRRRRR.."},     {COMPARISON_LESS, "RRRGGG.."},     {COMPARISON_EQUAL, "RRRRRRGG"},
      {COMPARISON_LESS_EQUAL, "RRRGGGGG"}, {COMPARISON_GREATER, "GGGRRR.."},  {COMPARISON_NOT_EQUAL, "GGGGGG.."},
      {COMPARISON_GREATER_EQUAL, "GGGRRRGG"}, {COMPARISON_ALWAYS, "GGGGGGGG"},
  };
  auto before = Pixels();
  for (const Case& c : cases) {
    SCOPED_TRACE(testing::Message() << "DepthFunc " << c.func);
    DEPTH_STENCIL_DESC desc;
    desc.DepthFunc = c.func;
    desc.DepthWriteMask = DEPTH_WRITE_MASK_ZERO;  // keep the stored depths for the next case
    auto state = DepthStencil(desc);
    context->OMSetDepthStencilState(state.Get(), 0);
    context->UpdateSubresource(target_.texture.Get(), 0, nullptr, before.data(), 8 * 4, 8 * 8 * 4);
    DrawVertices(Quad(0, 0, 8, 8, kGreen, 8, 8, 0.5f));
    EXPECT_EQ(Result(), Rows(8, c.row));
  }
}

TEST_F(DepthTest, DepthWriteMaskZeroTestsButDoesNotWrite) {
  // Green at z = 0.5 with ALWAYS and no depth writes covers everything; a white
  // quad at z = 0.5 with EQUAL then passes only where the depth still is 0.5.
  DEPTH_STENCIL_DESC noWrite;
  noWrite.DepthFunc = COMPARISON_ALWAYS;
  noWrite.DepthWriteMask = DEPTH_WRITE_MASK_ZERO;
  auto noWriteState = DepthStencil(noWrite);
  context->OMSetDepthStencilState(noWriteState.Get(), 0);
  DrawVertices(Quad(0, 0, 8, 8, kGreen, 8, 8, 0.5f));
  DEPTH_STENCIL_DESC equal;
  equal.DepthFunc = COMPARISON_EQUAL;
  auto equalState = DepthStencil(equal);
  context->OMSetDepthStencilState(equalState.Get(), 0);
  DrawVertices(Quad(0, 0, 8, 8, kWhite, 8, 8, 0.5f));
  EXPECT_EQ(Result(), Rows(8, "GGGGGGWW"));
}

TEST_F(StateTest, NullDepthStencilStateIsDefaultLessWithWrites) {
  // Depth cleared to 0.5. Red at 0.25 over columns 0-5 passes (LESS) and writes
  // 0.25; green at 0.375 over everything then passes only in columns 6-7.
  // (ALWAYS would give all green; no writes would give all green too.)
  UseDepth(DXGI_FORMAT_D32_FLOAT);
  context->ClearDepthStencilView(depth_.dsv.Get(), CLEAR_DEPTH, 0.5f, 0);
  DEPTH_STENCIL_DESC other;
  other.DepthFunc = COMPARISON_ALWAYS;
  other.DepthWriteMask = DEPTH_WRITE_MASK_ZERO;
  auto state = DepthStencil(other);
  context->OMSetDepthStencilState(state.Get(), 0);
  context->OMSetDepthStencilState(nullptr, 0);
  DrawVertices(Quad(0, 0, 6, 8, kRed, 8, 8, 0.25f));
  DrawVertices(Quad(0, 0, 8, 8, kGreen, 8, 8, 0.375f));
  EXPECT_EQ(Result(), Rows(8, "RRRRRRGG"));
}

// ---------------------------------------------------------------------------
// Stencil (D24_UNORM_S8_UINT, depth test off)

DEPTH_STENCIL_DESC StencilOnly(COMPARISON_FUNC func, STENCIL_OP passOp) {
  DEPTH_STENCIL_DESC desc;
  desc.DepthEnable = FALSE;
  desc.StencilEnable = TRUE;
  desc.FrontFace = {STENCIL_OP_KEEP, STENCIL_OP_KEEP, passOp, func};
  desc.BackFace = desc.FrontFace;
  return desc;
}

class StencilTest : public StateTest {
 protected:
  void SetUp() override {
    StateTest::SetUp();
    if (HasFatalFailure()) return;
    UseDepth(DXGI_FORMAT_D24_UNORM_S8_UINT);
  }
  // Draws columns [x0,x1) with stencil `func`/`passOp` against `ref`.
  void StencilDraw(float x0, float x1, COMPARISON_FUNC func, STENCIL_OP passOp, UINT ref, Color color) {
    auto state = DepthStencil(StencilOnly(func, passOp));
    context->OMSetDepthStencilState(state.Get(), ref);
    DrawVertices(Quad(x0, 0, x1, 8, color, 8, 8));
  }
};

TEST_F(StencilTest, ReplaceWritesReferenceAndEqualTestsAgainstIt) {
  context->ClearDepthStencilView(depth_.dsv.Get(), CLEAR_STENCIL, 1.0f, 0);
  StencilDraw(0, 4, COMPARISON_ALWAYS, STENCIL_OP_REPLACE, 5, kBlack);  // stencil 5 | 0
  StencilDraw(0, 8, COMPARISON_EQUAL, STENCIL_OP_KEEP, 5, kGreen);
  StencilDraw(0, 8, COMPARISON_EQUAL, STENCIL_OP_KEEP, 0, kBlue);
  EXPECT_EQ(Result(), Rows(8, "GGGGBBBB"));
}

TEST_F(StencilTest, IncrSatSaturatesAndDecrDecrements) {
  // Clear 254; INCR_SAT twice over columns 0-3: 255 (saturated, not 0);
  // DECR over columns 2-7: 255 -> 254 in 2-3, 254 -> 253 in 4-7.
  context->ClearDepthStencilView(depth_.dsv.Get(), CLEAR_STENCIL, 1.0f, 254);
  StencilDraw(0, 4, COMPARISON_ALWAYS, STENCIL_OP_INCR_SAT, 0, kBlack);
  StencilDraw(0, 4, COMPARISON_ALWAYS, STENCIL_OP_INCR_SAT, 0, kBlack);
  StencilDraw(2, 8, COMPARISON_ALWAYS, STENCIL_OP_DECR, 0, kBlack);
  StencilDraw(0, 8, COMPARISON_EQUAL, STENCIL_OP_KEEP, 255, kRed);
  StencilDraw(0, 8, COMPARISON_EQUAL, STENCIL_OP_KEEP, 254, kGreen);
  StencilDraw(0, 8, COMPARISON_EQUAL, STENCIL_OP_KEEP, 253, kBlue);
  EXPECT_EQ(Result(), Rows(8, "RRGGBBBB"));
}

TEST_F(StencilTest, DecrWrapsAndDecrSatClampsAtZero) {
  context->ClearDepthStencilView(depth_.dsv.Get(), CLEAR_STENCIL, 1.0f, 0);
  StencilDraw(0, 4, COMPARISON_ALWAYS, STENCIL_OP_DECR, 0, kBlack);      // 0 -> 255
  StencilDraw(4, 8, COMPARISON_ALWAYS, STENCIL_OP_DECR_SAT, 0, kBlack);  // 0 -> 0
  StencilDraw(0, 8, COMPARISON_EQUAL, STENCIL_OP_KEEP, 255, kRed);
  StencilDraw(0, 8, COMPARISON_EQUAL, STENCIL_OP_KEEP, 0, kGreen);
  EXPECT_EQ(Result(), Rows(8, "RRRRGGGG"));
}

TEST_F(StencilTest, TwoSidedStencilAppliesFrontOpsToFrontFacesAndBackOpsToBackFaces) {
  // Stencil 10; front faces INCR (-> 11), back faces DECR (-> 9). Columns 0-3
  // are clockwise (front), 4-7 counter-clockwise (back); culling off.
  context->ClearDepthStencilView(depth_.dsv.Get(), CLEAR_STENCIL, 1.0f, 10);
  RASTERIZER_DESC rs;
  rs.CullMode = CULL_NONE;
  auto noCull = Rasterizer(rs);
  context->RSSetState(noCull.Get());
  DEPTH_STENCIL_DESC twoSided = StencilOnly(COMPARISON_ALWAYS, STENCIL_OP_INCR);
  twoSided.BackFace.StencilPassOp = STENCIL_OP_DECR;
  auto state = DepthStencil(twoSided);
  context->OMSetDepthStencilState(state.Get(), 0);
  std::vector<Vertex> v = Quad(0, 0, 4, 8, kBlack, 8, 8, 0.5f, true);
  std::vector<Vertex> back = Quad(4, 0, 8, 8, kBlack, 8, 8, 0.5f, false);
  v.insert(v.end(), back.begin(), back.end());
  DrawVertices(v);
  StencilDraw(0, 8, COMPARISON_EQUAL, STENCIL_OP_KEEP, 11, kRed);
  StencilDraw(0, 8, COMPARISON_EQUAL, STENCIL_OP_KEEP, 9, kGreen);
  EXPECT_EQ(Result(), Rows(8, "RRRRGGGG"));
}

// ---------------------------------------------------------------------------
// Blend

TEST_F(StateTest, RenderTargetWriteMaskRedOnlyKeepsOtherChannels) {
  Clear(target_.rtv.Get(), {0, 0, 1, 1});
  BLEND_DESC desc;
  desc.RenderTarget[0].RenderTargetWriteMask = COLOR_WRITE_ENABLE_RED;
  auto state = Blend(desc);
  context->OMSetBlendState(state.Get(), nullptr, DEFAULT_SAMPLE_MASK);
  DrawVertices(Quad(0, 0, 8, 8, {1, 1, 0, 0}, 8, 8));
  // R from the draw (255); G, B, A kept from the clear (0, 255, 255).
  EXPECT_EQ(CountPixels(Pixels(), RGBA(255, 0, 255, 255)), 64);
}

TEST_F(StateTest, BlendSrcAlphaInvSrcAlphaGivesExactUnormResult) {
  // dst = (0,0,1,1); src = (1, 0.5, 0, 0.25); colour = src*0.25 + dst*0.75:
  // R 0.25 -> 64, G 0.125 -> 31.875 -> 32, B 0.75 -> 191.25 -> 191;
  // alpha ONE/ZERO: 0.25 -> 64.
  Clear(target_.rtv.Get(), {0, 0, 1, 1});
  BLEND_DESC desc;
  desc.RenderTarget[0].BlendEnable = TRUE;
  desc.RenderTarget[0].SrcBlend = BLEND_SRC_ALPHA;
  desc.RenderTarget[0].DestBlend = BLEND_INV_SRC_ALPHA;
  auto state = Blend(desc);
  context->OMSetBlendState(state.Get(), nullptr, DEFAULT_SAMPLE_MASK);
  DrawVertices(Quad(0, 0, 8, 8, {1, 0.5f, 0, 0.25f}, 8, 8));
  EXPECT_EQ(CountPixels(Pixels(), RGBA(64, 32, 191, 64)), 64);
}

TEST_F(StateTest, BlendFactorFromOMSetBlendStateIsUsedAndUpdatedPerDraw) {
  // src red (1,0,0,1), dst blue (0,0,1,1), result = src*F + dst*(1-F) per channel.
  // F = (0.25, 0.5, 0.125, 0.5): R 0.25 -> 64, G 0, B 0.875 -> 223, A 1 -> 255.
  // F = (0.75, 0, 0.625, 0.5):   R 0.75 -> 191, G 0, B 0.375 -> 95.625 -> 96, A 255.
  Clear(target_.rtv.Get(), {0, 0, 1, 1});
  BLEND_DESC desc;
  auto& rt = desc.RenderTarget[0];
  rt.BlendEnable = TRUE;
  rt.SrcBlend = rt.SrcBlendAlpha = BLEND_BLEND_FACTOR;
  rt.DestBlend = rt.DestBlendAlpha = BLEND_INV_BLEND_FACTOR;
  auto state = Blend(desc);
  const FLOAT first[4] = {0.25f, 0.5f, 0.125f, 0.5f}, second[4] = {0.75f, 0, 0.625f, 0.5f};
  context->OMSetBlendState(state.Get(), first, DEFAULT_SAMPLE_MASK);
  DrawVertices(Quad(0, 0, 4, 8, kRed, 8, 8));
  context->OMSetBlendState(state.Get(), second, DEFAULT_SAMPLE_MASK);
  DrawVertices(Quad(4, 0, 8, 8, kRed, 8, 8));
  auto pixels = Pixels();
  EXPECT_EQ(Picture(pixels, 8, 8, {{RGBA(64, 0, 223, 255), '1'}, {RGBA(191, 0, 96, 255), '2'}}),
            Rows(8, "11112222"));
}

TEST_F(StateTest, EachDrawUsesThePipelineOfItsStateAcrossRebindsAndTargetChanges) {
  // The backend keeps the pipeline key up to date in the setters and looks
  // pipelines up through a table of recent keys: a state bound again (the
  // third draw), a target of another format in between, and a target bound
  // back must each draw with their own pipeline (a pipeline built for another
  // colour format would also be a validation error).
  // Factor blending of red over blue, F = (0.25, 0.5, 0.125, 0.5): (64, 0, 223, 255) '1'; opaque red '2'.
  Clear(target_.rtv.Get(), {0, 0, 1, 1});
  BLEND_DESC desc;
  auto& rt = desc.RenderTarget[0];
  rt.BlendEnable = TRUE;
  rt.SrcBlend = rt.SrcBlendAlpha = BLEND_BLEND_FACTOR;
  rt.DestBlend = rt.DestBlendAlpha = BLEND_INV_BLEND_FACTOR;
  auto byFactor = Blend(desc);
  const FLOAT factor[4] = {0.25f, 0.5f, 0.125f, 0.5f};
  context->OMSetBlendState(byFactor.Get(), factor, DEFAULT_SAMPLE_MASK);
  DrawVertices(Quad(0, 0, 2, 8, kRed, 8, 8));
  context->OMSetBlendState(nullptr, nullptr, DEFAULT_SAMPLE_MASK);
  DrawVertices(Quad(2, 0, 4, 8, kRed, 8, 8));
  context->OMSetBlendState(byFactor.Get(), factor, DEFAULT_SAMPLE_MASK);
  DrawVertices(Quad(4, 0, 6, 8, kRed, 8, 8));
  Target half = MakeRenderTarget(8, 8, DXGI_FORMAT_R16G16B16A16_FLOAT);
  BindTarget(half.rtv.Get(), 8, 8);
  DrawVertices(Quad(0, 0, 8, 8, kRed, 8, 8));
  BindTarget(target_.rtv.Get(), 8, 8);
  context->OMSetBlendState(nullptr, nullptr, DEFAULT_SAMPLE_MASK);
  DrawVertices(Quad(6, 0, 8, 8, kRed, 8, 8));
  EXPECT_EQ(Picture(Pixels(), 8, 8, {{RGBA(64, 0, 223, 255), '1'}, {RGBA(255, 0, 0, 255), '2'}}),
            Rows(8, "11221122"));
}

TEST_F(StateTest, NullBlendStateIsDefaultNoBlending) {
  Clear(target_.rtv.Get(), {0, 0, 1, 1});
  BLEND_DESC desc;
  desc.RenderTarget[0].BlendEnable = TRUE;
  desc.RenderTarget[0].SrcBlend = BLEND_SRC_ALPHA;
  desc.RenderTarget[0].DestBlend = BLEND_INV_SRC_ALPHA;
  auto state = Blend(desc);
  context->OMSetBlendState(state.Get(), nullptr, DEFAULT_SAMPLE_MASK);
  context->OMSetBlendState(nullptr, nullptr, DEFAULT_SAMPLE_MASK);
  // The source replaces the destination: (1, 0.25, 0, 0.25) -> (255, 64, 0, 64).
  DrawVertices(Quad(0, 0, 8, 8, {1, 0.25f, 0, 0.25f}, 8, 8));
  EXPECT_EQ(CountPixels(Pixels(), RGBA(255, 64, 0, 64)), 64);
}

TEST_F(StateTest, SampleMaskSelectsWrittenSamplesOf4xMsaaTargetAndResolveAverages) {
  // White over black (0,0,0,0) in a 4x target, full pixel coverage. Sample mask
  // 0x1 writes 1 of 4 samples: resolve 255/4 = 63.75 -> 64; mask 0x7 writes 3:
  // 191.25 -> 191 (every channel, alpha included).
  Target msaa = MakeRenderTarget(8, 8, DXGI_FORMAT_R8G8B8A8_UNORM, 4);
  BindTarget(msaa.rtv.Get(), 8, 8);
  Clear(msaa.rtv.Get(), {0, 0, 0, 0});
  context->OMSetBlendState(nullptr, nullptr, 0x1);
  DrawVertices(Quad(0, 0, 4, 8, kWhite, 8, 8));
  context->OMSetBlendState(nullptr, nullptr, 0x7);
  DrawVertices(Quad(4, 0, 8, 8, kWhite, 8, 8));
  context->ResolveSubresource(target_.texture.Get(), 0, msaa.texture.Get(), 0, DXGI_FORMAT_R8G8B8A8_UNORM);
  EXPECT_EQ(Picture(Pixels(), 8, 8, {{RGBA(64, 64, 64, 64), '1'}, {RGBA(191, 191, 191, 191), '3'}}),
            Rows(8, "11113333"));
}

// ---------------------------------------------------------------------------
// Creation: refusals and deduplication

TEST_F(StateTest, InvalidDescriptionsAreRefusedWithMessageNamingTheField) {
  BLEND_DESC blend;
  blend.RenderTarget[0].BlendEnable = TRUE;
  blend.RenderTarget[0].SrcBlendAlpha = BLEND_SRC_COLOR;  // colour factors are invalid for alpha
  ComPtr<BlendState> blendState;
  EXPECT_EQ(device->CreateBlendState(&blend, blendState.GetAddressOf()), E_INVALIDARG);
  EXPECT_FALSE(blendState);
  EXPECT_TRUE(RefusedWith("SrcBlendAlpha"));

  DEPTH_STENCIL_DESC depth;
  depth.DepthFunc = static_cast<COMPARISON_FUNC>(0);
  ComPtr<DepthStencilState> depthState;
  EXPECT_EQ(device->CreateDepthStencilState(&depth, depthState.GetAddressOf()), E_INVALIDARG);
  EXPECT_FALSE(depthState);
  EXPECT_TRUE(RefusedWith("DepthFunc"));

  RASTERIZER_DESC raster;
  raster.CullMode = static_cast<CULL_MODE>(0);
  ComPtr<RasterizerState> rasterState;
  EXPECT_EQ(device->CreateRasterizerState(&raster, rasterState.GetAddressOf()), E_INVALIDARG);
  EXPECT_FALSE(rasterState);
  EXPECT_TRUE(RefusedWith("CullMode"));

  SAMPLER_DESC sampler;
  sampler.Filter = FILTER_ANISOTROPIC;
  sampler.MaxAnisotropy = 17;
  ComPtr<SamplerState> samplerState;
  EXPECT_EQ(device->CreateSamplerState(&sampler, samplerState.GetAddressOf()), E_INVALIDARG);
  EXPECT_FALSE(samplerState);
  EXPECT_TRUE(RefusedWith("MaxAnisotropy"));

  for (const std::string& text : Refusals()) std::printf("refusal: %s\n", text.c_str());
}

TEST_F(StateTest, IdenticalDescriptionsReturnTheSameObjectDifferentOnesDoNot) {
  BLEND_DESC blendA, blendB;
  blendB.RenderTarget[0].RenderTargetWriteMask = COLOR_WRITE_ENABLE_RED;
  EXPECT_EQ(Blend(blendA).Get(), Blend(blendA).Get());
  EXPECT_NE(Blend(blendA).Get(), Blend(blendB).Get());

  DEPTH_STENCIL_DESC depthA, depthB;
  depthB.DepthFunc = COMPARISON_GREATER;
  EXPECT_EQ(DepthStencil(depthA).Get(), DepthStencil(depthA).Get());
  EXPECT_NE(DepthStencil(depthA).Get(), DepthStencil(depthB).Get());

  RASTERIZER_DESC rasterA, rasterB;
  rasterB.CullMode = CULL_NONE;
  EXPECT_EQ(Rasterizer(rasterA).Get(), Rasterizer(rasterA).Get());
  EXPECT_NE(Rasterizer(rasterA).Get(), Rasterizer(rasterB).Get());

  SAMPLER_DESC samplerA, samplerB;
  samplerB.AddressU = TEXTURE_ADDRESS_WRAP;
  ComPtr<SamplerState> a1, a2, b;
  ASSERT_EQ(device->CreateSamplerState(&samplerA, a1.GetAddressOf()), S_OK);
  ASSERT_EQ(device->CreateSamplerState(&samplerA, a2.GetAddressOf()), S_OK);
  ASSERT_EQ(device->CreateSamplerState(&samplerB, b.GetAddressOf()), S_OK);
  EXPECT_EQ(a1.Get(), a2.Get());
  EXPECT_NE(a1.Get(), b.Get());
}

}  // namespace
}  // namespace rhi_test
