// Small DDS files written byte by byte for the texture-file tests (the layout of
// Microsoft's "DDS_HEADER" / "DDS_HEADER_DXT10" reference pages, not the loader's structs).
#pragma once

#include <cstdint>
#include <cstring>
#include <vector>

namespace textures_test {

struct LegacyPixelFormat {
  uint32_t flags, fourCC, bits, r, g, b, a;
};
constexpr uint32_t kFourCC = 0x4, kRgb = 0x40, kAlphaPixels = 0x1;
constexpr uint32_t FourCC(const char (&s)[5]) {
  return uint32_t(uint8_t(s[0])) | uint32_t(uint8_t(s[1])) << 8 | uint32_t(uint8_t(s[2])) << 16 |
         uint32_t(uint8_t(s[3])) << 24;
}
constexpr LegacyPixelFormat kDxt1{kFourCC, FourCC("DXT1"), 0, 0, 0, 0, 0};
constexpr LegacyPixelFormat kRgba8{kRgb | kAlphaPixels, 0, 32, 0xff, 0xff00, 0xff0000, 0xff000000};
constexpr LegacyPixelFormat kDx10{kFourCC, FourCC("DX10"), 0, 0, 0, 0, 0};

struct DdsShape {
  uint32_t width = 4, height = 4, depth = 0, mips = 1;
  LegacyPixelFormat format = kDxt1;
  uint32_t caps2 = 0;  // 0xFE00: cube map with all faces; 0x200000: volume
  // DX10 extension (written when format is kDx10).
  uint32_t dxgiFormat = 0, dimension = 3, miscFlag = 0, arraySize = 1;
};

inline void Put(std::vector<uint8_t>& out, uint32_t v) {
  for (int i = 0; i < 4; ++i) out.push_back(uint8_t(v >> (8 * i)));
}

// "DDS ", the 124-byte header, the DX10 header when asked, then `texels`.
inline std::vector<uint8_t> WriteDds(const DdsShape& s, const std::vector<uint8_t>& texels) {
  std::vector<uint8_t> out;
  Put(out, FourCC("DDS "));
  Put(out, 124);
  Put(out, 0x1 | 0x2 | 0x4 | 0x1000 | (s.mips > 1 ? 0x20000 : 0) | (s.depth ? 0x800000 : 0));  // CAPS|HEIGHT|WIDTH|PIXELFORMAT
  Put(out, s.height);
  Put(out, s.width);
  Put(out, 0);  // pitch or linear size
  Put(out, s.depth);
  Put(out, s.mips);
  for (int i = 0; i < 11; ++i) Put(out, 0);
  Put(out, 32);
  for (uint32_t v : {s.format.flags, s.format.fourCC, s.format.bits, s.format.r, s.format.g, s.format.b, s.format.a})
    Put(out, v);
  Put(out, 0x1000 | (s.mips > 1 ? 0x400008 : 0) | (s.caps2 ? 0x8 : 0));  // caps
  Put(out, s.caps2);
  for (int i = 0; i < 3; ++i) Put(out, 0);
  if (s.format.fourCC == FourCC("DX10"))
    for (uint32_t v : {s.dxgiFormat, s.dimension, s.miscFlag, s.arraySize, 0u}) Put(out, v);
  out.insert(out.end(), texels.begin(), texels.end());
  return out;
}

// One BC1 block: colours c0 > c1 (4-colour mode), 2-bit indices row-major from texel (0,0).
inline std::vector<uint8_t> Bc1Block(uint16_t c0, uint16_t c1, uint32_t indices) {
  std::vector<uint8_t> block{uint8_t(c0), uint8_t(c0 >> 8), uint8_t(c1), uint8_t(c1 >> 8)};
  for (int i = 0; i < 4; ++i) block.push_back(uint8_t(indices >> (8 * i)));
  return block;
}

}  // namespace textures_test
