// DXGI_FORMAT -> Vulkan format table for every format in d3d11_types.h.
#pragma once

#include <vulkan/vulkan_core.h>

#include <cstdint>
#include <functional>
#include <span>

#include "rhi/d3d11_types.h"

namespace rhi::states {

enum class ComponentKind : uint8_t { Typeless, Unorm, Snorm, Float, Uint, Sint, Depth };

// How sampled (SRV) image views must swizzle to read like D3D.
enum class ViewSwizzle : uint8_t {
  Identity,
  AlphaOne,      // B8G8R8X8*: stored as B8G8R8A8, the X byte is hidden, reads give A = 1
  AlphaFromRed,  // A8_UNORM: stored as R8_UNORM (no VK_FORMAT_A8_UNORM_KHR here), reads give (0, 0, 0, R)
  StencilInGreen,  // X24_TYPELESS_G8_UINT: Vulkan reads stencil in R, D3D11 in G; reads give (0, S, 0, 1)
};

struct FormatInfo {
  DXGI_FORMAT format;
  const char* name;         // "DXGI_FORMAT_R8G8B8A8_UNORM"
  // The Vulkan format of images and views of this format. Typeless formats get a
  // typed member of the same compatibility class (create the image with
  // VK_IMAGE_CREATE_MUTABLE_FORMAT_BIT); formats of the R24G8 family get the
  // preferred depth format (see PickDepthFormat for the fallback).
  VkFormat vkFormat;
  uint8_t bytesPerElement;  // bytes per texel / vertex element; per 4x4 block of a block-compressed format
  uint8_t componentCount;   // X channels are not counted (B8G8R8X8 has 3)
  ComponentKind kind;
  bool hasAlpha;            // the D3D format has a real alpha channel
  // The D3D format has no alpha but vkFormat stores one (B8G8R8X8*). The backend
  // must: swizzle SRV views (ViewSwizzle::AlphaOne), call
  // states::AdjustForMissingAlpha on the render target's blend attachment
  // (dest alpha reads as 1, alpha writes masked), and never rely on the stored
  // alpha (uploads may put garbage there).
  bool alphaIsOne;
  bool isSrgb;
  bool isDepth;             // has (or views) a depth aspect
  bool hasStencil;          // has (or views) a stencil aspect; a view format with it and no depth reads stencil
  // BIND_* flags D3D11 feature level 11_0 requires for this format: VERTEX_BUFFER
  // (usable in an input layout), INDEX_BUFFER, SHADER_RESOURCE, RENDER_TARGET,
  // DEPTH_STENCIL, UNORDERED_ACCESS. A8_UNORM as a render target needs the pixel
  // shader's alpha routed to .r (no swizzle is allowed on attachments).
  UINT bindFlags;
  // The typeless format whose views this format may be (itself for typeless
  // formats), DXGI_FORMAT_UNKNOWN for formats without a family (R11G11B10_FLOAT,
  // A8_UNORM).
  DXGI_FORMAT family;
  ViewSwizzle swizzle;
  // 4 for the block-compressed formats (BC1-BC7: 4x4 texel blocks), 1 otherwise.
  uint8_t blockSize = 1;
};

// Bytes of one row of blocks (of texels when not block-compressed) of a level
// `width` texels wide, and the number of such rows in `height` texels: sizes round
// up to whole blocks, as D3D11 lays out block-compressed memory.
inline UINT RowPitchBytes(const FormatInfo& f, UINT width) {
  return (width + f.blockSize - 1) / f.blockSize * f.bytesPerElement;
}
inline UINT RowCount(const FormatInfo& f, UINT height) { return (height + f.blockSize - 1) / f.blockSize; }

// nullptr for DXGI_FORMAT_UNKNOWN and any value not in d3d11_types.h.
const FormatInfo* GetFormatInfo(DXGI_FORMAT format);
// Every format of d3d11_types.h except UNKNOWN, in enum order.
std::span<const FormatInfo> AllFormats();
// "DXGI_FORMAT_R8_UNORM", or nullptr like GetFormatInfo.
const char* FormatName(DXGI_FORMAT format);

VkComponentMapping ToVkComponentMapping(ViewSwizzle swizzle);

// Whether a view of format `view` may be created on a resource of format
// `resource` (D3D11.0 rules): typeless views are never allowed (R24_UNORM_X8_TYPELESS
// is a typed read format despite its name); a typed resource only takes its own
// format; a typeless resource takes any member of its family.
bool IsViewCompatible(DXGI_FORMAT resource, DXGI_FORMAT view);

// Depth formats, best first, for an image of `format`'s family created as a
// depth buffer (D24_UNORM_S8_UINT, R24G8_TYPELESS, R24_UNORM_X8_TYPELESS, D32_FLOAT,
// R32_TYPELESS, R32_FLOAT, D16_UNORM, R16_TYPELESS, ...); empty for families
// without a depth member. D24_UNORM_S8_UINT falls back to D32_SFLOAT_S8_UINT:
// lavapipe and AMD lack VK_FORMAT_D24_UNORM_S8_UINT (Vulkan only promises one of
// the two). On a depth image every view (DSV and SRV) uses the image's VkFormat;
// an SRV selects VK_IMAGE_ASPECT_DEPTH_BIT.
std::span<const VkFormat> DepthFormatCandidates(DXGI_FORMAT format);

// The first candidate `isSupported` accepts (the caller decides the usage, e.g.
// optimal-tiling DEPTH_STENCIL_ATTACHMENT | SAMPLED_IMAGE), or
// VK_FORMAT_UNDEFINED. With the D32_SFLOAT_S8_UINT fallback the backend must
// convert uploads/copies (different texel layout) and rescale DepthBias, whose
// D3D unit is 2^-24 for 24-bit UNORM depth.
VkFormat PickDepthFormat(DXGI_FORMAT format, const std::function<bool(VkFormat)>& isSupported);

}  // namespace rhi::states
