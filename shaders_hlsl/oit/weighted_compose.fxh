// The 2D composing pass of the weighted methods (WBOIT, colored OIT): a
// full-screen triangle (Draw(3, 0), no vertex buffer) reading accum and
// revealage, writing (accum.rgb / max(accum.a, 0.0001), 1 - revealage) through
// the method's composing blend state (Table 2 or 4).
#ifndef OIT_WEIGHTED_COMPOSE_FXH
#define OIT_WEIGHTED_COMPOSE_FXH
#include "../fullscreen.hlsli"

Texture2D<float4> Accum;      // R16G16B16A16_FLOAT: the sum of (c*a, a)*w
Texture2D<float4> Revealage;  // R8_UNORM: the product of (1 - a)

// What the composing pass outputs for a pixel's accum and revealage (also the
// compute-tile WBOIT's, compute_tiles.fxh).
float4 WeightedComposite(float4 accum, float revealage) {
  return float4(accum.rgb / max(accum.a, 0.0001), 1.0 - revealage);
}

float4 PSCompose(float4 pos : SV_Position) : SV_Target {
  int3 p = int3(pos.xy, 0);
  return WeightedComposite(Accum.Load(p), Revealage.Load(p).r);
}

#define COMPOSE_PASS(blend)                                   \
  pass Compose {                                              \
    SetVertexShader(CompileShader(vs_5_0, VSFullscreenTriangle()));   \
    SetGeometryShader(NULL);                                  \
    SetPixelShader(CompileShader(ps_5_0, PSCompose()));       \
    SetBlendState(blend, float4(0, 0, 0, 0), 0xFFFFFFFF);     \
    SetDepthStencilState(NoDepth, 0);                         \
    SetRasterizerState(NoCull);                               \
  }

#endif
