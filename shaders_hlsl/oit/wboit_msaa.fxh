// Weighted blended OIT with MSAA and a per-sample resolve (document 001, SPEC.md
// "001"; the JCGT 2013 weighted average without a depth weight), and the variants
// its discussion names. renderer/src/oit/wboit_msaa.cpp runs the passes:
//   Scene         (scene.fx Opaque/Scene through oit::Backdrop) the opaque objects into
//                 a multisampled R16G16B16A16_FLOAT colour target (D3D11 has no RGB16F:
//                 the article's GL_RGB16F is this class) and a multisampled D32_FLOAT depth;
//   Transparency  the objects, depth test LESS_EQUAL, no depth writes, no culling, into
//                 RT0 accum   R16G16B16A16_FLOAT, cleared (0,0,0,0), ONE/ONE:  (w·c, w)
//                 RT1 product R16_FLOAT,          cleared (1,0,0,0), DEST_COLOR/ZERO: 1 − w
//                 with w the fragment's opacity;
//   Compose       a full-screen pass reading the three multisampled textures with
//                 Texture2DMS.Load(pos, SV_SampleIndex), which makes it run per sample,
//                 into a multisampled R8G8B8A8 target, resolved to the frame
//                 (ResolveSubresource: the average of the samples).
// ComposePerPixel (the method wboit-msaa-per-pixel, for comparison): the three targets
// resolved first (averaged), then the same formula once per pixel into the frame.
//
// The variants (WBOIT_MSAA_ADDITIVE, set by the small includes wboit_msaa_*.fxh):
//   additive  plain additive blending, premultiplied, ONE/ONE, no division: RT0
//             accumulates (w·c, w) alone and Compose outputs C0 + Σ w·c, clamped by the
//             UNORM target;
//   linear    the same in linear colour: c and C0 (display, i.e. sRGB-encoded values)
//             decoded to linear, summed, written to an R8G8B8A8_UNORM_SRGB target that
//             encodes, resolved in linear space (sRGB frame);
//   exposure  the same as additive, with 1 − exp(−Exposure · C) instead of the clamp.
#include "common.fxh"
#include "../fullscreen.hlsli"

#ifndef WBOIT_MSAA_ADDITIVE
#define WBOIT_MSAA_ADDITIVE 0
#endif
#ifndef WBOIT_MSAA_LINEAR
#define WBOIT_MSAA_LINEAR 0
#endif
#ifndef WBOIT_MSAA_EXPOSURE
#define WBOIT_MSAA_EXPOSURE 0
#endif

// The exposure variant's k in 1 − exp(−k·c), "chosen so that it is neither too light
// nor too dark" (document 001's discussion gives no value): 1.5 keeps a colour of 0.5
// at 0.53 and maps 1 to 0.78, so that sums up to about 3 stay distinguishable.
float Exposure = 1.5;

// Document 001's translucent pass tests LEQUAL (glDepthFunc(GL_LEQUAL)), never writes.
DepthStencilState DepthTestLessEqualNoWrite {
  DepthEnable = TRUE;
  DepthWriteMask = ZERO;
  DepthFunc = LESS_EQUAL;
};

// glBlendFunci(0, GL_ONE, GL_ONE) and glBlendFunci(1, GL_DST_COLOR, GL_ZERO). D3D11
// forbids colour factors for alpha: RT1's alpha factors are DEST_ALPHA/ZERO, the same
// product (R16_FLOAT has no alpha: it is never stored).
BlendState WboitMsaaAccumulate {
  BlendEnable[0] = TRUE;
  SrcBlend[0] = ONE;
  DestBlend[0] = ONE;
  BlendOp[0] = ADD;
  SrcBlendAlpha[0] = ONE;
  DestBlendAlpha[0] = ONE;
  BlendOpAlpha[0] = ADD;
  BlendEnable[1] = TRUE;
  SrcBlend[1] = DEST_COLOR;
  DestBlend[1] = ZERO;
  BlendOp[1] = ADD;
  SrcBlendAlpha[1] = DEST_ALPHA;
  DestBlendAlpha[1] = ZERO;
  BlendOpAlpha[1] = ADD;
};

// The additive variants: premultiplied colour summed with ONE/ONE into RT0 alone.
BlendState AdditiveAccumulate {
  BlendEnable[0] = TRUE;
  SrcBlend[0] = ONE;
  DestBlend[0] = ONE;
  BlendOp[0] = ADD;
  SrcBlendAlpha[0] = ONE;
  DestBlendAlpha[0] = ONE;
  BlendOpAlpha[0] = ADD;
};

// The composing passes overwrite their target.
BlendState ComposeOverwrites { BlendEnable[0] = FALSE; };

// The colour space blending happens in: display values as the scene writes them,
// or (linear) those values decoded as sRGB (the exact IEC 61966-2-1 curve, the one
// an _SRGB target encodes with).
float3 BlendSpace(float3 c) {
#if WBOIT_MSAA_LINEAR
  float3 x = saturate(c);
  return lerp(pow((x + 0.055) / 1.055, 2.4), x / 12.92, float3(x <= 0.04045));
#else
  return c;
#endif
}

// Document 001's formula (2): where Σw = 0 the opaque colour, else
// Σ(w·c)/Σw · α + C0 · (1 − α) with α = 1 − Π(1 − w).
float3 WeightedComposite(float3 opaque, float4 accum, float product) {
  if (accum.a == 0) return opaque;
  float alpha = 1.0 - product;
  return accum.rgb / accum.a * alpha + opaque * (1.0 - alpha);
}

// The additive variants: C0 + Σ w·c in the blend space, then the exposure curve
// instead of the clamp the UNORM target applies.
float3 AdditiveComposite(float3 opaque, float4 accum) {
  float3 c = BlendSpace(opaque) + accum.rgb;
#if WBOIT_MSAA_EXPOSURE
  c = 1.0 - exp(-Exposure * c);
#endif
  return c;
}

float3 Composite(float3 opaque, float4 accum, float product) {
#if WBOIT_MSAA_ADDITIVE
  return AdditiveComposite(opaque, accum);
#else
  return WeightedComposite(opaque, accum, product);
#endif
}

Texture2DMS<float4> OpaqueSamples;  // R16G16B16A16_FLOAT: C0
Texture2DMS<float4> AccumSamples;   // R16G16B16A16_FLOAT: (Σ w·c, Σ w)
Texture2DMS<float> ProductSamples;  // R16_FLOAT: Π(1 − w)

// Per sample: SV_SampleIndex runs the pass once per sample (gl_SampleID in the article).
float4 PSComposeSample(float4 pos : SV_Position, uint s : SV_SampleIndex) : SV_Target {
  int2 p = int2(pos.xy);
  float product = 1.0;
#if !WBOIT_MSAA_ADDITIVE
  product = ProductSamples.Load(p, s);
#endif
  return float4(Composite(OpaqueSamples.Load(p, s).rgb, AccumSamples.Load(p, s), product), 1.0);
}

#if !WBOIT_MSAA_ADDITIVE
Texture2D<float4> OpaquePixels;  // the samples of OpaqueSamples averaged (ResolveSubresource)
Texture2D<float4> AccumPixels;
Texture2D<float> ProductPixels;

// Per pixel, from the averaged targets: what the per-sample resolve is compared with.
float4 PSComposePixel(float4 pos : SV_Position) : SV_Target {
  int3 p = int3(pos.xy, 0);
  return float4(WeightedComposite(OpaquePixels.Load(p).rgb, AccumPixels.Load(p), ProductPixels.Load(p)), 1.0);
}
#endif

#ifdef OBJECT_VS
struct WboitMsaaOut {
  float4 accum : SV_Target0;
  float4 product : SV_Target1;
};

// The article's fragment shader: outData = (w·color, w), alpha = 1 − w, w = opacity.
WboitMsaaOut PSWboitMsaa(OBJECT_PIXEL p) {
  float3 c, t;
  float w;
  Shade(p, c, w, t);
  WboitMsaaOut o;
  o.accum = float4(w * c, w);
  o.product = (1.0 - w).xxxx;
  return o;
}

// Premultiplied colour for ONE/ONE, in the blend space.
float4 PSAdditive(OBJECT_PIXEL p) : SV_Target0 {
  float3 c, t;
  float w;
  Shade(p, c, w, t);
  return float4(w * BlendSpace(c), w);
}
#endif

#define WBOIT_MSAA_COMPOSE_PASS(name, ps)                    \
  pass name {                                                \
    SetVertexShader(CompileShader(vs_5_0, VSFullscreenTriangle()));  \
    SetGeometryShader(NULL);                                 \
    SetPixelShader(CompileShader(ps_5_0, ps()));             \
    SetBlendState(ComposeOverwrites, float4(0, 0, 0, 0), 0xFFFFFFFF); \
    SetDepthStencilState(NoDepth, 0);                        \
    SetRasterizerState(NoCull);                              \
  }

technique11 WboitMsaa {
#ifdef OBJECT_VS
#if WBOIT_MSAA_ADDITIVE
  OBJECT_PASS_DEPTH(Transparency, PSAdditive, AdditiveAccumulate, DepthTestLessEqualNoWrite)
#else
  OBJECT_PASS_DEPTH(Transparency, PSWboitMsaa, WboitMsaaAccumulate, DepthTestLessEqualNoWrite)
#endif
#endif
  WBOIT_MSAA_COMPOSE_PASS(Compose, PSComposeSample)
#if !WBOIT_MSAA_ADDITIVE
  WBOIT_MSAA_COMPOSE_PASS(ComposePerPixel, PSComposePixel)
#endif
}
