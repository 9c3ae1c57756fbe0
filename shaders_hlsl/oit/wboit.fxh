// Weighted blended order-independent transparency (document 000, SPEC.md
// Tables 1 and 2). Render-target slots:
//   pass Transparency: RT0 accum (R16G16B16A16_FLOAT, cleared (0,0,0,0)),
//                      RT1 revealage (R8_UNORM, cleared (1,0,0,0));
//   pass Compose:      RT0 the frame (R8G8B8A8_UNORM) with the opaque objects.
// FX11 starts every BlendState with IndependentBlendEnable TRUE (no state member
// for it), so targets a block leaves alone keep blending off.
#include "common.fxh"
#include "weighted_compose.fxh"
#include "wboit_weight.hlsli"

// Table 1: accum ONE/ONE; revealage ZERO/INV_SRC_COLOR (D3D11 forbids colour
// factors for alpha: revealage is R8, its alpha factors never matter, ZERO/INV_SRC_ALPHA).
BlendState WboitAccumulate {
  BlendEnable[0] = TRUE;
  SrcBlend[0] = ONE;
  DestBlend[0] = ONE;
  BlendOp[0] = ADD;
  SrcBlendAlpha[0] = ONE;
  DestBlendAlpha[0] = ONE;
  BlendOpAlpha[0] = ADD;
  BlendEnable[1] = TRUE;
  SrcBlend[1] = ZERO;
  DestBlend[1] = INV_SRC_COLOR;
  BlendOp[1] = ADD;
  SrcBlendAlpha[1] = ZERO;
  DestBlendAlpha[1] = INV_SRC_ALPHA;
  BlendOpAlpha[1] = ADD;
};

// Table 2: the resolve over the frame with SRC_ALPHA / INV_SRC_ALPHA.
BlendState WboitCompose {
  BlendEnable[0] = TRUE;
  SrcBlend[0] = SRC_ALPHA;
  DestBlend[0] = INV_SRC_ALPHA;
  BlendOp[0] = ADD;
  SrcBlendAlpha[0] = SRC_ALPHA;
  DestBlendAlpha[0] = INV_SRC_ALPHA;
  BlendOpAlpha[0] = ADD;
};

#ifdef OBJECT_VS
struct WboitOut {
  float4 accum : SV_Target0;
  float4 revealage : SV_Target1;
};

// Table 1's outputs: RT0 = (c*a, a)*w, RT1 = a.
WboitOut PSWboit(OBJECT_PIXEL p) {
  float3 c, t;
  float a;
  Shade(p, c, a, t);
  WboitOut o;
  float w = WboitWeight(a, p.position.z);
  o.accum = float4(c * a, a) * w;
  o.revealage = float4(a, a, a, a);
  return o;
}

#endif

// With an object, the whole method (FX11: a technique holds every pass); without
// one (oit/method.fx), the passes that draw no object.
technique11 Wboit {
#ifdef OBJECT_VS
  OBJECT_PASS(Transparency, PSWboit, WboitAccumulate)
#endif
  COMPOSE_PASS(WboitCompose)
}
