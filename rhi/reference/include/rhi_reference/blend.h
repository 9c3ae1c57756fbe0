// What D3D11's output merger writes to one render-target pixel (FS 17.1-17.6,
// 17.15): result = Src*SrcFactor OP Dest*DestFactor, per channel, RGB and alpha
// with their own factors and ops, then the write mask.
#pragma once

#include "rhi/d3d11_types.h"
#include "rhi_reference/formats.h"

namespace rhi::reference {

// Where one channel's blend factor came from, so the tolerance model can size
// the error of a device that converts the factor's inputs to the render
// target's precision first (FS 17.5, tolerance.cpp): `blend` is the D3D11_BLEND,
// `input` the value the factor is made of (x of SRC_COLOR / INV_SRC_COLOR /
// BLEND_FACTOR / ...; oN.a for SRC_ALPHA_SAT), `input2` RT(N).a for
// SRC_ALPHA_SAT (unused otherwise). ZERO / ONE carry no input.
struct FactorSource {
  BLEND blend = BLEND_ZERO;
  float input = 0.0f;
  float input2 = 0.0f;
};

// The blender's arithmetic for one pixel, per channel (RGBA), before the result
// is clamped and converted: what the tolerance model needs to size the error a
// conforming device may make (tolerance.h, BlendTermBound).
struct BlendTerms {
  Float4 srcTerm{};     // Csrc*Fsrc (linear; 0 where the op has no product)
  Float4 destTerm{};    // Cdst*Fdst (linear; for sRGB the destination decoded first)
  Float4 result{};      // srcTerm OP destTerm, unclamped (MIN/MAX: the min/max)
  Float4 srcOperand{};  // Csrc and Cdst as they entered the blender (after the clamp / decode);
  Float4 destOperand{}; // the term bound of float targets uses them (tolerance.cpp)
  Float4 srcFactor{};   // Fsrc and Fdst as the reference computed them (float32)
  Float4 destFactor{};
  std::array<FactorSource, 4> srcFactorSource{};
  std::array<FactorSource, 4> destFactorSource{};
  // True where ADD / SUBTRACT / REV_SUBTRACT of two products was written to the
  // channel (blending on, non-UINT target, write mask set). MIN / MAX, unblended
  // writes and masked channels involve no blend arithmetic.
  std::array<bool, 4> arithmetic{};
};

// How SRC_ALPHA_SAT's f = min(oN.a, 1 - RT(N).a) is read when it falls outside
// [0, 1], which only float targets allow (UNORM inputs are clamped to [0, 1]
// first, FS 17.5):
//  - Formula: FS 17.1 gives the factor as "(f,f,f,1), f = min(1 - RT(N).a, oN.a)"
//    and nothing more; Vulkan's VK_BLEND_FACTOR_SRC_ALPHA_SATURATE is the same
//    min with no clamp for floating-point attachments. f is used as it is.
//  - Saturated: the factor's name ("SAT"), and the D3D11_BLEND documentation,
//    which says of SRC_ALPHA_SAT: "The pre-blend operation clamps the data to 1
//    or less", describe a saturated factor; f is clamped to [0, 1].
// Neither source settles which one D3D11 means for out-of-range data, so the
// reference reports both and the tolerance accepts a pixel that matches either
// (docs/blend_tables.md, "SRC_ALPHA_SAT outside [0, 1]").
enum class SatReading { Formula, Saturated };

struct BlendReading {
  StoredColor stored;  // the target's new contents (what a readback must match)
  Float4 decoded;      // Decode(format, stored): linear for sRGB
  BlendTerms terms{};  // the blend's products and result per channel
};

struct BlendOutput : BlendReading {
  // Set when a written, blended channel uses SRC_ALPHA_SAT with f outside
  // [0, 1]: then `saturated` is the same blend with f clamped to [0, 1] (the
  // inherited fields hold the FS 17.1 formula reading). CompareBlend accepts
  // either reading for the whole pixel.
  bool hasSaturatedReading = false;
  BlendReading saturated{};
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

// One reading only (the above computes Formula and, where it differs, Saturated).
BlendReading BlendReadingOf(DXGI_FORMAT format, const RENDER_TARGET_BLEND_DESC& blend, const Float4& blendFactor,
                            const Float4& src0, const Float4& src1, const StoredColor& dest, SatReading sat);

// The settings target `renderTarget` uses: RenderTarget[0]'s when
// IndependentBlendEnable is FALSE (FS 17.1: "If false, only use entry [0]").
const RENDER_TARGET_BLEND_DESC& TargetBlendDesc(const BLEND_DESC& desc, UINT renderTarget);

// The whole blend state applied to target `renderTarget`.
BlendOutput BlendResult(DXGI_FORMAT format, const BLEND_DESC& desc, UINT renderTarget,
                        const Float4& blendFactor, const Float4& src0, const Float4& src1,
                        const StoredColor& dest);

}  // namespace rhi::reference
