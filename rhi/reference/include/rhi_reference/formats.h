// The render-target formats the reference model knows, and how each one turns
// floats into stored bits and back (FS 3.2 "Data Conversion", FS 19.1 "Formats").
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "rhi/d3d11_types.h"

namespace rhi::reference {

// A pixel shader output register or a decoded pixel, RGBA. For UINT formats the
// four floats carry the register's raw 32-bit patterns (see UintRegister).
using Float4 = std::array<float, 4>;

// What a render target stores for one pixel, channel by channel in RGBA order
// (memory order is PackPixel's business): UNORM / sRGB codes, float16 or float32
// bit patterns, or UINT values. Channels the format lacks (including the X8 of
// B8G8R8X8) hold 0.
struct StoredColor {
  std::array<uint32_t, 4> bits{};
  friend bool operator==(const StoredColor&, const StoredColor&) = default;
};

enum class ChannelKind : uint8_t { Absent, Unorm, Srgb, Float16, Float32, Uint };

// R8G8B8A8_UNORM(_SRGB), B8G8R8A8_UNORM(_SRGB), B8G8R8X8_UNORM(_SRGB), R10G10B10A2_UNORM,
// R16G16B16A16_FLOAT/UNORM, R32G32B32A32_FLOAT, R32G32_FLOAT/UINT, R16G16_FLOAT/UNORM,
// R8G8_UNORM, R8_UNORM, R16_FLOAT/UNORM, R32_FLOAT, R32_UINT, R32G32B32A32_UINT.
// Everything else (SNORM, SINT, 8/16-bit UINT, R11G11B10_FLOAT, A8_UNORM) is rejected
// (the functions below throw std::invalid_argument).
bool IsReferenceFormat(DXGI_FORMAT format);
ChannelKind KindOf(DXGI_FORMAT format, int channel);
int UnormBits(DXGI_FORMAT format, int channel);  // 0 unless UNORM or sRGB
bool IsUintFormat(DXGI_FORMAT format);
// UNORM and sRGB targets: the blender clamps its inputs to [0,1] (FS 17.5).
bool IsNormalizedFormat(DXGI_FORMAT format);
std::size_t BytesPerPixel(DXGI_FORMAT format);

// Float -> stored, per channel, as D3D11 converts a shader output for the target:
// UNORM FS 3.2.3.6, sRGB FS 3.2.3.8 (alpha stays linear, FS 19.1.3.2), float16
// FS 3.2.2 (round toward zero), float32 unchanged, UINT the raw register bits.
StoredColor Encode(DXGI_FORMAT format, const Float4& value);

// Stored -> float, as the blender reads the destination: UNORM FS 3.2.3.5, sRGB
// FS 3.2.3.7 (so sRGB channels come back linear), missing channels FS 19.1.3.3
// (0, alpha 1; for UINT formats the "1" is the integer 1).
Float4 Decode(DXGI_FORMAT format, const StoredColor& stored);

// Memory layout of one pixel (FS 19.1.3.1: components at increasing addresses,
// little-endian; R10G10B10A2 as one 32-bit word, R in bits 0-9, A in 30-31).
std::vector<uint8_t> PackPixel(DXGI_FORMAT format, const StoredColor& stored);
StoredColor UnpackPixel(DXGI_FORMAT format, std::span<const uint8_t> bytes);

// The single-value conversions the above are made of.
uint32_t FloatToUnorm(float value, int bits);   // FS 3.2.3.6: NaN->0, clamp, *(2^n-1), +0.5, truncate
float UnormToFloat(uint32_t code, int bits);    // FS 3.2.3.5
float SrgbToLinear(float encoded);              // FS 3.2.3.7, ideal curve, no quantisation
float LinearToSrgb(float linear);               // FS 3.2.3.8, ideal curve, no quantisation
uint32_t FloatToSrgb8(float linear);            // FS 3.2.3.8 with the 8-bit rounding

// A UINT shader output as the Float4 the blend functions take: the register bits.
Float4 UintRegister(uint32_t r, uint32_t g, uint32_t b, uint32_t a);

}  // namespace rhi::reference
