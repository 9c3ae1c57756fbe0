// The resolve of the fragment-buffer methods (prefix_sum.fxh, linked_list.fxh:
// document 004's step 5): a full-screen pass of the object's effect that, per
// pixel, gathers the pixel's stored (triangle id, depth) fragments, sorts them
// front to back (ties by triangle id: deterministic), shades each from its id
// (the object's ShadeTriangle: deferred) and composites with the object's
// per-surface model, C += T * a * c; T *= TransmissionFactor(a, t), from C = 0,
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

// A pixel's fragments up to this many are sorted in registers; deeper pixels are
// walked once per fragment, picking the next nearest each time (exact at any depth).
static const uint kFragmentsSortedInRegisters = 32;

bool Nearer(Fragment a, Fragment b) { return a.depth < b.depth || (a.depth == b.depth && a.id < b.id); }

void CompositeFragment(Fragment f, float2 pixelCentre, inout float3 C, inout float3 T) {
  float3 c, t;
  float a;
  ShadeTriangle(f.id, float4(pixelCentre, f.depth, 1), c, a, t);
  C += T * a * c;
  T *= TransmissionFactor(a, t);
}

float4 VSResolve(uint id : SV_VertexID) : SV_Position {
  float2 uv = float2((id << 1) & 2, id & 2);
  return float4(uv * float2(2, -2) + float2(-1, 1), 0, 1);
}

struct ResolveOut {
  float4 color : SV_Target0;         // C
  float4 transmission : SV_Target1;  // T: the blend's SRC1_COLOR
};

ResolveOut PSResolve(float4 position : SV_Position) {
  uint2 pixel = uint2(position.xy);
  Fragment sorted[kFragmentsSortedInRegisters];
  uint count = 0;
  for (FragmentCursor at = FirstFragment(pixel); !AtEnd(at); at = NextFragment(at)) {
    if (count < kFragmentsSortedInRegisters) sorted[count] = FragmentAt(at);
    ++count;
  }
  if (count == 0) discard;
  float3 C = 0, T = 1;
  if (count <= kFragmentsSortedInRegisters) {
    for (uint i = 1; i < count; ++i)  // insertion sort, nearest first
      for (uint j = i; j > 0 && Nearer(sorted[j], sorted[j - 1]); --j) {
        Fragment f = sorted[j];
        sorted[j] = sorted[j - 1];
        sorted[j - 1] = f;
      }
    for (uint k = 0; k < count; ++k) CompositeFragment(sorted[k], position.xy, C, T);
  } else {
    Fragment previous = (Fragment)0;
    for (uint k = 0; k < count; ++k) {
      Fragment next = (Fragment)0;
      bool found = false;
      for (FragmentCursor at = FirstFragment(pixel); !AtEnd(at); at = NextFragment(at)) {
        Fragment f = FragmentAt(at);
        if ((k == 0 || Nearer(previous, f)) && (!found || Nearer(f, next))) {
          next = f;
          found = true;
        }
      }
      CompositeFragment(next, position.xy, C, T);
      previous = next;
    }
  }
  ResolveOut o;
  o.color = float4(C, 0);
  o.transmission = float4(T, 1);
  return o;
}

#define FRAGMENT_RESOLVE_PASS                                  \
  pass Resolve {                                              \
    SetVertexShader(CompileShader(vs_5_0, VSResolve()));      \
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
