// D3D11 depth-stencil state: validation, canonical form, hashing, Vulkan translation.
#pragma once

#include <vulkan/vulkan_core.h>

#include <cstdint>
#include <string>

#include "rhi/d3d11_types.h"

namespace rhi::states {

// Empty when CreateDepthStencilState accepts the desc, else the reason, e.g.
// "DEPTH_STENCIL_DESC.FrontFace.StencilPassOp: 9 is not a valid D3D11_STENCIL_OP".
// DepthWriteMask/DepthFunc are checked only when DepthEnable, the stencil
// fields only when StencilEnable (the runtime resets them otherwise).
std::string Validate(const DEPTH_STENCIL_DESC& desc);

// Canonical desc (what D3D11 GetDesc reports): DepthEnable FALSE -> DepthWriteMask
// ALL, DepthFunc LESS; StencilEnable FALSE -> masks 0xFF, both faces
// KEEP/KEEP/KEEP/ALWAYS; BOOLs become 0/1.
DEPTH_STENCIL_DESC Normalize(const DEPTH_STENCIL_DESC& desc);

bool RawEqual(const DEPTH_STENCIL_DESC& a, const DEPTH_STENCIL_DESC& b);
uint64_t RawHash(const DEPTH_STENCIL_DESC& desc);
bool KeyEqual(const DEPTH_STENCIL_DESC& a, const DEPTH_STENCIL_DESC& b);
uint64_t KeyHash(const DEPTH_STENCIL_DESC& desc);

// The normalised desc as Vulkan state. The stencil reference is 0 here: it is
// OMSetDepthStencilState's StencilRef, set with vkCmdSetStencilReference
// (VK_DYNAMIC_STATE_STENCIL_REFERENCE). Compare/write masks are static.
// Front/back follow the rasterizer's facing, as in D3D11 (lines and points
// are front-facing in both APIs). A read-only DSV must additionally clear
// depthWriteEnable / the stencil write masks; that is the backend's job.
VkPipelineDepthStencilStateCreateInfo ToVulkan(const DEPTH_STENCIL_DESC& desc);

VkCompareOp ToVkCompareOp(COMPARISON_FUNC func);
VkStencilOp ToVkStencilOp(STENCIL_OP op);

// "D3D11_COMPARISON_LESS", or nullptr for an invalid value.
const char* ComparisonName(COMPARISON_FUNC func);

}  // namespace rhi::states
