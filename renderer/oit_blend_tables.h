// The four blend tables of SPEC.md document 000 (the Direct3D 11 particle /
// OIT paper) as BLEND_DESC factories, header-only.
//
// Render-target slots used by every factory:
//   accumulate passes (Tables 1 and 3): RT0 accum (R16G16B16A16_FLOAT, cleared
//   (0,0,0,0)), RT1 revealage (R8_UNORM, cleared (1,0,0,0)), RT2 the frame with
//   the opaque objects (R8G8B8A8_UNORM, Table 3 only);
//   composing passes (Tables 2 and 4): RT0 the frame.
// Pixel-shader outputs the tables prescribe:
//   RT0 = (r*a, g*a, b*a, a) * w, RT1 = a, RT2 = a * (1 - t.rgb) (Table 3),
//   compose: (accum.rgb / max(accum.a, 0.0001), 1 - revealage).
//
// Table 4 is offered twice. As printed (Fsrc = INV_SRC_ALPHA, Fdst = ONE) the
// composing pass adds C * (1 - (1 - revealage)) = C * revealage: the weighted
// average colour scaled by the *transmitted* fraction, so a layer stack that
// covers the pixel fully (revealage -> 0) adds nothing and a nearly transparent
// one adds almost its full colour. The method's intent is
//   frame = background * prod(1 - a_i (1 - t_i)) + C * (1 - prod(1 - a_i)),
// and the frame already holds the first term after Table 3's pass, so the
// composing pass must add C * (1 - revealage) = C * source alpha: Fsrc =
// SRC_ALPHA, Fdst = ONE (ColoredComposeBlendCorrected). docs/blend_tables.md
// gives the numbers measured by tests/conformance/oit_tables_test.cpp.
#pragma once

#include <algorithm>
#include <cmath>

#include "rhi/d3d11_types.h"

namespace oit {

inline rhi::RENDER_TARGET_BLEND_DESC TargetBlend(rhi::BLEND src, rhi::BLEND dest, rhi::BLEND srcAlpha,
                                                 rhi::BLEND destAlpha, rhi::UINT8 writeMask = rhi::COLOR_WRITE_ENABLE_ALL) {
  rhi::RENDER_TARGET_BLEND_DESC rt;
  rt.BlendEnable = rhi::TRUE;
  rt.SrcBlend = src;
  rt.DestBlend = dest;
  rt.BlendOp = rhi::BLEND_OP_ADD;
  rt.SrcBlendAlpha = srcAlpha;
  rt.DestBlendAlpha = destAlpha;
  rt.BlendOpAlpha = rhi::BLEND_OP_ADD;
  rt.RenderTargetWriteMask = writeMask;
  return rt;
}

// Table 1: accum ONE/ONE; revealage ZERO/INV_SRC_COLOR. (D3D11 forbids colour
// factors for alpha; revealage is R8 so its alpha factors never matter: the
// alpha-channel equivalent ZERO/INV_SRC_ALPHA is used.)
inline rhi::BLEND_DESC WboitAccumulateBlend() {
  rhi::BLEND_DESC d;
  d.IndependentBlendEnable = rhi::TRUE;
  d.RenderTarget[0] = TargetBlend(rhi::BLEND_ONE, rhi::BLEND_ONE, rhi::BLEND_ONE, rhi::BLEND_ONE);
  d.RenderTarget[1] = TargetBlend(rhi::BLEND_ZERO, rhi::BLEND_INV_SRC_COLOR, rhi::BLEND_ZERO, rhi::BLEND_INV_SRC_ALPHA);
  return d;
}

// Table 2: frame SRC_ALPHA / INV_SRC_ALPHA (alpha the same).
inline rhi::BLEND_DESC WboitComposeBlend() {
  rhi::BLEND_DESC d;
  d.RenderTarget[0] =
      TargetBlend(rhi::BLEND_SRC_ALPHA, rhi::BLEND_INV_SRC_ALPHA, rhi::BLEND_SRC_ALPHA, rhi::BLEND_INV_SRC_ALPHA);
  return d;
}

// Table 3: Table 1 plus the frame ZERO / INV_SRC_COLOR (the frame's colour is
// multiplied by 1 - a(1 - t)). The table gives no alpha rule for the frame; its
// alpha is kept (ZERO / ONE).
inline rhi::BLEND_DESC ColoredAccumulateBlend() {
  rhi::BLEND_DESC d = WboitAccumulateBlend();
  d.RenderTarget[2] = TargetBlend(rhi::BLEND_ZERO, rhi::BLEND_INV_SRC_COLOR, rhi::BLEND_ZERO, rhi::BLEND_ONE);
  return d;
}

// Table 4 as printed: INV_SRC_ALPHA / ONE. Adds C * revealage (see above).
inline rhi::BLEND_DESC ColoredComposeBlendLiteral() {
  rhi::BLEND_DESC d;
  d.RenderTarget[0] = TargetBlend(rhi::BLEND_INV_SRC_ALPHA, rhi::BLEND_ONE, rhi::BLEND_ZERO, rhi::BLEND_ONE);
  return d;
}

// Table 4 corrected: SRC_ALPHA / ONE. Adds C * (1 - revealage): the intent.
inline rhi::BLEND_DESC ColoredComposeBlendCorrected() {
  rhi::BLEND_DESC d;
  d.RenderTarget[0] = TargetBlend(rhi::BLEND_SRC_ALPHA, rhi::BLEND_ONE, rhi::BLEND_ZERO, rhi::BLEND_ONE);
  return d;
}

// The WBOIT weight of Table 1 (z = SV_Position.z), as the pixel shader computes it.
inline float WboitWeight(float a, float z) {
  const float w = std::pow(std::min(1.0f, a * 10.0f) + 0.01f, 3.0f) * 1e8f * std::pow(1.0f - z * 0.9f, 3.0f);
  return std::clamp(w, 1e-2f, 3e3f);
}

// The same in HLSL, for pixel shaders.
inline constexpr const char* kWboitWeightHlsl =
    "float WboitWeight(float a, float z) {\n"
    "  return clamp(pow(min(1.0, a * 10.0) + 0.01, 3.0) * 1e8 * pow(1.0 - z * 0.9, 3.0), 1e-2, 3e3);\n"
    "}\n";

}  // namespace oit
