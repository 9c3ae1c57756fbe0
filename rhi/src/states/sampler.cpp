#include "states/sampler.h"

#include <algorithm>
#include <cmath>

#include "states/depth_stencil.h"
#include "states/util.h"

namespace rhi::states {
namespace {

constexpr const char* kPrefix = "SAMPLER_DESC.";

bool IsDefinedFilter(FILTER f) {
  switch (f) {
    case FILTER_MIN_MAG_MIP_POINT:
    case FILTER_MIN_MAG_POINT_MIP_LINEAR:
    case FILTER_MIN_POINT_MAG_LINEAR_MIP_POINT:
    case FILTER_MIN_POINT_MAG_MIP_LINEAR:
    case FILTER_MIN_LINEAR_MAG_MIP_POINT:
    case FILTER_MIN_LINEAR_MAG_POINT_MIP_LINEAR:
    case FILTER_MIN_MAG_LINEAR_MIP_POINT:
    case FILTER_MIN_MAG_MIP_LINEAR:
    case FILTER_ANISOTROPIC:
    case FILTER_COMPARISON_MIN_MAG_MIP_POINT:
    case FILTER_COMPARISON_MIN_MAG_POINT_MIP_LINEAR:
    case FILTER_COMPARISON_MIN_POINT_MAG_LINEAR_MIP_POINT:
    case FILTER_COMPARISON_MIN_POINT_MAG_MIP_LINEAR:
    case FILTER_COMPARISON_MIN_LINEAR_MAG_MIP_POINT:
    case FILTER_COMPARISON_MIN_LINEAR_MAG_POINT_MIP_LINEAR:
    case FILTER_COMPARISON_MIN_MAG_LINEAR_MIP_POINT:
    case FILTER_COMPARISON_MIN_MAG_MIP_LINEAR:
    case FILTER_COMPARISON_ANISOTROPIC:
      return true;
  }
  return false;
}

bool UsesBorder(const SAMPLER_DESC& d) {
  return d.AddressU == TEXTURE_ADDRESS_BORDER || d.AddressV == TEXTURE_ADDRESS_BORDER ||
         d.AddressW == TEXTURE_ADDRESS_BORDER;
}

std::string CheckAddress(const char* field, TEXTURE_ADDRESS_MODE m) {
  if (m >= TEXTURE_ADDRESS_WRAP && m <= TEXTURE_ADDRESS_MIRROR_ONCE) return {};
  return kPrefix + std::string(field) + ": " + std::to_string(m) + " is not a valid D3D11_TEXTURE_ADDRESS_MODE";
}

std::string CheckNotNan(const std::string& field, float v) {
  if (!std::isnan(v)) return {};
  return kPrefix + field + ": NaN is not allowed";
}

std::string CheckMipLodBias(float bias) {
  if (std::string error = CheckNotNan("MipLODBias", bias); !error.empty()) return error;
  // Judgement: D3D11_MIP_LOD_BIAS_MIN/MAX bound the field; we refuse values
  // outside them rather than clamp silently.
  if (bias >= MIP_LOD_BIAS_MIN && bias <= MIP_LOD_BIAS_MAX) return {};
  return std::string(kPrefix) + "MipLODBias: " + FloatText(bias) + " is outside [-16, 15.99]";
}

std::string CheckAnisotropy(const SAMPLER_DESC& d) {
  // D3D11_SAMPLER_DESC: "Valid values are between 1 and 16" for anisotropic
  // filters. Other filters ignore the field, but values above
  // D3D11_REQ_MAXANISOTROPY are still refused (DXVK does the same); 0 is common
  // there (zero-initialised descs) and accepted.
  const std::string field = std::string(kPrefix) + "MaxAnisotropy: " + std::to_string(d.MaxAnisotropy);
  if (d.MaxAnisotropy > REQ_MAXANISOTROPY) return field + " exceeds D3D11_REQ_MAXANISOTROPY (16)";
  if (DecodeFilter(d.Filter).anisotropic && d.MaxAnisotropy < 1)
    return field + " is invalid for an anisotropic filter (valid: 1..16)";
  return {};
}

std::string CheckComparison(const SAMPLER_DESC& d) {
  // Only comparison filters read ComparisonFunc; the runtime resets it otherwise.
  if (!DecodeFilter(d.Filter).comparison || ComparisonName(d.ComparisonFunc)) return {};
  return std::string(kPrefix) + "ComparisonFunc: " + std::to_string(d.ComparisonFunc) +
         " is not a valid D3D11_COMPARISON_FUNC";
}

// D3D allows MaxLOD = FLOAT32_MAX ("no clamp"); Vulkan's largest meaningful
// value is VK_LOD_CLAMP_NONE. Below 0 the LOD is clamped to 0 anyway (Vulkan
// and D3D both pick level 0 and magnification for LOD <= 0), so clamping the
// bounds at 0 changes nothing and avoids -FLOAT32_MAX reaching the driver.
float ClampLod(float lod) { return std::clamp(lod, 0.0f, VK_LOD_CLAMP_NONE); }

}  // namespace

FilterVk DecodeFilter(FILTER filter) {
  const UINT bits = filter;
  FilterVk out;
  out.mipmapMode = (bits & 0x01) ? VK_SAMPLER_MIPMAP_MODE_LINEAR : VK_SAMPLER_MIPMAP_MODE_NEAREST;
  out.magFilter = (bits & 0x04) ? VK_FILTER_LINEAR : VK_FILTER_NEAREST;
  out.minFilter = (bits & 0x10) ? VK_FILTER_LINEAR : VK_FILTER_NEAREST;
  out.anisotropic = (bits & 0x40) != 0;
  out.comparison = (bits & 0x80) != 0;
  return out;
}

std::string Validate(const SAMPLER_DESC& desc) {
  if (!IsDefinedFilter(desc.Filter))
    return std::string(kPrefix) + "Filter: " + HexText(desc.Filter) + " is not a valid D3D11_FILTER";
  for (const std::string& error :
       {CheckAddress("AddressU", desc.AddressU), CheckAddress("AddressV", desc.AddressV),
        CheckAddress("AddressW", desc.AddressW), CheckMipLodBias(desc.MipLODBias), CheckAnisotropy(desc),
        CheckComparison(desc), CheckNotNan("BorderColor[0]", desc.BorderColor[0]),
        CheckNotNan("BorderColor[1]", desc.BorderColor[1]), CheckNotNan("BorderColor[2]", desc.BorderColor[2]),
        CheckNotNan("BorderColor[3]", desc.BorderColor[3]), CheckNotNan("MinLOD", desc.MinLOD),
        CheckNotNan("MaxLOD", desc.MaxLOD)}) {
    if (!error.empty()) return error;
  }
  // Judgement: the docs say MaxLOD "must be greater than or equal to MinLOD",
  // but the runtime is not known to refuse it (Wine clamps MaxLOD up to MinLOD
  // instead), so it is accepted and ToVulkan clamps the same way.
  return {};
}

SAMPLER_DESC Normalize(const SAMPLER_DESC& desc) {
  SAMPLER_DESC out = desc;
  const FilterVk f = DecodeFilter(desc.Filter);
  if (!f.anisotropic) out.MaxAnisotropy = 0;
  if (!f.comparison) out.ComparisonFunc = COMPARISON_NEVER;
  if (!UsesBorder(desc)) std::fill(std::begin(out.BorderColor), std::end(out.BorderColor), 0.0f);
  return out;
}

bool RawEqual(const SAMPLER_DESC& a, const SAMPLER_DESC& b) {
  for (int i = 0; i < 4; ++i) {
    if (!SameBits(a.BorderColor[i], b.BorderColor[i])) return false;
  }
  return a.Filter == b.Filter && a.AddressU == b.AddressU && a.AddressV == b.AddressV && a.AddressW == b.AddressW &&
         SameBits(a.MipLODBias, b.MipLODBias) && a.MaxAnisotropy == b.MaxAnisotropy &&
         a.ComparisonFunc == b.ComparisonFunc && SameBits(a.MinLOD, b.MinLOD) && SameBits(a.MaxLOD, b.MaxLOD);
}

uint64_t RawHash(const SAMPLER_DESC& desc) {
  Fnv1a h;
  h.Add(desc.Filter);
  h.Add(desc.AddressU);
  h.Add(desc.AddressV);
  h.Add(desc.AddressW);
  h.Add(desc.MipLODBias);
  h.Add(desc.MaxAnisotropy);
  h.Add(desc.ComparisonFunc);
  for (float c : desc.BorderColor) h.Add(c);
  h.Add(desc.MinLOD);
  h.Add(desc.MaxLOD);
  return h.value();
}

bool KeyEqual(const SAMPLER_DESC& a, const SAMPLER_DESC& b) { return RawEqual(Normalize(a), Normalize(b)); }
uint64_t KeyHash(const SAMPLER_DESC& desc) { return RawHash(Normalize(desc)); }

SamplerVk ToVulkan(const SAMPLER_DESC& desc, const SamplerLimits& limits) {
  const SAMPLER_DESC n = Normalize(desc);
  const FilterVk f = DecodeFilter(n.Filter);
  SamplerVk out;
  VkSamplerCreateInfo& info = out.info;
  info.sType = VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO;
  info.magFilter = f.magFilter;
  info.minFilter = f.minFilter;
  info.mipmapMode = f.mipmapMode;
  info.addressModeU = ToVkAddressMode(n.AddressU);
  info.addressModeV = ToVkAddressMode(n.AddressV);
  info.addressModeW = ToVkAddressMode(n.AddressW);
  info.mipLodBias = std::clamp(n.MipLODBias, -limits.maxSamplerLodBias, limits.maxSamplerLodBias);
  info.anisotropyEnable = f.anisotropic ? VK_TRUE : VK_FALSE;
  info.maxAnisotropy =
      f.anisotropic ? std::clamp(static_cast<float>(n.MaxAnisotropy), 1.0f, limits.maxSamplerAnisotropy) : 1.0f;
  info.compareEnable = f.comparison ? VK_TRUE : VK_FALSE;
  info.compareOp = f.comparison ? ToVkCompareOp(n.ComparisonFunc) : VK_COMPARE_OP_NEVER;
  info.minLod = ClampLod(n.MinLOD);
  info.maxLod = std::max(ClampLod(n.MaxLOD), info.minLod);
  info.borderColor = ChooseBorderColor(n.BorderColor);  // all zero unless BORDER is used
  info.unnormalizedCoordinates = VK_FALSE;

  out.needsCustomBorderColor = info.borderColor == VK_BORDER_COLOR_FLOAT_CUSTOM_EXT;
  if (out.needsCustomBorderColor) {
    out.customBorder.sType = VK_STRUCTURE_TYPE_SAMPLER_CUSTOM_BORDER_COLOR_CREATE_INFO_EXT;
    std::copy(std::begin(n.BorderColor), std::end(n.BorderColor), out.customBorder.customBorderColor.float32);
    out.customBorder.format = VK_FORMAT_UNDEFINED;
  }
  out.needsAnisotropy = f.anisotropic;
  out.needsMirrorClampToEdge = info.addressModeU == VK_SAMPLER_ADDRESS_MODE_MIRROR_CLAMP_TO_EDGE ||
                               info.addressModeV == VK_SAMPLER_ADDRESS_MODE_MIRROR_CLAMP_TO_EDGE ||
                               info.addressModeW == VK_SAMPLER_ADDRESS_MODE_MIRROR_CLAMP_TO_EDGE;
  return out;
}

VkBorderColor ChooseBorderColor(const FLOAT (&c)[4]) {
  auto is = [&c](float r, float g, float b, float a) { return c[0] == r && c[1] == g && c[2] == b && c[3] == a; };
  if (is(0, 0, 0, 0)) return VK_BORDER_COLOR_FLOAT_TRANSPARENT_BLACK;
  if (is(0, 0, 0, 1)) return VK_BORDER_COLOR_FLOAT_OPAQUE_BLACK;
  if (is(1, 1, 1, 1)) return VK_BORDER_COLOR_FLOAT_OPAQUE_WHITE;
  return VK_BORDER_COLOR_FLOAT_CUSTOM_EXT;
}

VkSamplerAddressMode ToVkAddressMode(TEXTURE_ADDRESS_MODE mode) {
  switch (mode) {
    case TEXTURE_ADDRESS_WRAP: return VK_SAMPLER_ADDRESS_MODE_REPEAT;
    case TEXTURE_ADDRESS_MIRROR: return VK_SAMPLER_ADDRESS_MODE_MIRRORED_REPEAT;
    case TEXTURE_ADDRESS_CLAMP: return VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
    case TEXTURE_ADDRESS_BORDER: return VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_BORDER;
    // Mirror once about 0, then clamp: Vulkan's MIRROR_CLAMP_TO_EDGE.
    case TEXTURE_ADDRESS_MIRROR_ONCE: return VK_SAMPLER_ADDRESS_MODE_MIRROR_CLAMP_TO_EDGE;
  }
  return VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
}

}  // namespace rhi::states
