// Colored blended order-independent transparency (document 000, SPEC.md
// Tables 3 and 4): WBOIT plus a third target, the frame itself, multiplied by
// each surface's transmission. Render-target slots:
//   pass Transparency: RT0 accum, RT1 revealage (as Table 1), RT2 the frame
//                      with the opaque objects (R8G8B8A8_UNORM);
//   pass Compose:      RT0 the frame.
// Table 4 corrected (docs/blend_tables.md); colored_literal.fxh defines
// COLORED_TECHNIQUE and COLORED_COMPOSE to compose with Table 4 as printed.
#include "common.fxh"
#include "weighted_compose.fxh"
#include "wboit_weight.hlsli"

#ifndef COLORED_TECHNIQUE
#define COLORED_TECHNIQUE Colored
#define COLORED_COMPOSE ColoredCompose
#endif

// Table 3: Table 1 plus the frame ZERO/INV_SRC_COLOR (the background is multiplied
// by 1 - a(1 - t)); the table gives no alpha rule for the frame: kept (ZERO/ONE).
BlendState ColoredAccumulate {
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
  BlendEnable[2] = TRUE;
  SrcBlend[2] = ZERO;
  DestBlend[2] = INV_SRC_COLOR;
  BlendOp[2] = ADD;
  SrcBlendAlpha[2] = ZERO;
  DestBlendAlpha[2] = ONE;
  BlendOpAlpha[2] = ADD;
};

// Table 4 corrected: SRC_ALPHA / ONE adds C * (1 - revealage).
BlendState ColoredCompose {
  BlendEnable[0] = TRUE;
  SrcBlend[0] = SRC_ALPHA;
  DestBlend[0] = ONE;
  BlendOp[0] = ADD;
  SrcBlendAlpha[0] = ZERO;
  DestBlendAlpha[0] = ONE;
  BlendOpAlpha[0] = ADD;
};

#ifdef OBJECT_VS
struct ColoredOut {
  float4 accum : SV_Target0;
  float4 revealage : SV_Target1;
  float4 frame : SV_Target2;
};

// Table 3's outputs: Table 1's plus RT2 = a*(1 - t.rgb).
ColoredOut PSColored(OBJECT_PIXEL p) {
  float3 c, t;
  float a;
  Shade(p, c, a, t);
  ColoredOut o;
  float w = WboitWeight(a, p.position.z);
  o.accum = float4(c * a, a) * w;
  o.revealage = float4(a, a, a, a);
  o.frame = float4(a * (1.0 - t), a);
  return o;
}

#endif

// With an object, the whole method (FX11: a technique holds every pass); without
// one (oit/method.fx), the passes that draw no object.
technique11 COLORED_TECHNIQUE {
#ifdef OBJECT_VS
  OBJECT_PASS(Transparency, PSColored, ColoredAccumulate)
#endif
  COMPOSE_PASS(COLORED_COMPOSE)
}
