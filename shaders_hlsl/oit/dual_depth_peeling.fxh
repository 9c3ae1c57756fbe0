// Dual depth peeling (Bavoil & Myers 2008, "Order Independent Transparency with
// Dual Depth Peeling", NVIDIA): each geometry pass peels two layers, the nearest and
// the farthest left, so N layers take N/2 peeling passes after one that finds the
// depth range. MAX blending does the depth tests: a pixel's (-z, z) under MAX keeps
// the range of the fragments not yet peeled. Render-target slots (every one MAX):
//   pass Init:  RT0 the depth range (R32G32_FLOAT, cleared (-1, -1)): (-z, z).
//   pass Peel:  RT0 the next depth range (the other R32G32_FLOAT buffer);
//               RT1, RT2 the front accumulation (R16G16B16A16_FLOAT, ping-ponged:
//                 the pass reads the other pair): colour sum T a c, and 1 - T;
//               RT3, RT4 the back layer peeled now (R16G16B16A16_FLOAT, cleared 0):
//                 (a c, a) and 1 - TransmissionFactor(a, t).
//   pass LoadFrame (first): RT0 the composite (R32G32B32A32_FLOAT) = the opaque frame
//       (float_composite.hlsli says why).
//   pass BlendBack (after each Peel) and BlendFront (last): RT0 the composite.
//   pass StoreFrame: RT0 the frame = the composite, rounded once.
// The opaque depth is bound read-only-in-effect (DepthTestNoWrite): fragments
// behind the opaque geometry take part in no pass, so it bounds every layer.
//
// Transmission: the per-channel model of common.fxh (TransmissionFactor) holds
// everywhere. The front accumulates under its layers in the shader (MAX passes the
// larger values on: a sum that only grows, 1 - T that only grows), with 1 - T kept
// per channel in its own target. The back layers go over the frame (B&M clear their
// back buffer to the background, which here is the frame itself) with dual-source
// blending, frame = a c + T * frame, T per channel in SV_Target1: plain D3D11
// blending (SRC_ALPHA / INV_SRC_ALPHA, B&M's) has one transmission for all channels.
#include "common.fxh"
#include "../fullscreen.hlsli"
#include "float_composite.hlsli"

Texture2D<float2> DepthRange;    // (-nearest, farthest) of what the last pass left to peel
Texture2D<float4> FrontColour;   // the front so far: sum of T a c over its layers
Texture2D<float4> FrontOpacity;  // the front so far: 1 - the product of its TransmissionFactors
Texture2D<float4> BackColour;    // the back layer peeled by the last Peel: (a c, a)
Texture2D<float4> BackOpacity;   // ... and its 1 - TransmissionFactor

// Every depth is in [0, 1]: (-1, -1) is below every range under MAX.
static const float2 kNoRange = float2(-1, -1);

BlendState MaxBlend {
  BlendEnable[0] = TRUE; SrcBlend[0] = ONE; DestBlend[0] = ONE; BlendOp[0] = MAX;
  SrcBlendAlpha[0] = ONE; DestBlendAlpha[0] = ONE; BlendOpAlpha[0] = MAX;
  BlendEnable[1] = TRUE; SrcBlend[1] = ONE; DestBlend[1] = ONE; BlendOp[1] = MAX;
  SrcBlendAlpha[1] = ONE; DestBlendAlpha[1] = ONE; BlendOpAlpha[1] = MAX;
  BlendEnable[2] = TRUE; SrcBlend[2] = ONE; DestBlend[2] = ONE; BlendOp[2] = MAX;
  SrcBlendAlpha[2] = ONE; DestBlendAlpha[2] = ONE; BlendOpAlpha[2] = MAX;
  BlendEnable[3] = TRUE; SrcBlend[3] = ONE; DestBlend[3] = ONE; BlendOp[3] = MAX;
  SrcBlendAlpha[3] = ONE; DestBlendAlpha[3] = ONE; BlendOpAlpha[3] = MAX;
  BlendEnable[4] = TRUE; SrcBlend[4] = ONE; DestBlend[4] = ONE; BlendOp[4] = MAX;
  SrcBlendAlpha[4] = ONE; DestBlendAlpha[4] = ONE; BlendOpAlpha[4] = MAX;
};

// frame = C + T * frame per channel (C in SV_Target0, T in SV_Target1); alpha kept.
BlendState OverFrame {
  BlendEnable[0] = TRUE;
  SrcBlend[0] = ONE;
  DestBlend[0] = SRC1_COLOR;
  BlendOp[0] = ADD;
  SrcBlendAlpha[0] = ZERO;
  DestBlendAlpha[0] = ONE;
  BlendOpAlpha[0] = ADD;
};

#ifdef OBJECT_VS
// A fragment with a = 0 is no surface (no colour, TransmissionFactor(0, t) = 1): it
// takes no part in the ranges, as depth peeling gives it no layer.
float4 PSInit(OBJECT_PIXEL p) : SV_Target {
  float3 c, t;
  float a;
  Shade(p, c, a, t);
  return a == 0 ? float4(kNoRange, 0, 0) : float4(-p.position.z, p.position.z, 0, 0);
}

struct PeelOut {
  float4 range : SV_Target0;
  float4 frontColour : SV_Target1;
  float4 frontOpacity : SV_Target2;
  float4 backColour : SV_Target3;
  float4 backOpacity : SV_Target4;
};

// B&M's peeling shader. Every fragment passes the front on (MAX keeps the one that
// grew it) and writes no back layer (0), and takes itself out of the next range
// unless it lies strictly inside this one; the fragment at the nearest depth joins
// the front, the one at the farthest is the back layer.
PeelOut PSPeel(OBJECT_PIXEL p) {
  // Shaded first, while the whole quad runs: the object may sample with derivatives.
  float3 c, t;
  float a;
  Shade(p, c, a, t);
  int3 at = int3(p.position.xy, 0);
  float2 range = DepthRange.Load(at);
  float nearest = -range.x, farthest = range.y, z = p.position.z;
  PeelOut o;
  o.range = float4(kNoRange, 0, 0);
  o.frontColour = FrontColour.Load(at);
  o.frontOpacity = FrontOpacity.Load(at);
  o.backColour = 0;
  o.backOpacity = 0;
  if (a == 0 || z < nearest || z > farthest) return o;  // no surface, or peeled by an earlier pass
  if (z > nearest && z < farthest) {          // for a later pass
    o.range = float4(-z, z, 0, 0);
    return o;
  }
  // Saturated as depth peeling does (OVER's source clamped by the UNORM frame).
  float3 premultiplied = a * SurfaceColour(c), transmission = TransmissionFactor(a, t);
  if (z == nearest) {  // under the front: C += T a c, T *= TransmissionFactor
    float3 frontT = 1.0 - o.frontOpacity.rgb;
    o.frontColour.rgb += frontT * premultiplied;
    o.frontOpacity.rgb = 1.0 - frontT * transmission;
  } else {
    o.backColour = float4(premultiplied, a);
    o.backOpacity = float4(1.0 - transmission, a);
  }
  return o;
}
#endif

struct OverFrameOut {
  float4 colour : SV_Target0;
  float4 transmission : SV_Target1;
};

OverFrameOut OverTheFrame(Texture2D<float4> colour, Texture2D<float4> opacity, float4 pos) {
  int3 at = int3(pos.xy, 0);
  OverFrameOut o;
  o.colour = float4(colour.Load(at).rgb, 0);
  o.transmission = float4(1.0 - opacity.Load(at).rgb, 1);
  return o;
}

// The back layers arrive farthest first: each goes over the frame as it comes.
OverFrameOut PSBlendBack(float4 pos : SV_Position) { return OverTheFrame(BackColour, BackOpacity, pos); }
// The front, every layer nearer than the back ones, goes over them last.
OverFrameOut PSBlendFront(float4 pos : SV_Position) { return OverTheFrame(FrontColour, FrontOpacity, pos); }

#define DUAL_OBJECT_PASS(name, ps)                           \
  pass name {                                                \
    SetVertexShader(CompileShader(vs_5_0, OBJECT_VS()));     \
    SetGeometryShader(OBJECT_GS);                            \
    SetPixelShader(CompileShader(ps_5_0, ps()));             \
    SetBlendState(MaxBlend, float4(0, 0, 0, 0), 0xFFFFFFFF); \
    SetDepthStencilState(DepthTestNoWrite, 0);               \
    SetRasterizerState(NoCull);                              \
  }

#define DUAL_FULLSCREEN_PASS(name, ps, blend)                     \
  pass name {                                                     \
    SetVertexShader(CompileShader(vs_5_0, VSFullscreenTriangle()));   \
    SetGeometryShader(NULL);                                      \
    SetPixelShader(CompileShader(ps_5_0, ps()));                  \
    SetBlendState(blend, float4(0, 0, 0, 0), 0xFFFFFFFF);         \
    SetDepthStencilState(NoDepth, 0);                             \
    SetRasterizerState(NoCull);                                   \
  }

// With an object, the whole method (FX11: a technique holds every pass); without
// one (oit/method.fx), the passes that draw no object.
technique11 DualDepthPeeling {
#ifdef OBJECT_VS
  DUAL_OBJECT_PASS(Init, PSInit)
  DUAL_OBJECT_PASS(Peel, PSPeel)
#endif
  DUAL_FULLSCREEN_PASS(LoadFrame, PSCopy, NULL)
  DUAL_FULLSCREEN_PASS(BlendBack, PSBlendBack, OverFrame)
  DUAL_FULLSCREEN_PASS(BlendFront, PSBlendFront, OverFrame)
  DUAL_FULLSCREEN_PASS(StoreFrame, PSCopy, NULL)
}
