// The resolve of the fragment-buffer methods (prefix_sum.fxh, linked_list.fxh:
// document 004's step 5): a full-screen pass of the object's effect that, per
// pixel, gathers the pixel's stored (triangle id, depth) fragments, sorts them
// front to back (ties by triangle id: deterministic), shades each from its id
// (the object's ShadeTriangle: deferred) and composites with the object's
// per-surface model, C += T * a * SurfaceColour(c); T *= TransmissionFactor(a, t), from C = 0,
// T = 1. The output merger puts it over the opaque frame with dual-source
// blending: frame = C * ONE + frame * SRC1_COLOR (T).
//
// The including method defines, before this file, how a pixel's fragments are walked:
//   struct FragmentCursor;                      where the walk is
//   FragmentCursor FirstFragment(uint2 pixel);
//   bool AtEnd(FragmentCursor at);
//   Fragment FragmentAt(FragmentCursor at);
//   FragmentCursor NextFragment(FragmentCursor at);
#ifndef OIT_FRAGMENT_RESOLVE_FXH
#define OIT_FRAGMENT_RESOLVE_FXH
#include "../fullscreen.hlsli"

// Front to back onto the frame: frame = C + frame * T (T per channel: SV_Target1).
BlendState CompositeOverOpaque {
  BlendEnable[0] = TRUE;
  SrcBlend[0] = ONE;
  DestBlend[0] = SRC1_COLOR;
  BlendOp[0] = ADD;
  SrcBlendAlpha[0] = ZERO;
  DestBlendAlpha[0] = ONE;
  BlendOpAlpha[0] = ADD;
};

#ifdef OBJECT_VS
#if !OBJECT_DEFERRED
#error this method shades in its resolve: the object must define OBJECT_DEFERRED, TriangleId and ShadeTriangle (oit/common.fxh)
#endif

// The nearest fragments not yet composited are sorted in registers this many at a
// time: one walk of the pixel's fragments per batch, so exact at any depth (a pixel of
// n fragments takes ceil((n + 1) / 32) walks; lavapipe caps a loop at 65535 turns,
// which one walk of a deep pixel stays far below).
static const uint kBatch = 32;

bool Nearer(Fragment a, Fragment b) { return a.depth < b.depth || (a.depth == b.depth && a.id < b.id); }

void CompositeFragment(Fragment f, float2 pixelCentre, inout float3 C, inout float3 T) {
  float3 c, t;
  float a;
  ShadeTriangle(f.id, float4(pixelCentre, f.depth, 1), c, a, t);
  C += T * a * SurfaceColour(c);
  T *= TransmissionFactor(a, t);
}

struct ResolveOut {
  float4 color : SV_Target0;         // C
  float4 transmission : SV_Target1;  // T: the blend's SRC1_COLOR
};

ResolveOut PSResolve(float4 position : SV_Position) {
  uint2 pixel = uint2(position.xy);
  float3 C = 0, T = 1;
  Fragment batch[kBatch];
  Fragment last = (Fragment)0;  // the farthest fragment composited so far
  bool started = false;
  uint kept;
  do {
    // The kBatch nearest fragments behind `last`, in order (insertion into a sorted batch).
    kept = 0;
    for (FragmentCursor at = FirstFragment(pixel); !AtEnd(at); at = NextFragment(at)) {
      Fragment f = FragmentAt(at);
      if (started && !Nearer(last, f)) continue;  // composited in an earlier batch
      if (kept == kBatch && !Nearer(f, batch[kBatch - 1])) continue;
      uint j = min(kept, kBatch - 1);
      for (; j > 0 && Nearer(f, batch[j - 1]); --j) batch[j] = batch[j - 1];
      batch[j] = f;
      kept = min(kept + 1, kBatch);
    }
    for (uint i = 0; i < kept; ++i) CompositeFragment(batch[i], position.xy, C, T);
    if (kept > 0) {
      last = batch[kept - 1];
      started = true;
    }
  } while (kept == kBatch);
  if (!started) discard;
  ResolveOut o;
  o.color = float4(C, 0);
  o.transmission = float4(T, 1);
  return o;
}

#define FRAGMENT_RESOLVE_PASS                                  \
  pass Resolve {                                              \
    SetVertexShader(CompileShader(vs_5_0, VSFullscreenTriangle()));      \
    SetGeometryShader(NULL);                                  \
    SetPixelShader(CompileShader(ps_5_0, PSResolve()));       \
    SetBlendState(CompositeOverOpaque, float4(0, 0, 0, 0), 0xFFFFFFFF); \
    SetDepthStencilState(NoDepth, 0);                         \
    SetRasterizerState(NoCull);                               \
  }

// An object pass of a fragment-buffer method: the pixel shader `ps` writes only UAVs
// (no render target), after the depth test against the opaque depth
// ([earlydepthstencil] in `ps`: a hidden fragment neither runs it nor counts).
#define FRAGMENT_PASS(name, ps)                              \
  pass name {                                                \
    SetVertexShader(CompileShader(vs_5_0, OBJECT_VS()));     \
    SetGeometryShader(OBJECT_GS);                            \
    SetPixelShader(CompileShader(ps_5_0, ps()));             \
    SetBlendState(NULL, float4(0, 0, 0, 0), 0xFFFFFFFF);     \
    SetDepthStencilState(DepthTestNoWrite, 0);               \
    SetRasterizerState(NoCull);                              \
  }
#endif

#endif
