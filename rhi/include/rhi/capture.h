// Reading a texture back to the CPU as D3D11 code does (DirectXTK's
// CaptureTexture): a STAGING copy of one subresource, CopySubresourceRegion,
// Map with MAP_READ, the rows copied out. For screenshots, golden images and
// the headless demos.
#pragma once

#include <vector>

#include "rhi/rhi.h"

namespace rhi {

// Reads `subresource` of the 2D texture `source` into `texels`, rows tightly
// packed (the mip level's width times the format's bytes per texel, no row
// pitch). A multisampled texture is resolved first (ResolveSubresource: the
// average of each pixel's samples), its subresource being the array slice.
// Waits for the GPU. Returns S_OK; E_INVALIDARG, with the reason sent to the
// device's message callback, for a subresource out of range or a multisampled
// texture that has no resolve (integer, depth and typeless formats); or the
// HRESULT of the call that failed.
HRESULT CaptureTexture2D(Device* device, DeviceContext* context, Texture2D* source, UINT subresource,
                         std::vector<uint8_t>* texels);

}  // namespace rhi
