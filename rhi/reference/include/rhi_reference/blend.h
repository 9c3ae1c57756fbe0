// What D3D11's output merger writes to one render-target pixel (FS 17.1-17.6,
// 17.15): result = Src*SrcFactor OP Dest*DestFactor, per channel, RGB and alpha
// with their own factors and ops, then the write mask.
#pragma once

#include "rhi/d3d11_types.h"
#include "rhi_reference/formats.h"

namespace rhi::reference {

// The blender's arithmetic for one pixel, per channel (RGBA), before the result
// is clamped and converted: what the tolerance model needs to size the error a
// conforming device may make (tolerance.h, BlendTermBound).
struct BlendTerms {
  Float4 srcTerm{};     // Csrc*Fsrc (linear; 0 where the op has no product)
  Float4 destTerm{};    // Cdst*Fdst (linear; for sRGB the destination decoded first)
  Float4 result{};      // srcTerm OP destTerm, unclamped (MIN/MAX: the min/max)
  Float4 srcOperand{};  // Csrc and Cdst as they entered the blender (after the clamp / decode);
  Float4 destOperand{}; // informational: the term bound uses the products, not these
  // True where ADD / SUBTRACT / REV_SUBTRACT of two products was written to the
  // channel (blending on, non-UINT target, write mask set). MIN / MAX, unblended
  // writes and masked channels involve no blend arithmetic.
  std::array<bool, 4> arithmetic{};
};

struct BlendOutput {
  StoredColor stored;  // the target's new contents (what a readback must match)
  Float4 decoded;      // Decode(format, stored): linear for sRGB
  BlendTerms terms{};  // the blend's products and result per channel
};

// One render target. `src0` is SV_Target (o0 / oN), `src1` is SV_Target1 (only
// read by the SRC1_* factors), `blendFactor` is OMSetBlendState's factor, `dest`
// the pixel before the draw. BlendEnable FALSE and UINT targets write src0 after
// format conversion (D3D11 does not blend integer targets). Dual-source blending
// is only defined for target 0 with ADD/SUBTRACT/REV_SUBTRACT (FS 17.6); this
// function evaluates it regardless.
BlendOutput BlendResult(DXGI_FORMAT format, const RENDER_TARGET_BLEND_DESC& blend,
                        const Float4& blendFactor, const Float4& src0, const Float4& src1,
                        const StoredColor& dest);

// The settings target `renderTarget` uses: RenderTarget[0]'s when
// IndependentBlendEnable is FALSE (FS 17.1: "If false, only use entry [0]").
const RENDER_TARGET_BLEND_DESC& TargetBlendDesc(const BLEND_DESC& desc, UINT renderTarget);

// The whole blend state applied to target `renderTarget`.
BlendOutput BlendResult(DXGI_FORMAT format, const BLEND_DESC& desc, UINT renderTarget,
                        const Float4& blendFactor, const Float4& src0, const Float4& src1,
                        const StoredColor& dest);

}  // namespace rhi::reference
