// D3D11 blend state: validation, canonical form, hashing, Vulkan translation.
#pragma once

#include <vulkan/vulkan_core.h>

#include <array>
#include <cstdint>
#include <string>

#include "rhi/d3d11_types.h"

namespace rhi::states {

// Empty when CreateBlendState accepts the desc, else the reason, e.g.
// "BLEND_DESC.RenderTarget[2].SrcBlend: 0 is not a valid D3D11_BLEND".
// Only RenderTarget[0] is checked when IndependentBlendEnable is FALSE (the
// others are ignored), and factors/ops only when BlendEnable is TRUE.
std::string Validate(const BLEND_DESC& desc);

// Canonical desc (what D3D11 GetDesc reports): IndependentBlendEnable FALSE
// copies RenderTarget[0] into all eight; BlendEnable FALSE resets factors/ops
// to ONE/ZERO/ADD; BOOLs become 0/1.
BLEND_DESC Normalize(const BLEND_DESC& desc);

// The desc as given, field by field.
bool RawEqual(const BLEND_DESC& a, const BLEND_DESC& b);
uint64_t RawHash(const BLEND_DESC& desc);
// The normalised desc: state-object cache and pipeline keys.
bool KeyEqual(const BLEND_DESC& a, const BLEND_DESC& b);
uint64_t KeyHash(const BLEND_DESC& desc);

struct BlendVk {
  std::array<VkPipelineColorBlendAttachmentState, SIMULTANEOUS_RENDER_TARGET_COUNT> attachments{};
  VkBool32 alphaToCoverageEnable = VK_FALSE;  // goes to VkPipelineMultisampleStateCreateInfo
  bool usesDualSource = false;        // SRC1 factors: needs the dualSrcBlend feature
  bool usesBlendConstants = false;    // BLEND_FACTOR factors: OMSetBlendState's factor via vkCmdSetBlendConstants
  bool needsIndependentBlend = false; // attachments differ: needs the independentBlend feature
};

// Translates the normalised desc. The backend must still apply
// AdjustForMissingAlpha to attachments whose format has FormatInfo::alphaIsOne.
BlendVk ToVulkan(const BLEND_DESC& desc);

// `alpha`: the factor is SrcBlendAlpha/DestBlendAlpha (BLEND_FACTOR then maps to CONSTANT_ALPHA).
VkBlendFactor ToVkBlendFactor(BLEND factor, bool alpha);
VkBlendOp ToVkBlendOp(BLEND_OP op);
VkColorComponentFlags ToVkColorWriteMask(UINT8 mask);

// For a render target whose D3D format has no alpha but whose Vulkan format
// stores one (B8G8R8X8 -> B8G8R8A8): D3D blends as if destination alpha were 1,
// so DEST_ALPHA -> ONE, INV_DEST_ALPHA -> ZERO, SRC_ALPHA_SAT (min(As, 1-Ad)) ->
// ZERO for colour, and alpha writes are masked so the hidden channel is untouched.
void AdjustForMissingAlpha(VkPipelineColorBlendAttachmentState& attachment);

// Empty when render target `slot` (of the D3D format named `formatName`) may
// be drawn with `attachment`; else why the draw is refused: blending is on and
// the device cannot blend the format (`formatBlends`: its Vulkan format has
// VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BLEND_BIT). Vulkan makes that optional
// (float32 formats lack it on some devices); D3D11's feature level 11 blends
// every float and UNORM target, so there is no D3D11 fallback to take.
std::string CheckBlendable(UINT slot, const char* formatName, const VkPipelineColorBlendAttachmentState& attachment,
                           bool formatBlends, const std::string& adapter);

// "D3D11_BLEND_SRC_COLOR", or nullptr for a value that is not a D3D11_BLEND.
const char* BlendName(BLEND factor);

}  // namespace rhi::states
