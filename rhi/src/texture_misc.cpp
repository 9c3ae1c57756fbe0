// Cube maps and mip generation: D3D11's rules for RESOURCE_MISC_TEXTURECUBE
// and RESOURCE_MISC_GENERATE_MIPS, and GenerateMips as a chain of linear blits
// (each level the 2x2 box filter of the one above, as D3D11's GenerateMips).
#include <string>

#include "context.h"
#include "resources.h"
#include "states/formats.h"
#include "views.h"

namespace rhi::vk {

std::string CheckMiscFlags(const TextureShape& s, const std::string& where) {
  if (s.miscFlags & RESOURCE_MISC_SHARED)
    return where + "RESOURCE_MISC_SHARED is not supported: no resource is shared across devices or processes";
  if (s.miscFlags & RESOURCE_MISC_TEXTURECUBE) {
    if (s.dimension != RESOURCE_DIMENSION_TEXTURE2D) return where + "RESOURCE_MISC_TEXTURECUBE needs a 2D texture";
    if (s.arraySize % 6 != 0)
      return where + "RESOURCE_MISC_TEXTURECUBE needs ArraySize a multiple of 6 (one per face), not " +
             std::to_string(s.arraySize);
    if (s.width != s.height)
      return where + "RESOURCE_MISC_TEXTURECUBE needs square faces; Width " + std::to_string(s.width) +
             " != Height " + std::to_string(s.height);
    if (s.samples > 1) return where + "RESOURCE_MISC_TEXTURECUBE cannot be multisampled";
  }
  if (s.miscFlags & RESOURCE_MISC_GENERATE_MIPS) {
    constexpr UINT kNeeded = BIND_SHADER_RESOURCE | BIND_RENDER_TARGET;
    if ((s.bindFlags & kNeeded) != kNeeded)
      return where + "RESOURCE_MISC_GENERATE_MIPS needs BIND_SHADER_RESOURCE and BIND_RENDER_TARGET";
  }
  return {};
}

std::string CheckMipGenerationFormat(const Gpu& gpu, const TextureShape& shape, VkFormat format, const char* call) {
  if (!(shape.miscFlags & RESOURCE_MISC_GENERATE_MIPS)) return {};
  constexpr VkFormatFeatureFlags2 kBlit = VK_FORMAT_FEATURE_2_BLIT_SRC_BIT | VK_FORMAT_FEATURE_2_BLIT_DST_BIT |
                                          VK_FORMAT_FEATURE_2_SAMPLED_IMAGE_FILTER_LINEAR_BIT;
  if (gpu.IsFormatSupported(format, kBlit)) return {};
  return std::string(call) + ": RESOURCE_MISC_GENERATE_MIPS: " + gpu.AdapterName() + " cannot filter " +
         states::FormatName(shape.format) + " (CheckFormatSupport lacks FORMAT_SUPPORT_MIP_AUTOGEN)";
}

void ContextImpl::GenerateMips(ShaderResourceView* pShaderResourceView) {
  if (predicationSkips_) return;
  auto* view = static_cast<ShaderResourceViewImpl*>(pShaderResourceView);
  TextureStorage* texture = view ? view->ViewTarget::texture() : nullptr;
  if (!texture || !(texture->shape().miscFlags & RESOURCE_MISC_GENERATE_MIPS)) {
    ReportDrawError("GenerateMips: the view's resource must be a texture created with RESOURCE_MISC_GENERATE_MIPS; "
                    "the call is ignored");
    return;
  }
  const VkImageSubresourceRange range = view->range();
  EndRendering();
  for (UINT level = range.baseMipLevel + 1; level < range.baseMipLevel + range.levelCount; ++level) {
    // The image stays in GENERAL: one tracked resource, read then written per level.
    Use(*texture, uses::kTransferRead);
    Use(*texture, uses::kTransferWrite);
    FlushBarriers();
    const VkExtent3D from = texture->MipExtent(level - 1), to = texture->MipExtent(level);
    VkImageBlit blit{};
    blit.srcSubresource = {range.aspectMask, level - 1, range.baseArrayLayer, range.layerCount};
    blit.srcOffsets[1] = {int32_t(from.width), int32_t(from.height), 1};
    blit.dstSubresource = {range.aspectMask, level, range.baseArrayLayer, range.layerCount};
    blit.dstOffsets[1] = {int32_t(to.width), int32_t(to.height), 1};
    vkCmdBlitImage(Commands(), texture->image(), VK_IMAGE_LAYOUT_GENERAL, texture->image(), VK_IMAGE_LAYOUT_GENERAL, 1,
                   &blit, VK_FILTER_LINEAR);
  }
}

}  // namespace rhi::vk
