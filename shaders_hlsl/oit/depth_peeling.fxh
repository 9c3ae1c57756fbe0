// Depth peeling (document 002, Everitt; SPEC.md 002): one geometry pass per depth
// layer, each keeping the nearest fragment behind the layer before it, then the
// layers composited over the frame, back to front, one full-screen pass each.
// Render-target slots:
//   pass PeelNearest (layer 0) and Peel (layers 1..N-1):
//       RT0 colour layer k (a slice of an R16G16B16A16_FLOAT array, cleared (0,0,0,0)):
//           (a * c, a), premultiplied;
//       RT1 opacity layer k (a slice of an R16G16B16A16_FLOAT array, cleared
//           (0,0,0,0)): (1 - TransmissionFactor(a, t), 1), the 1 marking a fragment.
//           One minus the transmission, as dual depth peeling keeps it: a half float
//           holds a faint surface's transmission (0.999) only to 2^-11, and over 189
//           layers of fire those roundings, all alike, shift the product by 4/255;
//           its opacity (0.001) it holds to 2^-21.
//       depth: the layer's own D32_FLOAT buffer (an R32_TYPELESS texture), filled
//           with the opaque depth before the pass, tested LESS and written: the
//           opaque geometry bounds every layer, and the nearest fragment wins.
//   pass LoadFrame: RT0 the composite (R32G32B32A32_FLOAT) = the opaque frame
//       (float_composite.hlsli says why).
//   pass Composite (once per layer, N-1 first): RT0 the composite, dual-source
//       blended; pixels without a fragment in the layer are discarded, so that an
//       occlusion query around the pass counts the layer's pixels.
//   pass StoreFrame: RT0 the frame (R8G8B8A8_UNORM) = the composite, rounded once.
//   pass ShowLayer: RT0 the frame, overwritten with one layer over neutral grey.
//
// The invariance problem: Peel compares the fragment's depth with the depth pass
// k-1 stored for the same pixel, so both must come out of the same computation:
// every peeling pass runs the object's vertex (and geometry) shader, rasterizer
// state and viewport unchanged, and the D32_FLOAT buffer stores SV_Position.z as
// the pixel shader sees it, bit for bit. Peel's pixel shader discards, so it must
// not be [earlydepthstencil]: an early depth write would store the depth of
// fragments that the peeling test then throws away.
#include "common.fxh"
#include "../fullscreen.hlsli"
#include "float_composite.hlsli"

// Pass k >= 1 keeps only what lies strictly behind layer k-1: the paper's second,
// read-only depth test ("depth unit 0", GREATER), done in the pixel shader.
Texture2D<float> PreviousLayerDepth;  // R32_FLOAT view of the depth pass k-1 stored

// The composite and ShowLayer read one layer.
Texture2DArray<float4> ColourLayers;        // (a * c, a) per layer
Texture2DArray<float4> OpacityLayers;       // (1 - TransmissionFactor(a, t), 1 where a fragment is) per layer
uint Layer;                                 // the layer they read

// The nearest fragment wins and its depth is kept for the next pass.
DepthStencilState PeelDepth { DepthEnable = TRUE; DepthWriteMask = ALL; DepthFunc = LESS; };

// The layer targets take the layer's values as they are.
BlendState NoBlend { BlendEnable[0] = FALSE; BlendEnable[1] = FALSE; };

// frame = a c + T * frame, per channel: a c in SV_Target0, T in SV_Target1
// (dual-source blending: T is a colour, not one alpha); the frame's alpha is kept.
BlendState OverFrame {
  BlendEnable[0] = TRUE;
  SrcBlend[0] = ONE;
  DestBlend[0] = SRC1_COLOR;
  BlendOp[0] = ADD;
  SrcBlendAlpha[0] = ZERO;
  DestBlendAlpha[0] = ONE;
  BlendOpAlpha[0] = ADD;
};

struct LayerOut {
  float4 colour : SV_Target0;
  float4 transmission : SV_Target1;  // Peel: the opacity layer; Composite: the blend's SRC1_COLOR
};

#ifdef OBJECT_VS
// A fragment with a = 0 is no surface: it adds no colour and dims nothing
// (TransmissionFactor(0, t) = 1), so it takes no layer (the smoke's billboard
// corners would otherwise fill the layers). Shaded before any discard, while the
// whole quad runs: the object may sample with derivatives. The colour is the
// exact methods' SurfaceColour (common.fxh).
LayerOut ShadeLayer(OBJECT_PIXEL p) {
  float3 c, t;
  float a;
  Shade(p, c, a, t);
  if (a == 0) discard;
  LayerOut o;
  o.colour = float4(a * SurfaceColour(c), a);
  o.transmission = float4(1.0 - TransmissionFactor(a, t), 1);
  return o;
}

// Layer 0: the ordinary depth test alone.
LayerOut PSPeelNearest(OBJECT_PIXEL p) { return ShadeLayer(p); }

// Layers 1..N-1: what the previous layer already holds, or what lies in front of
// it, is discarded; of the rest, the depth test keeps the nearest.
LayerOut PSPeel(OBJECT_PIXEL p) {
  LayerOut o = ShadeLayer(p);
  if (p.position.z <= PreviousLayerDepth.Load(int3(p.position.xy, 0))) discard;
  return o;
}

#define PEEL_PASS(name, ps)                                  \
  pass name {                                                \
    SetVertexShader(CompileShader(vs_5_0, OBJECT_VS()));     \
    SetGeometryShader(OBJECT_GS);                            \
    SetPixelShader(CompileShader(ps_5_0, ps()));             \
    SetBlendState(NoBlend, float4(0, 0, 0, 0), 0xFFFFFFFF);  \
    SetDepthStencilState(PeelDepth, 0);                      \
    SetRasterizerState(NoCull);                              \
  }
#endif

// Layer `Layer` over the frame: frame = a c + T * frame. The C++ applies it to the
// layers back to front, the paper's order (its SRC_ALPHA, INV_SRC_ALPHA), each layer
// over everything behind it. Front to back with the under operator (C += T a c;
// T *= TransmissionFactor, then frame = C + T * frame) composes the same per-pixel
// maps in the other order of association and gives the same result; it needs the
// running T kept per channel beside the frame, which back to front does not.
LayerOut PSComposite(float4 pos : SV_Position) {
  int4 at = int4(pos.xy, Layer, 0);
  float4 opacity = OpacityLayers.Load(at);
  if (opacity.a == 0) discard;  // no fragment: nothing to add, and not counted
  LayerOut o;
  o.colour = float4(ColourLayers.Load(at).rgb, 0);
  o.transmission = float4(1.0 - opacity.rgb, 1);
  return o;
}

// One layer alone, over neutral grey (0.5): what `replay --layer K` writes.
float4 PSShowLayer(float4 pos : SV_Position) : SV_Target {
  int4 at = int4(pos.xy, Layer, 0);
  float3 grey = 0.5;
  return float4(ColourLayers.Load(at).rgb + (1.0 - OpacityLayers.Load(at).rgb) * grey, 1);
}

#define FULLSCREEN_PASS(name, ps, blend)                          \
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
technique11 DepthPeeling {
#ifdef OBJECT_VS
  PEEL_PASS(PeelNearest, PSPeelNearest)
  PEEL_PASS(Peel, PSPeel)
#endif
  FULLSCREEN_PASS(LoadFrame, PSCopy, NoBlend)
  FULLSCREEN_PASS(Composite, PSComposite, OverFrame)
  FULLSCREEN_PASS(StoreFrame, PSCopy, NoBlend)
  FULLSCREEN_PASS(ShowLayer, PSShowLayer, NoBlend)
}
