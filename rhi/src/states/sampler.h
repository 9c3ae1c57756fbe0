// D3D11 sampler state: validation, canonical form, hashing, Vulkan translation.
#pragma once

#include <vulkan/vulkan_core.h>

#include <cstdint>
#include <string>

#include "rhi/d3d11_types.h"

namespace rhi::states {

inline constexpr FLOAT MIP_LOD_BIAS_MIN = -16.0f;  // D3D11_MIP_LOD_BIAS_MIN
inline constexpr FLOAT MIP_LOD_BIAS_MAX = 15.99f;  // D3D11_MIP_LOD_BIAS_MAX

// Empty when CreateSamplerState accepts the desc, else the reason, e.g.
// "SAMPLER_DESC.Filter: 0x2 is not a valid D3D11_FILTER".
// ComparisonFunc is checked only for COMPARISON filters. MinLOD > MaxLOD is
// accepted (see sampler.cpp); NaN is refused in every float field.
std::string Validate(const SAMPLER_DESC& desc);

// Canonical desc (Wine's d3d_sampler_state_create, which matches native GetDesc):
// MaxAnisotropy 0 unless the filter is anisotropic, ComparisonFunc NEVER unless
// it is a comparison filter, BorderColor 0 unless an address mode is BORDER.
SAMPLER_DESC Normalize(const SAMPLER_DESC& desc);

bool RawEqual(const SAMPLER_DESC& a, const SAMPLER_DESC& b);
uint64_t RawHash(const SAMPLER_DESC& desc);
bool KeyEqual(const SAMPLER_DESC& a, const SAMPLER_DESC& b);
uint64_t KeyHash(const SAMPLER_DESC& desc);

// D3D11_FILTER decoded (d3d11.h D3D11_ENCODE_BASIC_FILTER: mip bit 0, mag bit 2,
// min bit 4, anisotropic bit 6, comparison bit 7).
struct FilterVk {
  VkFilter minFilter = VK_FILTER_NEAREST;
  VkFilter magFilter = VK_FILTER_NEAREST;
  VkSamplerMipmapMode mipmapMode = VK_SAMPLER_MIPMAP_MODE_NEAREST;
  bool anisotropic = false;
  bool comparison = false;
};
FilterVk DecodeFilter(FILTER filter);

// Device limits the translation clamps to (VkPhysicalDeviceLimits).
struct SamplerLimits {
  float maxSamplerAnisotropy = 16.0f;
  float maxSamplerLodBias = MIP_LOD_BIAS_MAX;
};

struct SamplerVk {
  VkSamplerCreateInfo info{};  // pNext null: chain customBorder when needsCustomBorderColor
  VkSamplerCustomBorderColorCreateInfoEXT customBorder{};
  // info.borderColor is VK_BORDER_COLOR_FLOAT_CUSTOM_EXT: needs VK_EXT_custom_border_color
  // with customBorderColors and, as customBorder.format is UNDEFINED (the sampler
  // does not know the view format), customBorderColorWithoutFormat.
  bool needsCustomBorderColor = false;
  bool needsAnisotropy = false;         // samplerAnisotropy feature
  bool needsMirrorClampToEdge = false;  // MIRROR_ONCE: samplerMirrorClampToEdge (Vulkan 1.2 feature)
};

// Translates the normalised desc. LODs: MaxLOD >= VK_LOD_CLAMP_NONE (D3D's
// FLOAT32_MAX) becomes VK_LOD_CLAMP_NONE; minLod is clamped to [0, VK_LOD_CLAMP_NONE]
// and maxLod to [minLod, VK_LOD_CLAMP_NONE] (Vulkan requires maxLod >= minLod).
// MipLODBias and MaxAnisotropy are clamped to `limits`.
SamplerVk ToVulkan(const SAMPLER_DESC& desc, const SamplerLimits& limits = {});

// One of Vulkan's three core colours when the float4 equals it exactly,
// otherwise VK_BORDER_COLOR_FLOAT_CUSTOM_EXT (VK_EXT_custom_border_color).
VkBorderColor ChooseBorderColor(const FLOAT (&color)[4]);
VkSamplerAddressMode ToVkAddressMode(TEXTURE_ADDRESS_MODE mode);

}  // namespace rhi::states
