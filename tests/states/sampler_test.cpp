#include "states/sampler.h"

#include <gtest/gtest.h>

#include <limits>

namespace rhi::states {
namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

SAMPLER_DESC Border(float r, float g, float b, float a) {
  SAMPLER_DESC d;
  d.AddressU = TEXTURE_ADDRESS_BORDER;
  d.BorderColor[0] = r;
  d.BorderColor[1] = g;
  d.BorderColor[2] = b;
  d.BorderColor[3] = a;
  return d;
}

TEST(SamplerValidate, DefaultDescIsValid) { EXPECT_EQ(Validate(SAMPLER_DESC{}), ""); }

TEST(SamplerValidate, FilterMustBeADefinedValue) {
  SAMPLER_DESC d;
  d.Filter = static_cast<FILTER>(0x2);
  EXPECT_EQ(Validate(d), "SAMPLER_DESC.Filter: 0x2 is not a valid D3D11_FILTER");
  d.Filter = static_cast<FILTER>(0x45);  // anisotropic bit with a non-linear combination
  EXPECT_EQ(Validate(d), "SAMPLER_DESC.Filter: 0x45 is not a valid D3D11_FILTER");
  d.Filter = static_cast<FILTER>(0x100);  // MINIMUM_* reductions are not in d3d11_types.h
  EXPECT_EQ(Validate(d), "SAMPLER_DESC.Filter: 0x100 is not a valid D3D11_FILTER");
}

TEST(SamplerValidate, AddressModesOneToFive) {
  SAMPLER_DESC d;
  d.AddressU = static_cast<TEXTURE_ADDRESS_MODE>(0);
  EXPECT_EQ(Validate(d), "SAMPLER_DESC.AddressU: 0 is not a valid D3D11_TEXTURE_ADDRESS_MODE");
  d.AddressU = TEXTURE_ADDRESS_MIRROR_ONCE;
  d.AddressV = static_cast<TEXTURE_ADDRESS_MODE>(6);
  EXPECT_EQ(Validate(d), "SAMPLER_DESC.AddressV: 6 is not a valid D3D11_TEXTURE_ADDRESS_MODE");
  d.AddressV = TEXTURE_ADDRESS_WRAP;
  d.AddressW = static_cast<TEXTURE_ADDRESS_MODE>(0);
  EXPECT_EQ(Validate(d), "SAMPLER_DESC.AddressW: 0 is not a valid D3D11_TEXTURE_ADDRESS_MODE");
}

TEST(SamplerValidate, MaxAnisotropy) {
  SAMPLER_DESC d;
  d.MaxAnisotropy = 0;  // ignored by a linear filter
  EXPECT_EQ(Validate(d), "");
  d.MaxAnisotropy = 17;
  EXPECT_EQ(Validate(d), "SAMPLER_DESC.MaxAnisotropy: 17 exceeds D3D11_REQ_MAXANISOTROPY (16)");
  d.Filter = FILTER_ANISOTROPIC;
  EXPECT_EQ(Validate(d), "SAMPLER_DESC.MaxAnisotropy: 17 exceeds D3D11_REQ_MAXANISOTROPY (16)");
  d.MaxAnisotropy = 0;
  EXPECT_EQ(Validate(d), "SAMPLER_DESC.MaxAnisotropy: 0 is invalid for an anisotropic filter (valid: 1..16)");
  d.MaxAnisotropy = 16;
  EXPECT_EQ(Validate(d), "");
  d.Filter = FILTER_COMPARISON_ANISOTROPIC;
  d.ComparisonFunc = COMPARISON_LESS;
  d.MaxAnisotropy = 0;
  EXPECT_EQ(Validate(d), "SAMPLER_DESC.MaxAnisotropy: 0 is invalid for an anisotropic filter (valid: 1..16)");
}

TEST(SamplerValidate, ComparisonFuncOnlyForComparisonFilters) {
  SAMPLER_DESC d;
  d.ComparisonFunc = static_cast<COMPARISON_FUNC>(0);
  EXPECT_EQ(Validate(d), "");
  d.Filter = FILTER_COMPARISON_MIN_MAG_LINEAR_MIP_POINT;
  EXPECT_EQ(Validate(d), "SAMPLER_DESC.ComparisonFunc: 0 is not a valid D3D11_COMPARISON_FUNC");
  d.ComparisonFunc = static_cast<COMPARISON_FUNC>(9);
  EXPECT_EQ(Validate(d), "SAMPLER_DESC.ComparisonFunc: 9 is not a valid D3D11_COMPARISON_FUNC");
  d.ComparisonFunc = COMPARISON_LESS_EQUAL;
  EXPECT_EQ(Validate(d), "");
}

TEST(SamplerValidate, MipLodBiasRange) {
  SAMPLER_DESC d;
  d.MipLODBias = -16.0f;
  EXPECT_EQ(Validate(d), "");
  d.MipLODBias = 15.99f;
  EXPECT_EQ(Validate(d), "");
  d.MipLODBias = 16.0f;
  EXPECT_EQ(Validate(d), "SAMPLER_DESC.MipLODBias: 16 is outside [-16, 15.99]");
  d.MipLODBias = -16.5f;
  EXPECT_EQ(Validate(d), "SAMPLER_DESC.MipLODBias: -16.5 is outside [-16, 15.99]");
  d.MipLODBias = kNaN;
  EXPECT_EQ(Validate(d), "SAMPLER_DESC.MipLODBias: NaN is not allowed");
}

TEST(SamplerValidate, NoNaN) {
  SAMPLER_DESC d;
  d.BorderColor[2] = kNaN;
  EXPECT_EQ(Validate(d), "SAMPLER_DESC.BorderColor[2]: NaN is not allowed");
  d = SAMPLER_DESC{};
  d.MinLOD = kNaN;
  EXPECT_EQ(Validate(d), "SAMPLER_DESC.MinLOD: NaN is not allowed");
  d = SAMPLER_DESC{};
  d.MaxLOD = kNaN;
  EXPECT_EQ(Validate(d), "SAMPLER_DESC.MaxLOD: NaN is not allowed");
}

TEST(SamplerValidate, AnyBorderColourAndInvertedLodRangeAreAccepted) {
  EXPECT_EQ(Validate(Border(2.0f, -1.0f, 0.5f, 7.0f)), "");
  SAMPLER_DESC d;
  d.MinLOD = 5.0f;
  d.MaxLOD = 2.0f;
  EXPECT_EQ(Validate(d), "");
}

TEST(SamplerNormalize, UnusedFieldsReset) {
  SAMPLER_DESC d;
  d.MaxAnisotropy = 8;
  d.ComparisonFunc = COMPARISON_GREATER;
  d.BorderColor[0] = 0.5f;
  const SAMPLER_DESC n = Normalize(d);
  EXPECT_EQ(n.MaxAnisotropy, 0u);
  EXPECT_EQ(n.ComparisonFunc, COMPARISON_NEVER);
  for (float c : n.BorderColor) EXPECT_EQ(c, 0.0f);
}

TEST(SamplerNormalize, UsedFieldsKept) {
  SAMPLER_DESC d = Border(0.25f, 0.5f, 0.75f, 1.0f);
  d.Filter = FILTER_COMPARISON_ANISOTROPIC;
  d.MaxAnisotropy = 8;
  d.ComparisonFunc = COMPARISON_GREATER;
  const SAMPLER_DESC n = Normalize(d);
  EXPECT_EQ(n.MaxAnisotropy, 8u);
  EXPECT_EQ(n.ComparisonFunc, COMPARISON_GREATER);
  EXPECT_EQ(n.BorderColor[2], 0.75f);
}

TEST(SamplerHash, EquivalentAndDifferentDescs) {
  SAMPLER_DESC a;
  SAMPLER_DESC b;
  b.MaxAnisotropy = 4;  // not anisotropic: ignored
  b.BorderColor[1] = 0.3f;  // no BORDER address: ignored
  EXPECT_TRUE(KeyEqual(a, b));
  EXPECT_EQ(KeyHash(a), KeyHash(b));
  EXPECT_FALSE(RawEqual(a, b));
  EXPECT_NE(RawHash(a), RawHash(b));

  SAMPLER_DESC c;
  c.AddressW = TEXTURE_ADDRESS_WRAP;
  EXPECT_NE(KeyHash(a), KeyHash(c));
  SAMPLER_DESC e = Border(1, 0, 0, 1);
  SAMPLER_DESC f = Border(1, 0, 0, 0.5f);
  EXPECT_NE(KeyHash(e), KeyHash(f));
  SAMPLER_DESC g;
  g.MinLOD = 1.0f;
  EXPECT_NE(KeyHash(a), KeyHash(g));
}

TEST(SamplerHash, NaNDescsAreRawEqualToThemselves) {
  SAMPLER_DESC a;
  a.MipLODBias = kNaN;
  EXPECT_TRUE(RawEqual(a, a));
  EXPECT_EQ(RawHash(a), RawHash(SAMPLER_DESC(a)));
}

struct FilterCase {
  FILTER filter;
  VkFilter min, mag;
  VkSamplerMipmapMode mip;
  bool anisotropic, comparison;
};

TEST(SamplerToVulkan, EveryFilter) {
  constexpr VkFilter P = VK_FILTER_NEAREST, L = VK_FILTER_LINEAR;
  constexpr VkSamplerMipmapMode MP = VK_SAMPLER_MIPMAP_MODE_NEAREST, ML = VK_SAMPLER_MIPMAP_MODE_LINEAR;
  const FilterCase cases[] = {
      {FILTER_MIN_MAG_MIP_POINT, P, P, MP, false, false},
      {FILTER_MIN_MAG_POINT_MIP_LINEAR, P, P, ML, false, false},
      {FILTER_MIN_POINT_MAG_LINEAR_MIP_POINT, P, L, MP, false, false},
      {FILTER_MIN_POINT_MAG_MIP_LINEAR, P, L, ML, false, false},
      {FILTER_MIN_LINEAR_MAG_MIP_POINT, L, P, MP, false, false},
      {FILTER_MIN_LINEAR_MAG_POINT_MIP_LINEAR, L, P, ML, false, false},
      {FILTER_MIN_MAG_LINEAR_MIP_POINT, L, L, MP, false, false},
      {FILTER_MIN_MAG_MIP_LINEAR, L, L, ML, false, false},
      {FILTER_ANISOTROPIC, L, L, ML, true, false},
      {FILTER_COMPARISON_MIN_MAG_MIP_POINT, P, P, MP, false, true},
      {FILTER_COMPARISON_MIN_MAG_POINT_MIP_LINEAR, P, P, ML, false, true},
      {FILTER_COMPARISON_MIN_POINT_MAG_LINEAR_MIP_POINT, P, L, MP, false, true},
      {FILTER_COMPARISON_MIN_POINT_MAG_MIP_LINEAR, P, L, ML, false, true},
      {FILTER_COMPARISON_MIN_LINEAR_MAG_MIP_POINT, L, P, MP, false, true},
      {FILTER_COMPARISON_MIN_LINEAR_MAG_POINT_MIP_LINEAR, L, P, ML, false, true},
      {FILTER_COMPARISON_MIN_MAG_LINEAR_MIP_POINT, L, L, MP, false, true},
      {FILTER_COMPARISON_MIN_MAG_MIP_LINEAR, L, L, ML, false, true},
      {FILTER_COMPARISON_ANISOTROPIC, L, L, ML, true, true},
  };
  for (const FilterCase& c : cases) {
    SAMPLER_DESC d;
    d.Filter = c.filter;
    d.MaxAnisotropy = 4;
    d.ComparisonFunc = COMPARISON_LESS;
    ASSERT_EQ(Validate(d), "") << c.filter;
    const SamplerVk vk = ToVulkan(d);
    EXPECT_EQ(vk.info.minFilter, c.min) << c.filter;
    EXPECT_EQ(vk.info.magFilter, c.mag) << c.filter;
    EXPECT_EQ(vk.info.mipmapMode, c.mip) << c.filter;
    EXPECT_EQ(vk.info.anisotropyEnable, c.anisotropic ? VK_TRUE : VK_FALSE) << c.filter;
    EXPECT_EQ(vk.info.maxAnisotropy, c.anisotropic ? 4.0f : 1.0f) << c.filter;
    EXPECT_EQ(vk.needsAnisotropy, c.anisotropic) << c.filter;
    EXPECT_EQ(vk.info.compareEnable, c.comparison ? VK_TRUE : VK_FALSE) << c.filter;
    EXPECT_EQ(vk.info.compareOp, c.comparison ? VK_COMPARE_OP_LESS : VK_COMPARE_OP_NEVER) << c.filter;
  }
}

TEST(SamplerToVulkan, AnisotropyClampedToDeviceLimit) {
  SAMPLER_DESC d;
  d.Filter = FILTER_ANISOTROPIC;
  d.MaxAnisotropy = 16;
  EXPECT_EQ(ToVulkan(d, {8.0f, 15.99f}).info.maxAnisotropy, 8.0f);
  EXPECT_EQ(ToVulkan(d).info.maxAnisotropy, 16.0f);
}

TEST(SamplerToVulkan, AddressModes) {
  EXPECT_EQ(ToVkAddressMode(TEXTURE_ADDRESS_WRAP), VK_SAMPLER_ADDRESS_MODE_REPEAT);
  EXPECT_EQ(ToVkAddressMode(TEXTURE_ADDRESS_MIRROR), VK_SAMPLER_ADDRESS_MODE_MIRRORED_REPEAT);
  EXPECT_EQ(ToVkAddressMode(TEXTURE_ADDRESS_CLAMP), VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE);
  EXPECT_EQ(ToVkAddressMode(TEXTURE_ADDRESS_BORDER), VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_BORDER);
  EXPECT_EQ(ToVkAddressMode(TEXTURE_ADDRESS_MIRROR_ONCE), VK_SAMPLER_ADDRESS_MODE_MIRROR_CLAMP_TO_EDGE);
  SAMPLER_DESC d;
  d.AddressV = TEXTURE_ADDRESS_MIRROR_ONCE;
  const SamplerVk vk = ToVulkan(d);
  EXPECT_TRUE(vk.needsMirrorClampToEdge);
  EXPECT_EQ(vk.info.addressModeU, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE);
  EXPECT_EQ(vk.info.addressModeV, VK_SAMPLER_ADDRESS_MODE_MIRROR_CLAMP_TO_EDGE);
  EXPECT_FALSE(ToVulkan(SAMPLER_DESC{}).needsMirrorClampToEdge);
}

TEST(SamplerToVulkan, BorderColourChoice) {
  SamplerVk vk = ToVulkan(Border(0, 0, 0, 0));
  EXPECT_EQ(vk.info.borderColor, VK_BORDER_COLOR_FLOAT_TRANSPARENT_BLACK);
  EXPECT_FALSE(vk.needsCustomBorderColor);
  EXPECT_EQ(ToVulkan(Border(0, 0, 0, 1)).info.borderColor, VK_BORDER_COLOR_FLOAT_OPAQUE_BLACK);
  EXPECT_EQ(ToVulkan(Border(1, 1, 1, 1)).info.borderColor, VK_BORDER_COLOR_FLOAT_OPAQUE_WHITE);

  vk = ToVulkan(Border(1.0f, 0.5f, 0.25f, 1.0f));
  EXPECT_EQ(vk.info.borderColor, VK_BORDER_COLOR_FLOAT_CUSTOM_EXT);
  EXPECT_TRUE(vk.needsCustomBorderColor);
  EXPECT_EQ(vk.info.pNext, nullptr);
  EXPECT_EQ(vk.customBorder.sType, VK_STRUCTURE_TYPE_SAMPLER_CUSTOM_BORDER_COLOR_CREATE_INFO_EXT);
  EXPECT_EQ(vk.customBorder.customBorderColor.float32[0], 1.0f);
  EXPECT_EQ(vk.customBorder.customBorderColor.float32[1], 0.5f);
  EXPECT_EQ(vk.customBorder.customBorderColor.float32[2], 0.25f);
  EXPECT_EQ(vk.customBorder.customBorderColor.float32[3], 1.0f);
  EXPECT_EQ(vk.customBorder.format, VK_FORMAT_UNDEFINED);

  // The default D3D border colour is opaque white, so a BORDER sampler with
  // default colour needs no extension.
  SAMPLER_DESC d;
  d.AddressW = TEXTURE_ADDRESS_BORDER;
  EXPECT_EQ(ToVulkan(d).info.borderColor, VK_BORDER_COLOR_FLOAT_OPAQUE_WHITE);
}

TEST(SamplerToVulkan, BorderColourIgnoredWithoutBorderAddressing) {
  SAMPLER_DESC d = Border(0.3f, 0.3f, 0.3f, 0.3f);
  d.AddressU = TEXTURE_ADDRESS_CLAMP;
  const SamplerVk vk = ToVulkan(d);
  EXPECT_EQ(vk.info.borderColor, VK_BORDER_COLOR_FLOAT_TRANSPARENT_BLACK);
  EXPECT_FALSE(vk.needsCustomBorderColor);
}

TEST(SamplerToVulkan, LodClamp) {
  SamplerVk vk = ToVulkan(SAMPLER_DESC{});  // MinLOD -FLOAT32_MAX, MaxLOD FLOAT32_MAX
  EXPECT_EQ(vk.info.minLod, 0.0f);
  EXPECT_EQ(vk.info.maxLod, VK_LOD_CLAMP_NONE);

  SAMPLER_DESC d;
  d.MinLOD = 2.0f;
  d.MaxLOD = 5.5f;
  vk = ToVulkan(d);
  EXPECT_EQ(vk.info.minLod, 2.0f);
  EXPECT_EQ(vk.info.maxLod, 5.5f);

  d.MinLOD = 5.0f;  // inverted range: MinLOD wins, as D3D's clamp order gives
  d.MaxLOD = 2.0f;
  vk = ToVulkan(d);
  EXPECT_EQ(vk.info.minLod, 5.0f);
  EXPECT_EQ(vk.info.maxLod, 5.0f);

  d.MinLOD = FLOAT32_MAX;
  d.MaxLOD = FLOAT32_MAX;
  vk = ToVulkan(d);
  EXPECT_EQ(vk.info.minLod, VK_LOD_CLAMP_NONE);
  EXPECT_EQ(vk.info.maxLod, VK_LOD_CLAMP_NONE);
}

TEST(SamplerToVulkan, MipLodBias) {
  SAMPLER_DESC d;
  d.MipLODBias = -3.5f;
  EXPECT_EQ(ToVulkan(d).info.mipLodBias, -3.5f);
  d.MipLODBias = 15.0f;
  EXPECT_EQ(ToVulkan(d, {16.0f, 4.0f}).info.mipLodBias, 4.0f);
}

}  // namespace
}  // namespace rhi::states
