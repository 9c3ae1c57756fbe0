// Cube maps, mip generation and per-resource LOD clamps: D3D11's rules for
// RESOURCE_MISC_TEXTURECUBE, RESOURCE_MISC_GENERATE_MIPS and RESOURCE_MISC_RESOURCE_CLAMP,
// GenerateMips as a chain of linear blits (each level the 2x2 box filter of the
// one above, 2x2x2 for 3D textures, as D3D11's GenerateMips), and SetResourceMinLOD.
#include <sstream>
#include <string>

#include "context.h"
#include "resources.h"
#include "states/formats.h"
#include "views.h"

namespace rhi::vk {

std::string CheckMiscFlags(const TextureShape& s, const std::string& where) {
  constexpr UINT kBufferOnly =
      RESOURCE_MISC_DRAWINDIRECT_ARGS | RESOURCE_MISC_BUFFER_ALLOW_RAW_VIEWS | RESOURCE_MISC_BUFFER_STRUCTURED;
  if (s.miscFlags & kBufferOnly)
    return where + "MiscFlags 0x" + (std::stringstream() << std::hex << s.miscFlags).str() +
           " has buffer-only flags (DRAWINDIRECT_ARGS, BUFFER_ALLOW_RAW_VIEWS, BUFFER_STRUCTURED)";
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
    blit.srcOffsets[1] = {int32_t(from.width), int32_t(from.height), int32_t(from.depth)};
    blit.dstSubresource = {range.aspectMask, level, range.baseArrayLayer, range.layerCount};
    blit.dstOffsets[1] = {int32_t(to.width), int32_t(to.height), int32_t(to.depth)};
    vkCmdBlitImage(Commands(), texture->image(), VK_IMAGE_LAYOUT_GENERAL, texture->image(), VK_IMAGE_LAYOUT_GENERAL, 1,
                   &blit, VK_FILTER_LINEAR);
  }
}

void ContextImpl::SetResourceMinLOD(Resource* pResource, FLOAT MinLOD) {
  TextureStorage* texture = AsTexture(pResource);
  std::string reason;
  if (!texture)
    reason = "pResource must be a texture";
  else if (!(texture->shape().miscFlags & RESOURCE_MISC_RESOURCE_CLAMP))
    reason = "the texture was not created with RESOURCE_MISC_RESOURCE_CLAMP";
  else if (!(MinLOD >= 0.0f && MinLOD <= FLOAT(texture->shape().mipLevels)))  // NaN fails too
    reason = "MinLOD " + std::to_string(MinLOD) + " lies outside 0.." + std::to_string(texture->shape().mipLevels) +
             " (the texture's MipLevels)";
  if (!reason.empty()) {
    ReportDrawError("SetResourceMinLOD: " + reason + "; the call is ignored");
    return;
  }
  texture->SetMinLod(MinLOD);
  // Bound shader-resource views now describe other image views (ViewTarget::SampledImageView).
  descriptorsDirty_ = true;
}

FLOAT ContextImpl::GetResourceMinLOD(Resource* pResource) {
  const TextureStorage* texture = AsTexture(pResource);
  return texture ? texture->minLod() : 0.0f;
}

}  // namespace rhi::vk
