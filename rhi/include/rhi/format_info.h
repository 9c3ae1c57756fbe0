// Format facts for code above the RHI (DirectXTex's names), read from the
// backend's one format table: sizing buffers and reporting memory without a
// second table of formats.
#pragma once

#include "rhi/d3d11_types.h"

namespace rhi {

// Bits per texel (per element for buffer formats; BC1/BC4: 4, other BC formats: 8);
// 0 for DXGI_FORMAT_UNKNOWN and values not in d3d11_types.h.
UINT BitsPerPixel(DXGI_FORMAT format);

// "DXGI_FORMAT_R8G8B8A8_UNORM"; null for values not in d3d11_types.h.
const char* FormatName(DXGI_FORMAT format);

// The BIND_* flags D3D11 feature level 11_0 requires `format` to support (BIND_RENDER_TARGET:
// it can be rendered to); 0 for values not in d3d11_types.h. Typeless formats list what
// their typed views may be bound as.
UINT FormatBindFlags(DXGI_FORMAT format);

// Whether `format` is typeless (DXGI_FORMAT_*_TYPELESS, R24_UNORM_X8_TYPELESS excepted).
bool IsTypeless(DXGI_FORMAT format);

// Whether `format` is block-compressed (BC1-BC7: 4x4 texel blocks).
bool IsCompressed(DXGI_FORMAT format);

// DirectXTex's ComputePitch: the bytes of one row (of 4x4 blocks for BC formats) and of
// one slice of a `width` x `height` image, rounded up to whole blocks as D3D11 lays
// them out (a 2x2 BC1 level is one 8-byte block). False for unknown formats.
bool ComputePitch(DXGI_FORMAT format, UINT width, UINT height, UINT64* rowPitch, UINT64* slicePitch);

// Bytes of every subresource and sample of a 2D texture (sizes of mip levels
// rounded down, at least 1, as D3D11 computes them).
UINT64 TextureBytes(const TEXTURE2D_DESC& desc);

}  // namespace rhi
