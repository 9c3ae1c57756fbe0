// Format facts for code above the RHI (DirectXTex's names), read from the
// backend's one format table: sizing buffers and reporting memory without a
// second table of formats.
#pragma once

#include "rhi/d3d11_types.h"

namespace rhi {

// Bits per texel (per element for buffer formats); 0 for DXGI_FORMAT_UNKNOWN and
// values not in d3d11_types.h.
UINT BitsPerPixel(DXGI_FORMAT format);

// Bytes of every subresource and sample of a 2D texture (sizes of mip levels
// rounded down, at least 1, as D3D11 computes them).
UINT64 TextureBytes(const TEXTURE2D_DESC& desc);

}  // namespace rhi
