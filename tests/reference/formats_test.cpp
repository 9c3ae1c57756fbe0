// Per-format conversion: float -> stored codes -> float, and memory layout.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <stdexcept>

#include "rhi_reference/formats.h"

namespace rhi::reference {
namespace {

TEST(Formats, UnormRoundsToNearest) {
  // FS 3.2.3.6: c*255 + 0.5, truncated. 0.5 -> 127.5 + 0.5 = 128; 0.2 -> 51.5 -> 51;
  // 0.999 -> 254.745 + 0.5 -> 255; 1.5 clamps to 1 -> 255; -0.5 clamps to 0; NaN -> 0.
  EXPECT_EQ(FloatToUnorm(0.5f, 8), 128u);
  EXPECT_EQ(FloatToUnorm(0.2f, 8), 51u);
  EXPECT_EQ(FloatToUnorm(0.999f, 8), 255u);
  EXPECT_EQ(FloatToUnorm(1.5f, 8), 255u);
  EXPECT_EQ(FloatToUnorm(-0.5f, 8), 0u);
  EXPECT_EQ(FloatToUnorm(NAN, 8), 0u);
  // 10 bits: 0.25 * 1023 = 255.75 + 0.5 -> 256.
  EXPECT_EQ(FloatToUnorm(0.25f, 10), 256u);
  EXPECT_FLOAT_EQ(UnormToFloat(51, 8), 0.2f);  // 51/255
}

TEST(Formats, R10G10B10A2QuantisesAlphaToTwoBits) {
  // Alpha has 4 levels 0, 1/3, 2/3, 1: 0.5*3 + 0.5 = 2.0 -> 2; 0.4 -> 1.7 -> 1;
  // 0.16 -> 0.98 -> 0; 0.17 -> 1.01 -> 1.
  EXPECT_EQ(Encode(DXGI_FORMAT_R10G10B10A2_UNORM, {0, 0, 0, 0.5f}).bits[3], 2u);
  EXPECT_EQ(Encode(DXGI_FORMAT_R10G10B10A2_UNORM, {0, 0, 0, 0.4f}).bits[3], 1u);
  EXPECT_EQ(Encode(DXGI_FORMAT_R10G10B10A2_UNORM, {0, 0, 0, 0.16f}).bits[3], 0u);
  EXPECT_EQ(Encode(DXGI_FORMAT_R10G10B10A2_UNORM, {0, 0, 0, 0.17f}).bits[3], 1u);
  // Decoded: 2/3.
  EXPECT_FLOAT_EQ(Decode(DXGI_FORMAT_R10G10B10A2_UNORM, StoredColor{{0, 0, 0, 2}})[3], 2.0f / 3.0f);
}

TEST(Formats, R10G10B10A2MemoryLayout) {
  // (0.5, 0.25, 1.0, 0.5) -> R 511.5+0.5 = 512, G 255.75+0.5 = 256, B 1023, A 2.
  // Word = 512 | 256<<10 | 1023<<20 | 2<<30 = 0x200 + 0x40000 + 0x3FF00000 + 0x80000000
  //      = 0xBFF40200, little-endian bytes 00 02 F4 BF.
  const StoredColor stored = Encode(DXGI_FORMAT_R10G10B10A2_UNORM, {0.5f, 0.25f, 1.0f, 0.5f});
  EXPECT_EQ(stored, (StoredColor{{512, 256, 1023, 2}}));
  const std::vector<uint8_t> bytes = PackPixel(DXGI_FORMAT_R10G10B10A2_UNORM, stored);
  EXPECT_EQ(bytes, (std::vector<uint8_t>{0x00, 0x02, 0xF4, 0xBF}));
  EXPECT_EQ(UnpackPixel(DXGI_FORMAT_R10G10B10A2_UNORM, bytes), stored);
}

TEST(Formats, SrgbMidGreyRoundTrips) {
  // Code 128: c = 128/255 = 0.50196; ((c + 0.055) / 1.055)^2.4 = 0.2158605 linear.
  // Back: 1.055 * 0.2158605^(1/2.4) - 0.055 = 0.5019608; *255 + 0.5 = 128.50001 -> 128.
  const StoredColor grey{{128, 128, 128, 128}};
  const Float4 linear = Decode(DXGI_FORMAT_R8G8B8A8_UNORM_SRGB, grey);
  EXPECT_NEAR(linear[0], 0.2158605f, 1e-6f);
  EXPECT_FLOAT_EQ(linear[3], 128.0f / 255.0f);  // alpha is linear (FS 19.1.3.2)
  EXPECT_EQ(Encode(DXGI_FORMAT_R8G8B8A8_UNORM_SRGB, linear), grey);
  // Linear 0.5: 1.055 * 0.5^(1/2.4) - 0.055 = 0.7353570; *255 + 0.5 = 188.016 -> 188.
  EXPECT_EQ(FloatToSrgb8(0.5f), 188u);
  // The linear segment: 0.002 * 12.92 = 0.02584; *255 + 0.5 = 7.09 -> 7.
  EXPECT_EQ(FloatToSrgb8(0.002f), 7u);
}

TEST(Formats, MissingChannelsReadAsZeroAndAlphaOne) {
  // FS 19.1.3.3. R8_UNORM code 51 -> (0.2, 0, 0, 1).
  const Float4 r8 = Decode(DXGI_FORMAT_R8_UNORM, StoredColor{{51, 0, 0, 0}});
  EXPECT_FLOAT_EQ(r8[0], 0.2f);
  EXPECT_EQ(r8[1], 0.0f);
  EXPECT_EQ(r8[2], 0.0f);
  EXPECT_EQ(r8[3], 1.0f);
  // R16G16_FLOAT (0x3C00, 0x4000) -> (1, 2, 0, 1).
  EXPECT_EQ(Decode(DXGI_FORMAT_R16G16_FLOAT, StoredColor{{0x3C00, 0x4000, 0, 0}}), (Float4{1, 2, 0, 1}));
  // B8G8R8X8: the X byte never reads back; alpha is 1.
  EXPECT_EQ(Decode(DXGI_FORMAT_B8G8R8X8_UNORM, StoredColor{{0, 0, 0, 0}})[3], 1.0f);
  // R32_UINT: the missing alpha is the integer 1 (FS 19.1.3.3).
  EXPECT_EQ(std::bit_cast<uint32_t>(Decode(DXGI_FORMAT_R32_UINT, StoredColor{{7, 0, 0, 0}})[3]), 1u);
}

TEST(Formats, BgraMemoryOrder) {
  // (R,G,B,A) codes (10,20,30,40) are stored B,G,R,A; the X8 byte of B8G8R8X8 is
  // written 0 and dropped on the way back.
  const StoredColor color{{10, 20, 30, 40}};
  EXPECT_EQ(PackPixel(DXGI_FORMAT_B8G8R8A8_UNORM, color), (std::vector<uint8_t>{30, 20, 10, 40}));
  const StoredColor bgrx{{10, 20, 30, 0}};
  EXPECT_EQ(PackPixel(DXGI_FORMAT_B8G8R8X8_UNORM, bgrx), (std::vector<uint8_t>{30, 20, 10, 0}));
  const std::vector<uint8_t> fromGpu{30, 20, 10, 0xFF};
  EXPECT_EQ(UnpackPixel(DXGI_FORMAT_B8G8R8X8_UNORM, fromGpu), bgrx);
}

TEST(Formats, FloatAndUintLayouts) {
  // R16G16B16A16_FLOAT (1, 2, 0.5, -1) = 0x3C00 0x4000 0x3800 0xBC00, little-endian.
  const StoredColor half = Encode(DXGI_FORMAT_R16G16B16A16_FLOAT, {1.0f, 2.0f, 0.5f, -1.0f});
  EXPECT_EQ(half, (StoredColor{{0x3C00, 0x4000, 0x3800, 0xBC00}}));
  EXPECT_EQ(PackPixel(DXGI_FORMAT_R16G16B16A16_FLOAT, half),
            (std::vector<uint8_t>{0x00, 0x3C, 0x00, 0x40, 0x00, 0x38, 0x00, 0xBC}));
  // R32_FLOAT 1.0 = 0x3F800000 -> 00 00 80 3F; R32_UINT 0x01020304 -> 04 03 02 01.
  EXPECT_EQ(PackPixel(DXGI_FORMAT_R32_FLOAT, Encode(DXGI_FORMAT_R32_FLOAT, {1.0f, 0, 0, 0})),
            (std::vector<uint8_t>{0x00, 0x00, 0x80, 0x3F}));
  EXPECT_EQ(PackPixel(DXGI_FORMAT_R32_UINT, Encode(DXGI_FORMAT_R32_UINT, UintRegister(0x01020304, 0, 0, 0))),
            (std::vector<uint8_t>{0x04, 0x03, 0x02, 0x01}));
  EXPECT_EQ(BytesPerPixel(DXGI_FORMAT_R32G32B32A32_UINT), 16u);
  EXPECT_EQ(BytesPerPixel(DXGI_FORMAT_R16G16_FLOAT), 4u);
  EXPECT_EQ(BytesPerPixel(DXGI_FORMAT_R8_UNORM), 1u);
}

TEST(Formats, UnmodelledFormatsAreRejected) {
  EXPECT_FALSE(IsReferenceFormat(DXGI_FORMAT_R8G8_SNORM));
  EXPECT_TRUE(IsReferenceFormat(DXGI_FORMAT_R10G10B10A2_UNORM));
  EXPECT_THROW(Encode(DXGI_FORMAT_R16_SINT, {0, 0, 0, 0}), std::invalid_argument);
}

// 16-bit UNORM (FS 3.2.3.6 with n = 16) and the BGRX sRGB layout.
TEST(Formats, SixteenBitUnormAndBgrxSrgb) {
  // 0.5 * 65535 + 0.5 = 32768 -> 00 80; 1.0 -> FF FF.
  EXPECT_EQ(PackPixel(DXGI_FORMAT_R16G16_UNORM, Encode(DXGI_FORMAT_R16G16_UNORM, {0.5f, 1.0f, 0, 0})),
            (std::vector<uint8_t>{0x00, 0x80, 0xFF, 0xFF}));
  const StoredColor bgrx = UnpackPixel(DXGI_FORMAT_B8G8R8X8_UNORM_SRGB, std::vector<uint8_t>{255, 0, 0, 77});
  EXPECT_EQ(bgrx, (StoredColor{{0, 0, 255, 0}}));  // B in the first byte; the X byte is no channel
  EXPECT_EQ(Decode(DXGI_FORMAT_B8G8R8X8_UNORM_SRGB, bgrx)[3], 1.0f);
}

}  // namespace
}  // namespace rhi::reference
