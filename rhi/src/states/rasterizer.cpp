#include "states/rasterizer.h"

#include <cmath>

#include "states/util.h"

namespace rhi::states {
namespace {

std::string CheckFinite(const char* field, float v) {
  if (std::isfinite(v)) return {};
  return std::string("RASTERIZER_DESC.") + field + ": " + FloatText(v) + " is not a finite number";
}

}  // namespace

std::string Validate(const RASTERIZER_DESC& desc) {
  if (desc.FillMode != FILL_WIREFRAME && desc.FillMode != FILL_SOLID)
    return "RASTERIZER_DESC.FillMode: " + std::to_string(desc.FillMode) + " is not a valid D3D11_FILL_MODE";
  if (desc.CullMode < CULL_NONE || desc.CullMode > CULL_BACK)
    return "RASTERIZER_DESC.CullMode: " + std::to_string(desc.CullMode) + " is not a valid D3D11_CULL_MODE";
  // Judgement: the runtime's exact float checks are undocumented; a NaN or
  // infinite bias cannot mean anything, and Vulkan's bias math would spread it.
  if (std::string error = CheckFinite("DepthBiasClamp", desc.DepthBiasClamp); !error.empty()) return error;
  return CheckFinite("SlopeScaledDepthBias", desc.SlopeScaledDepthBias);
}

RASTERIZER_DESC Normalize(const RASTERIZER_DESC& desc) {
  RASTERIZER_DESC out = desc;
  out.FrontCounterClockwise = CanonicalBool(desc.FrontCounterClockwise);
  out.DepthClipEnable = CanonicalBool(desc.DepthClipEnable);
  out.ScissorEnable = CanonicalBool(desc.ScissorEnable);
  out.MultisampleEnable = CanonicalBool(desc.MultisampleEnable);
  out.AntialiasedLineEnable = CanonicalBool(desc.AntialiasedLineEnable);
  return out;
}

bool RawEqual(const RASTERIZER_DESC& a, const RASTERIZER_DESC& b) {
  return a.FillMode == b.FillMode && a.CullMode == b.CullMode && a.FrontCounterClockwise == b.FrontCounterClockwise &&
         a.DepthBias == b.DepthBias && SameBits(a.DepthBiasClamp, b.DepthBiasClamp) &&
         SameBits(a.SlopeScaledDepthBias, b.SlopeScaledDepthBias) && a.DepthClipEnable == b.DepthClipEnable &&
         a.ScissorEnable == b.ScissorEnable && a.MultisampleEnable == b.MultisampleEnable &&
         a.AntialiasedLineEnable == b.AntialiasedLineEnable;
}

uint64_t RawHash(const RASTERIZER_DESC& desc) {
  Fnv1a h;
  h.Add(desc.FillMode);
  h.Add(desc.CullMode);
  h.Add(desc.FrontCounterClockwise);
  h.Add(desc.DepthBias);
  h.Add(desc.DepthBiasClamp);
  h.Add(desc.SlopeScaledDepthBias);
  h.Add(desc.DepthClipEnable);
  h.Add(desc.ScissorEnable);
  h.Add(desc.MultisampleEnable);
  h.Add(desc.AntialiasedLineEnable);
  return h.value();
}

bool KeyEqual(const RASTERIZER_DESC& a, const RASTERIZER_DESC& b) { return RawEqual(Normalize(a), Normalize(b)); }
uint64_t KeyHash(const RASTERIZER_DESC& desc) { return RawHash(Normalize(desc)); }

RasterizerVk ToVulkan(const RASTERIZER_DESC& desc, bool hasDepthClipEnableExt) {
  RasterizerVk out;
  VkPipelineRasterizationStateCreateInfo& info = out.info;
  info.sType = VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO;
  info.polygonMode = ToVkPolygonMode(desc.FillMode);
  info.cullMode = ToVkCullMode(desc.CullMode);
  info.frontFace = ToVkFrontFace(desc.FrontCounterClockwise);
  info.rasterizerDiscardEnable = VK_FALSE;  // D3D11 discards via SO_NO_RASTERIZED_STREAM, not here
  info.lineWidth = 1.0f;                    // D3D11 lines are always one pixel wide

  // Bias parameters that are all zero are the same as no bias (DXVK does the same;
  // apps leave garbage in DepthBiasClamp).
  info.depthBiasEnable = (desc.DepthBias != 0 || desc.SlopeScaledDepthBias != 0.0f) ? VK_TRUE : VK_FALSE;
  if (info.depthBiasEnable) {
    info.depthBiasConstantFactor = static_cast<float>(desc.DepthBias);
    info.depthBiasClamp = desc.DepthBiasClamp;
    info.depthBiasSlopeFactor = desc.SlopeScaledDepthBias;
    out.needsDepthBiasClamp = desc.DepthBiasClamp != 0.0f;
  }

  out.usesDepthClipExt = hasDepthClipEnableExt;
  if (hasDepthClipEnableExt) {
    info.depthClampEnable = VK_TRUE;
    out.depthClip.sType = VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_DEPTH_CLIP_STATE_CREATE_INFO_EXT;
    out.depthClip.depthClipEnable = desc.DepthClipEnable ? VK_TRUE : VK_FALSE;
  } else {
    info.depthClampEnable = desc.DepthClipEnable ? VK_FALSE : VK_TRUE;
  }
  out.needsDepthClampFeature = info.depthClampEnable == VK_TRUE;

  out.line.sType = VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_LINE_STATE_CREATE_INFO_EXT;
  out.line.lineRasterizationMode = ToVkLineMode(desc);
  out.line.stippledLineEnable = VK_FALSE;

  out.scissorEnable = desc.ScissorEnable != FALSE;
  out.needsFillModeNonSolid = info.polygonMode != VK_POLYGON_MODE_FILL;
  return out;
}

VkPolygonMode ToVkPolygonMode(FILL_MODE mode) {
  return mode == FILL_WIREFRAME ? VK_POLYGON_MODE_LINE : VK_POLYGON_MODE_FILL;
}

VkCullModeFlags ToVkCullMode(CULL_MODE mode) {
  switch (mode) {
    case CULL_NONE: return VK_CULL_MODE_NONE;
    case CULL_FRONT: return VK_CULL_MODE_FRONT_BIT;
    case CULL_BACK: return VK_CULL_MODE_BACK_BIT;
  }
  return VK_CULL_MODE_NONE;
}

VkFrontFace ToVkFrontFace(BOOL frontCounterClockwise) {
  // See rasterizer.h: with the negative-height viewport the framebuffer winding
  // equals D3D's render-target winding, so no swap.
  return frontCounterClockwise ? VK_FRONT_FACE_COUNTER_CLOCKWISE : VK_FRONT_FACE_CLOCKWISE;
}

VkLineRasterizationModeEXT ToVkLineMode(const RASTERIZER_DESC& desc) {
  if (desc.MultisampleEnable) return VK_LINE_RASTERIZATION_MODE_RECTANGULAR_EXT;
  if (desc.AntialiasedLineEnable) return VK_LINE_RASTERIZATION_MODE_RECTANGULAR_SMOOTH_EXT;
  return VK_LINE_RASTERIZATION_MODE_BRESENHAM_EXT;
}

}  // namespace rhi::states
