// Plain alpha blending (OVER) in the order the geometry is drawn: the unsorted
// method, and with the geometry drawn back to front the sorted reference
// (renderer/oit/alpha.cpp registers both). One pass:
//   technique <OVER_TECHNIQUE> pass Transparency: into the frame, straight (c, a).
// An object whose "alpha blending" is another order-independent blend (the fire
// demo: additive) defines OVER_TECHNIQUE and OVER_BLEND before including this.
#include "common.fxh"

BlendState Over {
  BlendEnable[0] = TRUE;
  SrcBlend[0] = SRC_ALPHA;
  DestBlend[0] = INV_SRC_ALPHA;
  BlendOp[0] = ADD;
  SrcBlendAlpha[0] = ONE;
  DestBlendAlpha[0] = INV_SRC_ALPHA;
  BlendOpAlpha[0] = ADD;
};

#ifndef OVER_TECHNIQUE
#define OVER_TECHNIQUE Alpha
#define OVER_BLEND Over
#endif

#ifdef OBJECT_VS
float4 PSOver(OBJECT_PIXEL p) : SV_Target {
  float3 c, t;
  float a;
  Shade(p, c, a, t);
  return float4(c, a);
}

technique11 OVER_TECHNIQUE { OBJECT_PASS(Transparency, PSOver, OVER_BLEND) }
#endif
