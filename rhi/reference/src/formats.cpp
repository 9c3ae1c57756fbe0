#include "rhi_reference/formats.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <string>

#include "rhi_reference/float16.h"

namespace rhi::reference {
namespace {

using K = ChannelKind;

// One row per format. `memoryOrder[i]` is the RGBA channel stored at the i-th
// position in memory (-1: none), each `channelBytes` wide; R10G10B10A2 is the
// one packed format and is handled by name.
struct FormatInfo {
  DXGI_FORMAT format;
  std::array<ChannelKind, 4> kinds;
  std::array<uint8_t, 4> unormBits;
  std::array<int8_t, 4> memoryOrder;
  uint8_t channelBytes;
};

// B8G8R8X8: the X byte is stored but is no channel (FS 19.1.3.1 "X: unused").
constexpr FormatInfo kFormats[] = {
    {DXGI_FORMAT_R8G8B8A8_UNORM, {K::Unorm, K::Unorm, K::Unorm, K::Unorm}, {8, 8, 8, 8}, {0, 1, 2, 3}, 1},
    {DXGI_FORMAT_R8G8B8A8_UNORM_SRGB, {K::Srgb, K::Srgb, K::Srgb, K::Unorm}, {8, 8, 8, 8}, {0, 1, 2, 3}, 1},
    {DXGI_FORMAT_B8G8R8A8_UNORM, {K::Unorm, K::Unorm, K::Unorm, K::Unorm}, {8, 8, 8, 8}, {2, 1, 0, 3}, 1},
    {DXGI_FORMAT_B8G8R8X8_UNORM, {K::Unorm, K::Unorm, K::Unorm, K::Absent}, {8, 8, 8, 0}, {2, 1, 0, 3}, 1},
    {DXGI_FORMAT_R10G10B10A2_UNORM, {K::Unorm, K::Unorm, K::Unorm, K::Unorm}, {10, 10, 10, 2}, {0, 1, 2, 3}, 0},
    {DXGI_FORMAT_R16G16B16A16_FLOAT, {K::Float16, K::Float16, K::Float16, K::Float16}, {}, {0, 1, 2, 3}, 2},
    {DXGI_FORMAT_R32G32B32A32_FLOAT, {K::Float32, K::Float32, K::Float32, K::Float32}, {}, {0, 1, 2, 3}, 4},
    {DXGI_FORMAT_R16G16_FLOAT, {K::Float16, K::Float16, K::Absent, K::Absent}, {}, {0, 1, -1, -1}, 2},
    {DXGI_FORMAT_R8_UNORM, {K::Unorm, K::Absent, K::Absent, K::Absent}, {8, 0, 0, 0}, {0, -1, -1, -1}, 1},
    {DXGI_FORMAT_R16_FLOAT, {K::Float16, K::Absent, K::Absent, K::Absent}, {}, {0, -1, -1, -1}, 2},
    {DXGI_FORMAT_R32_FLOAT, {K::Float32, K::Absent, K::Absent, K::Absent}, {}, {0, -1, -1, -1}, 4},
    {DXGI_FORMAT_R32_UINT, {K::Uint, K::Absent, K::Absent, K::Absent}, {}, {0, -1, -1, -1}, 4},
    {DXGI_FORMAT_R32G32B32A32_UINT, {K::Uint, K::Uint, K::Uint, K::Uint}, {}, {0, 1, 2, 3}, 4},
    // The other render-target formats whose conversions are the rules above (UNORM of any
    // width, sRGB 8-bit, float32, 32-bit UINT), so that fxtool can read them back.
    {DXGI_FORMAT_R16G16B16A16_UNORM, {K::Unorm, K::Unorm, K::Unorm, K::Unorm}, {16, 16, 16, 16}, {0, 1, 2, 3}, 2},
    {DXGI_FORMAT_R32G32_FLOAT, {K::Float32, K::Float32, K::Absent, K::Absent}, {}, {0, 1, -1, -1}, 4},
    {DXGI_FORMAT_R32G32_UINT, {K::Uint, K::Uint, K::Absent, K::Absent}, {}, {0, 1, -1, -1}, 4},
    {DXGI_FORMAT_R16G16_UNORM, {K::Unorm, K::Unorm, K::Absent, K::Absent}, {16, 16, 0, 0}, {0, 1, -1, -1}, 2},
    {DXGI_FORMAT_R8G8_UNORM, {K::Unorm, K::Unorm, K::Absent, K::Absent}, {8, 8, 0, 0}, {0, 1, -1, -1}, 1},
    {DXGI_FORMAT_R16_UNORM, {K::Unorm, K::Absent, K::Absent, K::Absent}, {16, 0, 0, 0}, {0, -1, -1, -1}, 2},
    {DXGI_FORMAT_B8G8R8A8_UNORM_SRGB, {K::Srgb, K::Srgb, K::Srgb, K::Unorm}, {8, 8, 8, 8}, {2, 1, 0, 3}, 1},
    {DXGI_FORMAT_B8G8R8X8_UNORM_SRGB, {K::Srgb, K::Srgb, K::Srgb, K::Absent}, {8, 8, 8, 0}, {2, 1, 0, 3}, 1},
};

const FormatInfo* Find(DXGI_FORMAT format) {
  for (const FormatInfo& info : kFormats) {
    if (info.format == format) return &info;
  }
  return nullptr;
}

const FormatInfo& Info(DXGI_FORMAT format) {
  const FormatInfo* info = Find(format);
  if (info == nullptr) {
    throw std::invalid_argument("rhi::reference: DXGI_FORMAT " + std::to_string(format) +
                                " is not modelled");
  }
  return *info;
}

uint32_t MaxCode(int bits) { return (1u << bits) - 1u; }

uint32_t EncodeChannel(ChannelKind kind, int bits, float value) {
  switch (kind) {
    case K::Absent: return 0;
    case K::Unorm: return FloatToUnorm(value, bits);
    case K::Srgb: return FloatToSrgb8(value);
    case K::Float16: return FloatToHalf(value, HalfRounding::TowardZero);
    case K::Float32: return std::bit_cast<uint32_t>(value);
    case K::Uint: return std::bit_cast<uint32_t>(value);  // no conversion: the register bits
  }
  return 0;
}

float DecodeChannel(ChannelKind kind, int bits, uint32_t code) {
  switch (kind) {
    case K::Absent: return 0.0f;  // callers handle missing alpha
    case K::Unorm: return UnormToFloat(code, bits);
    case K::Srgb: return SrgbToLinear(UnormToFloat(code, 8));
    case K::Float16: return HalfToFloat(static_cast<uint16_t>(code));
    case K::Float32: return std::bit_cast<float>(code);
    case K::Uint: return std::bit_cast<float>(code);
  }
  return 0.0f;
}

void StoreLittleEndian(uint32_t value, std::size_t byteCount, uint8_t* out) {
  for (std::size_t i = 0; i < byteCount; ++i) out[i] = static_cast<uint8_t>(value >> (8 * i));
}

uint32_t LoadLittleEndian(const uint8_t* in, std::size_t byteCount) {
  uint32_t value = 0;
  for (std::size_t i = 0; i < byteCount; ++i) value |= static_cast<uint32_t>(in[i]) << (8 * i);
  return value;
}

// R10G10B10A2: FS 19.1.3.1, R bits 0-9, G 10-19, B 20-29, A 30-31.
uint32_t PackR10G10B10A2(const StoredColor& s) {
  return (s.bits[0] & 0x3FFu) | (s.bits[1] & 0x3FFu) << 10 | (s.bits[2] & 0x3FFu) << 20 |
         (s.bits[3] & 0x3u) << 30;
}

StoredColor UnpackR10G10B10A2(uint32_t word) {
  return StoredColor{{word & 0x3FFu, (word >> 10) & 0x3FFu, (word >> 20) & 0x3FFu, word >> 30}};
}

// FS 3.2.3.8 before the integer step: NaN -> 0, clamp to [0,1], the sRGB curve.
double EncodeSrgbCurve(float linear) {
  if (std::isnan(linear)) return 0.0;
  const double c = std::clamp(static_cast<double>(linear), 0.0, 1.0);
  return c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1.0 / 2.4) - 0.055;
}

}  // namespace

bool IsReferenceFormat(DXGI_FORMAT format) { return Find(format) != nullptr; }

ChannelKind KindOf(DXGI_FORMAT format, int channel) { return Info(format).kinds.at(channel); }

int UnormBits(DXGI_FORMAT format, int channel) { return Info(format).unormBits.at(channel); }

bool IsUintFormat(DXGI_FORMAT format) { return Info(format).kinds[0] == K::Uint; }

bool IsNormalizedFormat(DXGI_FORMAT format) {
  const ChannelKind first = Info(format).kinds[0];
  return first == K::Unorm || first == K::Srgb;
}

std::size_t BytesPerPixel(DXGI_FORMAT format) {
  const FormatInfo& info = Info(format);
  if (format == DXGI_FORMAT_R10G10B10A2_UNORM) return 4;
  const auto stored = std::count_if(info.memoryOrder.begin(), info.memoryOrder.end(),
                                    [](int8_t channel) { return channel >= 0; });
  return static_cast<std::size_t>(stored) * info.channelBytes;
}

StoredColor Encode(DXGI_FORMAT format, const Float4& value) {
  const FormatInfo& info = Info(format);
  StoredColor stored;
  for (int c = 0; c < 4; ++c) stored.bits[c] = EncodeChannel(info.kinds[c], info.unormBits[c], value[c]);
  return stored;
}

Float4 Decode(DXGI_FORMAT format, const StoredColor& stored) {
  const FormatInfo& info = Info(format);
  Float4 value{};
  for (int c = 0; c < 4; ++c) value[c] = DecodeChannel(info.kinds[c], info.unormBits[c], stored.bits[c]);
  // FS 19.1.3.3: a missing A reads as 1 in the first channel's interpretation.
  if (info.kinds[3] == K::Absent) {
    value[3] = IsUintFormat(format) ? std::bit_cast<float>(1u) : 1.0f;
  }
  return value;
}

std::vector<uint8_t> PackPixel(DXGI_FORMAT format, const StoredColor& stored) {
  const FormatInfo& info = Info(format);
  std::vector<uint8_t> bytes(BytesPerPixel(format), 0);
  if (format == DXGI_FORMAT_R10G10B10A2_UNORM) {
    StoreLittleEndian(PackR10G10B10A2(stored), 4, bytes.data());
    return bytes;
  }
  for (std::size_t slot = 0; slot * info.channelBytes < bytes.size(); ++slot) {
    const int channel = info.memoryOrder[slot];
    StoreLittleEndian(stored.bits[channel], info.channelBytes, bytes.data() + slot * info.channelBytes);
  }
  return bytes;
}

StoredColor UnpackPixel(DXGI_FORMAT format, std::span<const uint8_t> bytes) {
  const FormatInfo& info = Info(format);
  if (bytes.size() < BytesPerPixel(format)) throw std::invalid_argument("UnpackPixel: too few bytes");
  if (format == DXGI_FORMAT_R10G10B10A2_UNORM) return UnpackR10G10B10A2(LoadLittleEndian(bytes.data(), 4));
  StoredColor stored;
  for (std::size_t slot = 0; slot * info.channelBytes < BytesPerPixel(format); ++slot) {
    const int channel = info.memoryOrder[slot];
    // The X8 byte of B8G8R8X8 is no channel: dropped, so stored colours compare equal.
    if (info.kinds[channel] == K::Absent) continue;
    stored.bits[channel] = LoadLittleEndian(bytes.data() + slot * info.channelBytes, info.channelBytes);
  }
  return stored;
}

uint32_t FloatToUnorm(float value, int bits) {
  if (std::isnan(value)) return 0;
  const double clamped = std::clamp(static_cast<double>(value), 0.0, 1.0);
  // Scale, add 0.5 and drop the fraction: round half up. Done in double so the
  // reference is the infinitely precise ideal the 0.6-ULP tolerance is measured from.
  return static_cast<uint32_t>(clamped * MaxCode(bits) + 0.5);
}

float UnormToFloat(uint32_t code, int bits) {
  return static_cast<float>(static_cast<double>(code) / MaxCode(bits));
}

float SrgbToLinear(float encoded) {
  const double c = encoded;
  const double linear = c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
  return static_cast<float>(linear);
}

float LinearToSrgb(float linear) { return static_cast<float>(EncodeSrgbCurve(linear)); }

uint32_t FloatToSrgb8(float linear) {
  return static_cast<uint32_t>(EncodeSrgbCurve(linear) * 255.0 + 0.5);  // round half up, as UNORM
}

Float4 UintRegister(uint32_t r, uint32_t g, uint32_t b, uint32_t a) {
  return {std::bit_cast<float>(r), std::bit_cast<float>(g), std::bit_cast<float>(b), std::bit_cast<float>(a)};
}

}  // namespace rhi::reference
