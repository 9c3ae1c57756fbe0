// How this device's output merger rounds (renderer/output_merger_probe.h): D3D11
// leaves blend precision to the hardware, at the target format's or better, and the
// compute-tile methods (compute_tiles.fxh), which replay the output merger's blends
// in registers, take the arithmetic this probe finds. A 256x1 target, pixel x:
//   technique Unorm8: Fill writes the destination, then Over blends a source with
//                     alpha.fxh's Over (R8G8B8A8_UNORM);
//   technique Half:   Fill writes the destination, then Accumulate adds a source with
//                     wboit.fxh's WboitAccumulate, render target 0 (R16G16B16A16_FLOAT).
// The values are functions of x that renderer/src/output_merger_probe.cpp computes too.
#include "oit/alpha.fxh"
#include "oit/wboit.fxh"

float4 UnormDestination(float x) { return float4(uint4(x * 97, x * 53 + 7, x * 29 + 101, x * 13 + 31) % 256) / 255.0; }
float4 UnormSource(float x) { return frac(x * float4(0.6180339887, 0.7548776662, 0.5698402910, 0.4142135624) + 0.137); }
float4 HalfDestination(float x) { return x < 240 ? 2048 + 2 * (x % 16) : 65504; }
float4 HalfSource(float x) { return x < 240 ? 0.25 + x * float4(0.0137, 0.0071, 0.0113, 0.0059) : 100; }

float4 PSUnormDestination(float4 p : SV_Position) : SV_Target { return UnormDestination(floor(p.x)); }
float4 PSUnormSource(float4 p : SV_Position) : SV_Target { return UnormSource(floor(p.x)); }
float4 PSHalfDestination(float4 p : SV_Position) : SV_Target { return HalfDestination(floor(p.x)); }
float4 PSHalfSource(float4 p : SV_Position) : SV_Target { return HalfSource(floor(p.x)); }

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
}
technique11 Half {
  PROBE_PASS(Fill, PSHalfDestination, NoBlend)
  PROBE_PASS(Accumulate, PSHalfSource, WboitAccumulate)
}
