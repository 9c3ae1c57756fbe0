// Weighted blended order-independent transparency (WBOIT, SPEC.md document 000)
// of a flat-coloured surface, written as a user's effect file would use the
// project's method includes: technique Wboit pass Transparency accumulates the
// surface into two render targets (Table 1), pass Compose blends their resolve
// over the frame buffer with a full-screen triangle (Table 2).

cbuffer PerObject {
  float4x4 WorldViewProj;
  float4 Color = float4(1, 0, 0, 0.5);  // rgb, a = opacity
};

struct SurfaceIn { float4 position : SV_Position; };

SurfaceIn VSSurface(float3 position : POSITION) {
  SurfaceIn o;
  o.position = mul(WorldViewProj, float4(position, 1));
  return o;
}

void Shade(SurfaceIn p, out float3 c, out float a, out float3 t) {
  c = Color.rgb;
  a = Color.a;
  t = Color.rgb;
}

#define OBJECT_VS VSSurface
#define OBJECT_GS NULL
#define OBJECT_PIXEL SurfaceIn
#include "oit/wboit.fxh"
