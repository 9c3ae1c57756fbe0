// D3D11 rasterizer state: validation, canonical form, hashing, Vulkan translation.
#pragma once

#include <vulkan/vulkan_core.h>

#include <cstdint>
#include <string>

#include "rhi/d3d11_types.h"

namespace rhi::states {

// Empty when CreateRasterizerState accepts the desc, else the reason, e.g.
// "RASTERIZER_DESC.CullMode: 0 is not a valid D3D11_CULL_MODE".
std::string Validate(const RASTERIZER_DESC& desc);

// Canonical desc: BOOLs become 0/1. Nothing else is reset, because D3D11 keeps
// every rasterizer field (GetDesc returns them as given).
RASTERIZER_DESC Normalize(const RASTERIZER_DESC& desc);

bool RawEqual(const RASTERIZER_DESC& a, const RASTERIZER_DESC& b);
uint64_t RawHash(const RASTERIZER_DESC& desc);
bool KeyEqual(const RASTERIZER_DESC& a, const RASTERIZER_DESC& b);
uint64_t KeyHash(const RASTERIZER_DESC& desc);

struct RasterizerVk {
  // pNext is null: chain `depthClip` when usesDepthClipExt and `line` when the
  // device has VK_EXT_line_rasterization. These are not pre-chained so the
  // struct can be copied safely.
  VkPipelineRasterizationStateCreateInfo info{};
  VkPipelineRasterizationDepthClipStateCreateInfoEXT depthClip{};
  VkPipelineRasterizationLineStateCreateInfoEXT line{};
  bool usesDepthClipExt = false;        // depthClip must be chained
  bool scissorEnable = false;           // false: the backend sets the scissor to the whole render target
  bool needsDepthClampFeature = false;  // info.depthClampEnable is set
  bool needsFillModeNonSolid = false;   // FILL_WIREFRAME
  bool needsDepthBiasClamp = false;     // non-zero DepthBiasClamp with bias enabled
};

// `hasDepthClipEnableExt`: VK_EXT_depth_clip_enable (depthClipEnable feature) is on.
//
// Front face. D3D11 FrontCounterClockwise = FALSE means a triangle whose vertices
// are clockwise in render-target space (x right, y down) is front-facing. Vulkan
// decides facing from the sign of the triangle's area in framebuffer space, which
// is also x right, y down, and VK_FRONT_FACE_CLOCKWISE names the same on-screen
// winding. The backend flips the viewport (y = TopLeftY + Height, height =
// -Height), which maps D3D's NDC (+y up) to exactly the framebuffer position D3D
// rasterises to, so the winding seen by Vulkan's facing test is D3D's winding:
// FALSE -> VK_FRONT_FACE_CLOCKWISE, TRUE -> VK_FRONT_FACE_COUNTER_CLOCKWISE. No
// swap (a swap would only be needed if the image were rendered upside down).
//
// Depth clip. D3D10+ always clamps depth to the viewport's [MinDepth, MaxDepth]
// (also for SV_Depth) and DepthClipEnable only toggles clipping against z. With
// VK_EXT_depth_clip_enable that is depthClampEnable = TRUE plus depthClipEnable =
// DepthClipEnable; without it, depthClampEnable = !DepthClipEnable (a shader-written
// depth outside the viewport range is then not clamped while clipping is on).
//
// Lines (D3D11_RASTERIZER_DESC remarks): MultisampleEnable TRUE -> quadrilateral
// (RECTANGULAR); FALSE with AntialiasedLineEnable -> alpha antialiased
// (RECTANGULAR_SMOOTH); both FALSE -> aliased (BRESENHAM). Each mode needs its
// VkPhysicalDeviceLineRasterizationFeaturesEXT bit (rectangularLines /
// smoothLines / bresenhamLines); without it leave `line` unchained (DEFAULT).
RasterizerVk ToVulkan(const RASTERIZER_DESC& desc, bool hasDepthClipEnableExt);

VkPolygonMode ToVkPolygonMode(FILL_MODE mode);
VkCullModeFlags ToVkCullMode(CULL_MODE mode);
VkFrontFace ToVkFrontFace(BOOL frontCounterClockwise);
VkLineRasterizationModeEXT ToVkLineMode(const RASTERIZER_DESC& desc);

}  // namespace rhi::states
