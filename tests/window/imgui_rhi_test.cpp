// imgui_rhi (app/imgui_rhi.h) without a window: Dear ImGui draw data rendered into an
// offscreen R8G8B8A8_UNORM target through the RHI, validation layer on (GpuTest), exact pixels.
#include <imgui.h>

#include <cmath>
#include <string>

#include "gpu_test.h"
#include "imgui_rhi.h"

namespace {

using rhi::ComPtr;
using rhi::UINT;
using rhi_test::GpuTest;

constexpr UINT kWidth = 256, kHeight = 128;

class ImGuiRhiTest : public GpuTest {
 protected:
  void SetUp() override {
    GpuTest::SetUp();
    ImGui::CreateContext();
    ImGuiIO& io = ImGui::GetIO();
    io.IniFilename = nullptr;
    io.DisplaySize = ImVec2(float(kWidth), float(kHeight));
    io.DeltaTime = 1.0f / 60.0f;
    std::string error;
    ASSERT_TRUE(ImGui_ImplRhi_Init(device.Get(), context.Get(), &error)) << error;
    target_ = MakeRenderTarget(kWidth, kHeight);
  }
  void TearDown() override {
    ImGui_ImplRhi_Shutdown();
    ImGui::DestroyContext();
  }

  // Clears the target, renders the current ImGui frame into it and reads it back.
  std::vector<uint8_t> Render(const float clear[4]) {
    ImGui::Render();
    context->ClearRenderTargetView(target_.rtv.Get(), clear);
    rhi::RenderTargetView* rtv = target_.rtv.Get();
    context->OMSetRenderTargets(1, &rtv, nullptr);
    ImGui_ImplRhi_RenderDrawData(ImGui::GetDrawData());
    context->ClearState();
    return ReadTexture(target_.texture.Get());
  }
  static uint32_t Rgba(int r, int g, int b, int a) { return uint32_t(r) | uint32_t(g) << 8 | uint32_t(b) << 16 | uint32_t(a) << 24; }

  Target target_;
};

const float kBlack[4] = {0, 0, 0, 1};

// One scissor rect per draw command: a rect clipped by PushClipRect only fills the clip rect;
// the next command (no clip) is not clipped by the previous one's scissor.
TEST_F(ImGuiRhiTest, ScissorPerDrawCommand) {
  ImGui_ImplRhi_NewFrame();
  ImGui::NewFrame();
  ImDrawList* list = ImGui::GetForegroundDrawList();
  list->PushClipRect(ImVec2(10, 10), ImVec2(30, 20));
  list->AddRectFilled(ImVec2(0, 0), ImVec2(64, 64), IM_COL32(255, 0, 0, 255));
  list->PopClipRect();
  list->AddRectFilled(ImVec2(100, 40), ImVec2(120, 60), IM_COL32(0, 255, 0, 255));
  const std::vector<uint8_t> pixels = Render(kBlack);
  const uint32_t red = Rgba(255, 0, 0, 255), green = Rgba(0, 255, 0, 255), black = Rgba(0, 0, 0, 255);
  for (UINT y = 0; y < 70; ++y)
    for (UINT x = 0; x < 70; ++x) {
      const bool inside = x >= 10 && x < 30 && y >= 10 && y < 20;
      ASSERT_EQ(Pixel(pixels, kWidth, x, y), inside ? red : black) << x << "," << y;
    }
  EXPECT_EQ(Pixel(pixels, kWidth, 100, 40), green);
  EXPECT_EQ(Pixel(pixels, kWidth, 119, 59), green);
  EXPECT_EQ(Pixel(pixels, kWidth, 120, 60), black);
  EXPECT_EQ(Pixel(pixels, kWidth, 99, 39), black);
}

// SRC_ALPHA / INV_SRC_ALPHA colour, ONE / INV_SRC_ALPHA alpha, as imgui_impl_dx11.
TEST_F(ImGuiRhiTest, BlendsSrcAlphaOver) {
  ImGui_ImplRhi_NewFrame();
  ImGui::NewFrame();
  ImGui::GetForegroundDrawList()->AddRectFilled(ImVec2(0, 0), ImVec2(8, 8), IM_COL32(255, 0, 0, 51));
  const float blue[4] = {0, 0, 1, 1};
  const std::vector<uint8_t> pixels = Render(blue);
  const uint32_t p = Pixel(pixels, kWidth, 4, 4);
  // r = 1 * 0.2 = 51; b = 1 * (1 - 0.2) = 204; a = 0.2 + 1 * 0.8 = 1.
  EXPECT_NEAR(int(p & 0xff), 51, 1);
  EXPECT_EQ(int(p >> 8 & 0xff), 0);
  EXPECT_NEAR(int(p >> 16 & 0xff), 204, 1);
  EXPECT_EQ(int(p >> 24), 255);
}

// 128 x 128 one-pixel rects and 4,000 more in one draw list: 81,536 vertices, far past the first
// vertex buffer (5000) and past the 65,536 vertices one 16-bit-indexed command can address, so
// ImGui starts new commands with a VtxOffset that the backend passes as BaseVertexLocation.
// Every rect must land on its pixel, in its colour.
TEST_F(ImGuiRhiTest, GrowsBuffersAndUsesVertexOffsets) {
  const int columns = 128, rows = 128;
  auto colour = [](int x, int y) { return IM_COL32((x * 2) & 255, (y * 2) & 255, (x + y) & 255, 255); };
  for (int pass = 0; pass < 2; ++pass) {  // two frames: the second reuses the grown buffers
    ImGui_ImplRhi_NewFrame();
    ImGui::NewFrame();
    ImDrawList* list = ImGui::GetForegroundDrawList();
    for (int y = 0; y < rows; ++y)
      for (int x = 0; x < columns; ++x)
        list->AddRectFilled(ImVec2(float(x), float(y)), ImVec2(float(x + 1), float(y + 1)), colour(x, y));
    for (int i = 0; i < 4000; ++i)
      list->AddRectFilled(ImVec2(200, 120), ImVec2(201, 121), IM_COL32(255, 255, 255, 255));
    const std::vector<uint8_t> pixels = Render(kBlack);
    const ImDrawData* data = ImGui::GetDrawData();
    EXPECT_GT(data->TotalVtxCount, 65536) << "pass " << pass;
    bool offsetUsed = false;
    for (int n = 0; n < data->CmdListsCount; ++n)
      for (const ImDrawCmd& cmd : data->CmdLists[n]->CmdBuffer) offsetUsed |= cmd.VtxOffset != 0;
    EXPECT_TRUE(offsetUsed) << "pass " << pass;
    int wrong = 0;
    for (int y = 0; y < rows; ++y)
      for (int x = 0; x < columns; ++x) wrong += Pixel(pixels, kWidth, UINT(x), UINT(y)) != colour(x, y);
    EXPECT_EQ(wrong, 0) << "pass " << pass;
    EXPECT_EQ(Pixel(pixels, kWidth, 200, 120), Rgba(255, 255, 255, 255));
    EXPECT_EQ(Pixel(pixels, kWidth, 150, 50), Rgba(0, 0, 0, 255));
  }
}

// ImTextureID is an rhi::ShaderResourceView*: the font atlas for text, any SRV for ImGui::Image.
TEST_F(ImGuiRhiTest, DrawsTextAndUserTextures) {
  const uint32_t texels[4] = {Rgba(255, 0, 0, 255), Rgba(0, 255, 0, 255), Rgba(0, 0, 255, 255),
                              Rgba(255, 255, 0, 255)};
  rhi::TEXTURE2D_DESC desc{2, 2, 1, 1, rhi::DXGI_FORMAT_R8G8B8A8_UNORM, {1, 0}, rhi::USAGE_IMMUTABLE,
                           rhi::BIND_SHADER_RESOURCE, 0, 0};
  rhi::SUBRESOURCE_DATA init{texels, 8, 0};
  ComPtr<rhi::Texture2D> texture;
  ComPtr<rhi::ShaderResourceView> view;
  ASSERT_EQ(device->CreateTexture2D(&desc, &init, texture.GetAddressOf()), rhi::S_OK);
  ASSERT_EQ(device->CreateShaderResourceView(texture.Get(), nullptr, view.GetAddressOf()), rhi::S_OK);

  ImGui_ImplRhi_NewFrame();
  ImGui::NewFrame();
  ImDrawList* list = ImGui::GetForegroundDrawList();
  // 2x2 texels on 2x2 pixels: every pixel centre is a texel centre, so linear sampling returns
  // the texels exactly.
  list->AddImage(static_cast<ImTextureID>(view.Get()), ImVec2(128, 0), ImVec2(130, 2));
  list->AddText(ImVec2(4, 100), IM_COL32(255, 255, 255, 255), "ImGui");
  const std::vector<uint8_t> pixels = Render(kBlack);
  EXPECT_EQ(Pixel(pixels, kWidth, 128, 0), texels[0]);
  EXPECT_EQ(Pixel(pixels, kWidth, 129, 0), texels[1]);
  EXPECT_EQ(Pixel(pixels, kWidth, 128, 1), texels[2]);
  EXPECT_EQ(Pixel(pixels, kWidth, 129, 1), texels[3]);
  EXPECT_EQ(Pixel(pixels, kWidth, 130, 0), Rgba(0, 0, 0, 255));
  // Text: some glyph pixels lit (white, font atlas alpha), the area right of it untouched.
  int lit = 0;
  for (UINT y = 100; y < 116; ++y)
    for (UINT x = 4; x < 44; ++x) lit += (Pixel(pixels, kWidth, x, y) & 0xff) > 128;
  EXPECT_GT(lit, 20);
  for (UINT y = 100; y < 116; ++y) EXPECT_EQ(Pixel(pixels, kWidth, 100, y), Rgba(0, 0, 0, 255));
}

}  // namespace
