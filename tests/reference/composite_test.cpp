// Back-to-front OVER compositing through the reference blender.
#include <gtest/gtest.h>

#include <vector>

#include "rhi_reference/composite.h"

namespace rhi::reference {
namespace {

TEST(Composite, OverDescIsStraightAlphaOver) {
  const RENDER_TARGET_BLEND_DESC over = OverBlendDesc();
  EXPECT_EQ(over.BlendEnable, TRUE);
  EXPECT_EQ(over.SrcBlend, BLEND_SRC_ALPHA);
  EXPECT_EQ(over.DestBlend, BLEND_INV_SRC_ALPHA);
  EXPECT_EQ(over.SrcBlendAlpha, BLEND_ONE);
  EXPECT_EQ(over.DestBlendAlpha, BLEND_INV_SRC_ALPHA);
  EXPECT_EQ(over.RenderTargetWriteMask, COLOR_WRITE_ENABLE_ALL);
}

TEST(Composite, TwoLayersOnFloat) {
  // Background (0, 0, 1, 1). Red (1, 0, 0, 0.5) first:
  //   rgb (1,0,0)*0.5 + (0,0,1)*0.5 = (0.5, 0, 0.5); alpha 0.5 + 1*0.5 = 1.
  // Then green (0, 1, 0, 0.5) nearer:
  //   rgb (0,1,0)*0.5 + (0.5,0,0.5)*0.5 = (0.25, 0.5, 0.25); alpha 1.
  constexpr DXGI_FORMAT kFormat = DXGI_FORMAT_R32G32B32A32_FLOAT;
  const std::vector<Float4> layers{{1, 0, 0, 0.5f}, {0, 1, 0, 0.5f}};
  const StoredColor result = CompositeBackToFront(kFormat, layers, Encode(kFormat, {0, 0, 1, 1}));
  EXPECT_EQ(Decode(kFormat, result), (Float4{0.25f, 0.5f, 0.25f, 1.0f}));
}

TEST(Composite, OrderMatters) {
  // Green first, then red: (0, 0.5, 0.5) then (0.5, 0.25, 0.25).
  constexpr DXGI_FORMAT kFormat = DXGI_FORMAT_R32G32B32A32_FLOAT;
  const std::vector<Float4> layers{{0, 1, 0, 0.5f}, {1, 0, 0, 0.5f}};
  const StoredColor result = CompositeBackToFront(kFormat, layers, Encode(kFormat, {0, 0, 1, 1}));
  EXPECT_EQ(Decode(kFormat, result), (Float4{0.5f, 0.25f, 0.25f, 1.0f}));
}

TEST(Composite, QuantisesAfterEveryLayerOnUnorm) {
  // R8G8B8A8_UNORM, background black opaque (0, 0, 0, 255).
  // Red (1, 0, 0, 0.5): r 0.5 -> 128, alpha 0.5 + 0.5 = 1 -> 255.
  // Green (0, 1, 0, 0.5): r 0.5 * 128/255 = 0.25098 -> 64.0 + 0.5 -> 64; g 0.5 -> 128.
  constexpr DXGI_FORMAT kFormat = DXGI_FORMAT_R8G8B8A8_UNORM;
  const std::vector<Float4> layers{{1, 0, 0, 0.5f}, {0, 1, 0, 0.5f}};
  EXPECT_EQ(CompositeBackToFront(kFormat, layers, StoredColor{{0, 0, 0, 255}}), (StoredColor{{64, 128, 0, 255}}));
}

TEST(Composite, NoLayersLeavesTheBackground) {
  const StoredColor background{{1, 2, 3, 4}};
  EXPECT_EQ(CompositeBackToFront(DXGI_FORMAT_R8G8B8A8_UNORM, {}, background), background);
}

}  // namespace
}  // namespace rhi::reference
