// How this device's output merger rounds (renderer/output_merger_probe.h): D3D11
// leaves blend precision to the hardware, at the target format's or better, and the
// compute-tile methods (compute_tiles.fxh), which replay the output merger's blends
// in registers, take the arithmetic this probe finds. A 256x1 target, pixel x:
//   technique Unorm8: Fill writes the destination, then Over blends a source with
//                     alpha.fxh's Over (R8G8B8A8_UNORM); EachTerm and RoundedOnce
//                     write what output_merger.hlsli's two models make of the same blend;
//   technique Half:   Fill writes the destination, then Accumulate adds a source with
//                     wboit.fxh's WboitAccumulate, render target 0 (R16G16B16A16_FLOAT);
//                     TowardZero and Nearest write the two models' sums.
// The models' values are exact in the targets, so the probe compares stored bits.
#include "oit/alpha.fxh"
#include "oit/wboit.fxh"
#include "oit/output_merger.hlsli"

float4 UnormDestination(float x) { return float4(uint4(x * 97, x * 53 + 7, x * 29 + 101, x * 13 + 31) % 256) / 255.0; }
float4 UnormSource(float x) { return frac(x * float4(0.6180339887, 0.7548776662, 0.5698402910, 0.4142135624) + 0.137); }
float4 HalfDestination(float x) { return x < 240 ? 2048 + 2 * (x % 16) : 65504; }
float4 HalfSource(float x) { return x < 240 ? 0.25 + x * float4(0.0137, 0.0071, 0.0113, 0.0059) : 100; }

float4 PSUnormDestination(float4 p : SV_Position) : SV_Target { return UnormDestination(floor(p.x)); }
float4 PSUnormSource(float4 p : SV_Position) : SV_Target { return UnormSource(floor(p.x)); }
float4 PSHalfDestination(float4 p : SV_Position) : SV_Target { return HalfDestination(floor(p.x)); }
float4 PSHalfSource(float4 p : SV_Position) : SV_Target { return HalfSource(floor(p.x)); }

// Over (colour SRC_ALPHA, INV_SRC_ALPHA; alpha ONE, INV_SRC_ALPHA) in each model.
float4 OverModel(float x, bool roundsEachTerm) {
  float4 src = UnormSource(x);
  return BlendUnorm8(src, float4(src.aaa, 1), ToUnorm8(UnormDestination(x)), src.a, roundsEachTerm) / 255.0;
}
float4 PSEachTerm(float4 p : SV_Position) : SV_Target { return OverModel(floor(p.x), true); }
float4 PSRoundedOnce(float4 p : SV_Position) : SV_Target { return OverModel(floor(p.x), false); }
float4 PSTowardZero(float4 p : SV_Position) : SV_Target {
  return Half(HalfDestination(floor(p.x)) + HalfSource(floor(p.x)), true);
}
float4 PSNearest(float4 p : SV_Position) : SV_Target {
  return Half(HalfDestination(floor(p.x)) + HalfSource(floor(p.x)), false);
}

BlendState NoBlend { BlendEnable[0] = FALSE; };

#define PROBE_PASS(name, ps, blend)                                  \
  pass name {                                                        \
    SetVertexShader(CompileShader(vs_5_0, VSFullscreenTriangle()));  \
    SetGeometryShader(NULL);                                         \
    SetPixelShader(CompileShader(ps_5_0, ps()));                     \
    SetBlendState(blend, float4(0, 0, 0, 0), 0xFFFFFFFF);            \
    SetDepthStencilState(NoDepth, 0);                                \
    SetRasterizerState(NoCull);                                      \
  }

technique11 Unorm8 {
  PROBE_PASS(Fill, PSUnormDestination, NoBlend)
  PROBE_PASS(Over, PSUnormSource, Over)
  PROBE_PASS(EachTerm, PSEachTerm, NoBlend)
  PROBE_PASS(RoundedOnce, PSRoundedOnce, NoBlend)
}
technique11 Half {
  PROBE_PASS(Fill, PSHalfDestination, NoBlend)
  PROBE_PASS(Accumulate, PSHalfSource, WboitAccumulate)
  PROBE_PASS(TowardZero, PSTowardZero, NoBlend)
  PROBE_PASS(Nearest, PSNearest, NoBlend)
}
