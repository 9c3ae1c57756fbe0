// D3D11 depth and stencil test for one pixel (FS 17.8-17.12).
#pragma once

#include <cstdint>

#include "rhi/d3d11_types.h"

namespace rhi::reference {

struct DepthStencilOutcome {
  bool depthPassed = true;    // TRUE when DepthEnable is FALSE (FS 17.9)
  bool stencilPassed = true;  // TRUE when StencilEnable is FALSE or the format has no stencil
  bool passed = true;         // both: the pixel goes on to blending
  uint32_t depth = 0;         // stored depth afterwards: float bits (D32_FLOAT) or 24-bit code
  uint8_t stencil = 0;        // stored stencil afterwards (unchanged for D32_FLOAT)
};

// `fragmentDepth` is the depth reaching the output merger, already clamped to the
// viewport's [MinDepth, MaxDepth] (FS 17.10). `storedDepth` is in the buffer's
// representation (DepthToStored). `stencilRef` uses its low 8 bits. Depth formats:
// D32_FLOAT and D24_UNORM_S8_UINT.
DepthStencilOutcome DepthStencilResult(const DEPTH_STENCIL_DESC& desc, UINT stencilRef,
                                       bool frontFacing, float fragmentDepth, uint32_t storedDepth,
                                       uint8_t storedStencil, DXGI_FORMAT depthFormat);

// z in the depth buffer's representation (FS 17.11): D32_FLOAT keeps the float
// bits; D24 is round to nearest, z*(2^24-1)+0.5 truncated, after clamping to [0,1].
uint32_t DepthToStored(DXGI_FORMAT depthFormat, float z);
float StoredToDepth(DXGI_FORMAT depthFormat, uint32_t stored);

// `left FUNC right`: the fragment's value (depth, or ref & ReadMask) on the left.
bool Compare(COMPARISON_FUNC func, float left, float right);
bool Compare(COMPARISON_FUNC func, uint32_t left, uint32_t right);

// The new stencil value before the write mask is applied.
uint8_t ApplyStencilOp(STENCIL_OP op, uint8_t stored, uint8_t ref);

}  // namespace rhi::reference
