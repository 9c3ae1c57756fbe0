// rhi/format_info.h: format sizes read from the backend's one format table.
#include <gtest/gtest.h>

#include "rhi/format_info.h"

namespace {

struct FormatBits {
  rhi::DXGI_FORMAT format;
  rhi::UINT bits;
};

class BitsPerPixelTest : public ::testing::TestWithParam<FormatBits> {};

TEST_P(BitsPerPixelTest, IsTheFormatsTexelSize) {
  EXPECT_EQ(rhi::BitsPerPixel(GetParam().format), GetParam().bits);
}

INSTANTIATE_TEST_SUITE_P(Formats, BitsPerPixelTest,
                         ::testing::Values(FormatBits{rhi::DXGI_FORMAT_UNKNOWN, 0},
                                           FormatBits{rhi::DXGI_FORMAT_R8_UNORM, 8},
                                           FormatBits{rhi::DXGI_FORMAT_R8G8B8A8_UNORM, 32},
                                           FormatBits{rhi::DXGI_FORMAT_R16_FLOAT, 16},
                                           FormatBits{rhi::DXGI_FORMAT_R16G16B16A16_FLOAT, 64},
                                           FormatBits{rhi::DXGI_FORMAT_R32G32_FLOAT, 64},
                                           FormatBits{rhi::DXGI_FORMAT_R32G32B32A32_FLOAT, 128},
                                           FormatBits{rhi::DXGI_FORMAT_D32_FLOAT, 32}));

rhi::TEXTURE2D_DESC Desc(rhi::UINT w, rhi::UINT h, rhi::UINT mips, rhi::UINT array, rhi::DXGI_FORMAT f,
                         rhi::UINT samples) {
  return {w, h, mips, array, f, {samples, 0}, rhi::USAGE_DEFAULT, rhi::BIND_SHADER_RESOURCE, 0, 0};
}

TEST(TextureBytes, CountsEveryMipArraySliceAndSample) {
  EXPECT_EQ(rhi::TextureBytes(Desc(40, 24, 1, 1, rhi::DXGI_FORMAT_R16G16B16A16_FLOAT, 1)), 40u * 24 * 8);
  // 8x4 with its full chain (MipLevels 0): 8x4 + 4x2 + 2x1 + 1x1 texels.
  EXPECT_EQ(rhi::TextureBytes(Desc(8, 4, 0, 1, rhi::DXGI_FORMAT_R8_UNORM, 1)), 32u + 8 + 2 + 1);
  // Two levels of a 3-slice array: (5x3 + 2x1) texels x 3 slices x 4 bytes.
  EXPECT_EQ(rhi::TextureBytes(Desc(5, 3, 2, 3, rhi::DXGI_FORMAT_R32_FLOAT, 1)), (15u + 2) * 3 * 4);
  EXPECT_EQ(rhi::TextureBytes(Desc(16, 16, 1, 1, rhi::DXGI_FORMAT_R8G8B8A8_UNORM, 4)), 16u * 16 * 4 * 4);
}

}  // namespace
