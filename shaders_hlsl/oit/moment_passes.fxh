// The passes document 003's moment methods share (oit/mboit.fxh,
// oit/moment_transparency.fxh), over the mathematics of oit/moments.hlsli.
// Render-target slots:
//   moment pass:     RT0 the total optical depth b0 (R32_FLOAT, cleared 0, ONE/ONE),
//                    RT1 the power moments b1..b4 (R32G32B32A32_FLOAT, cleared 0, ONE/ONE),
//                    with MOMENT_MIN_DEPTH also RT2 the minimum view depth (R32_FLOAT, or
//                    R16_FLOAT to show document 003's precision finding; cleared to the
//                    far plane, MIN);
//   weighted pass:   RT0 accum (R16G16B16A16_FLOAT, cleared 0, ONE/ONE) += (c a, a) w,
//                    w = the transmittance in front of the fragment reconstructed from
//                    the moments (with MOMENT_MIN_DEPTH times the correction);
//   Compose:         RT0 the frame: accum.rgb / accum.a with opacity 1 - exp(-b0),
//                    SRC_ALPHA / INV_SRC_ALPHA.
// z and z_min are view depths in scene units in both passes (moments.hlsli says why).
#include "common.fxh"
#include "moments.hlsli"
#include "../fullscreen.hlsli"

#ifndef MOMENT_MIN_DEPTH
#define MOMENT_MIN_DEPTH 0
#endif

// The frame's camera planes (the method sets them in every object's effect each
// frame), which both passes warp and linearise depth with, and document 003's m.
float NearPlane;
float FarPlane;
float MinDepthSlope;

// What the moment pass wrote, read by the weighted pass and the composite.
Texture2D<float> TotalOpticalDepth;
Texture2D<float4> Moments;
Texture2D<float> MinDepth;
Texture2D<float4> Accum;

BlendState MomentsAccumulate {
  BlendEnable[0] = TRUE;
  SrcBlend[0] = ONE;
  DestBlend[0] = ONE;
  BlendOp[0] = ADD;
  SrcBlendAlpha[0] = ONE;
  DestBlendAlpha[0] = ONE;
  BlendOpAlpha[0] = ADD;
  BlendEnable[1] = TRUE;
  SrcBlend[1] = ONE;
  DestBlend[1] = ONE;
  BlendOp[1] = ADD;
  SrcBlendAlpha[1] = ONE;
  DestBlendAlpha[1] = ONE;
  BlendOpAlpha[1] = ADD;
  // The nearest translucent depth: MIN ignores the factors.
  BlendEnable[2] = TRUE;
  SrcBlend[2] = ONE;
  DestBlend[2] = ONE;
  BlendOp[2] = MIN;
  SrcBlendAlpha[2] = ONE;
  DestBlendAlpha[2] = ONE;
  BlendOpAlpha[2] = MIN;
};

// The weighted pass accumulates as WBOIT's Table 1 does into accum.
BlendState WeightedAccumulate {
  BlendEnable[0] = TRUE;
  SrcBlend[0] = ONE;
  DestBlend[0] = ONE;
  BlendOp[0] = ADD;
  SrcBlendAlpha[0] = ONE;
  DestBlendAlpha[0] = ONE;
  BlendOpAlpha[0] = ADD;
};

// The composite over the frame; the frame keeps its alpha (opaque: 1), so that the
// image written to a PNG is not see-through where translucency was composited.
BlendState MomentsCompose {
  BlendEnable[0] = TRUE;
  SrcBlend[0] = SRC_ALPHA;
  DestBlend[0] = INV_SRC_ALPHA;
  BlendOp[0] = ADD;
  SrcBlendAlpha[0] = ZERO;
  DestBlendAlpha[0] = ONE;
  BlendOpAlpha[0] = ADD;
};

// The fragment's view depth (scene units) and its warped depth, the same in both passes.
float FragmentViewDepth(float4 position) { return ViewDepthFromWindow(position.z, NearPlane, FarPlane); }

#ifdef OBJECT_VS
struct MomentsOut {
  float4 totalOpticalDepth : SV_Target0;
  float4 moments : SV_Target1;
#if MOMENT_MIN_DEPTH
  float4 minDepth : SV_Target2;
#endif
};

MomentsOut PSMoments(OBJECT_PIXEL p) {
  float3 c, t;
  float a;
  Shade(p, c, a, t);
  float viewDepth = FragmentViewDepth(p.position);
  float b0;
  float4 b;
  PowerMoments(WarpDepth(viewDepth, NearPlane, FarPlane), OpticalDepth(a), b0, b);
  MomentsOut o;
  o.totalOpticalDepth = b0.xxxx;
  o.moments = b;
#if MOMENT_MIN_DEPTH
  o.minDepth = viewDepth.xxxx;
#endif
  return o;
}

// (c a, a) w, w the transmittance in front of the fragment (document 003: Moment
// Transparency's weight; MBOIT's resolve weighs by the same transmittance).
float4 PSWeighted(OBJECT_PIXEL p) : SV_Target0 {
  float3 c, t;
  float a;
  Shade(p, c, a, t);
  int3 pixel = int3(p.position.xy, 0);
  float viewDepth = FragmentViewDepth(p.position);
  float w = TransmittanceInFront(TotalOpticalDepth.Load(pixel), Moments.Load(pixel),
                                 WarpDepth(viewDepth, NearPlane, FarPlane));
#if MOMENT_MIN_DEPTH
  w *= MinDepthCorrection(viewDepth, MinDepth.Load(pixel), MinDepthSlope);
#endif
  return float4(c * a, a) * w;
}
#endif

// The weighted average colour with the opacity of everything the pixel holds,
// 1 - exp(-b0) (MBOIT's composite; Moment Transparency's "final pass").
float4 PSMomentsCompose(float4 pos : SV_Position) : SV_Target {
  int3 pixel = int3(pos.xy, 0);
  float4 accum = Accum.Load(pixel);
  if (accum.a <= 0.0) discard;
  return float4(accum.rgb / accum.a, 1.0 - exp(-TotalOpticalDepth.Load(pixel)));
}

#define MOMENTS_COMPOSE_PASS                                        \
  pass Compose {                                                    \
    SetVertexShader(CompileShader(vs_5_0, VSFullscreenTriangle())); \
    SetGeometryShader(NULL);                                        \
    SetPixelShader(CompileShader(ps_5_0, PSMomentsCompose()));      \
    SetBlendState(MomentsCompose, float4(0, 0, 0, 0), 0xFFFFFFFF);  \
    SetDepthStencilState(NoDepth, 0);                               \
    SetRasterizerState(NoCull);                                     \
  }
