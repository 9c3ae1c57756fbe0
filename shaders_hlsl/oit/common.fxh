// What every transparency method's include (shaders_hlsl/oit/<method>.fxh) shares:
// the depth and rasterizer states of document 000's passes and the object pass.
//
// A method's effect for an object is the object's shader file built with the
// define OIT_METHOD="oit/<method>.fxh" (renderer/oit/method.h loads it); the
// object file defines, before it includes OIT_METHOD:
//   OBJECT_VS     its vertex shader's entry point
//   OBJECT_GS     its geometry shader: NULL or CompileShader(gs_5_0, <entry>())
//   OBJECT_PIXEL  the pixel shader's input struct, with `float4 position : SV_Position`
//   void Shade(OBJECT_PIXEL p, out float3 c, out float a, out float3 t)
//                 colour, opacity and transmission of a fragment.
// and, when its surfaces filter the light they let through by colour (the glass
// shards of document 000), OBJECT_COLORED_TRANSMISSION 1.
// Deferred shading, which the fragment-buffer methods (prefix_sum.fxh,
// linked_list.fxh: document 004) need: they store a (triangle id, depth) per
// fragment and shade only in their resolve, a full-screen pass of the object's
// effect. Such an object defines OBJECT_DEFERRED 1 and provides
//   uint TriangleId(OBJECT_PIXEL p, uint primitiveId)
//                 an id unique within the object for the fragment's triangle
//                 (primitiveId: the pixel shader's SV_PrimitiveID), e.g. instance
//                 * triangles per instance + SV_PrimitiveID, or a particle's index
//                 passed on by the geometry shader;
//   void ShadeTriangle(uint id, float4 position, out float3 c, out float a, out float3 t)
//                 what Shade gives the fragment of triangle `id` at `position` (as
//                 SV_Position: the pixel centre in xy, the fragment's depth in z),
//                 equal to it within 1/255 (tests/replay/fragment_buffer_test.cpp):
//                 it rebuilds Shade's input from the object's buffers (raw views
//                 the object binds) and the world point the pixel shows
//                 (UnprojectPixel, oit/deferred.hlsli, which the object includes).
// The deferred passes draw the object in submission order: the ids refer to its
// buffers as drawn then.
// Quads, which the compute-tile methods (compute_tiles.fxh) need: they bin and shade
// the object's primitives in compute shaders, with no rasterizer. Such an object
// (camera-facing billboards: the particles) defines OBJECT_QUADS 1 and provides
//   bool QuadOf(uint id, out OBJECT_PIXEL v[4], out float viewDepth)
//                 the four vertices (a triangle strip, SV_Position in clip space) its
//                 geometry shader emits for primitive `id` of the buffer drawn, and the
//                 view depth the sorted order uses; false when it emits none;
//   OBJECT_PIXEL InterpolateQuad(OBJECT_PIXEL a, OBJECT_PIXEL b, OBJECT_PIXEL c, float3 w)
//                 the rasterizer's interpolation of the triangle a, b, c's attributes
//                 with the perspective-correct weights w (flat ones from a);
//   void ShadeAt(OBJECT_PIXEL p, out float3 c, out float a, out float3 t)
//                 Shade without derivatives (SampleLevel), for compute;
// and OBJECT_ADDITIVE 1 where its OVER is additive (the fire).
// A method's technique holds every pass of the method, as an FX11 technique
// does; a method's own passes (those that draw no object, such as composing)
// are also built from the same include without an object (oit/method.fx):
// OBJECT_VS is then undefined.
#ifndef OIT_COMMON_FXH
#define OIT_COMMON_FXH

// Translucent surfaces are tested against the opaque depth but never write it;
// the composing pass uses no depth.
DepthStencilState DepthTestNoWrite { DepthEnable = TRUE; DepthWriteMask = ZERO; DepthFunc = LESS; };
DepthStencilState NoDepth { DepthEnable = FALSE; DepthWriteMask = ZERO; };
RasterizerState NoCull { CullMode = NONE; };

#ifndef OBJECT_COLORED_TRANSMISSION
#define OBJECT_COLORED_TRANSMISSION 0
#endif

// The colour a surface adds in the exact methods (depth peeling, dual depth peeling,
// the fragment buffers): c saturated, as D3D11 clamps OVER's source to the
// R8G8B8A8_UNORM frame's range on its way into the blender in `sorted`, so that
// highlights brighter than 1 (the shards' specular) weigh alike in every exact method.
float3 SurfaceColour(float3 c) { return saturate(c); }

// What a surface lets through of the light behind it, per channel: 1 - a for
// plain translucency (OVER), 1 - a (1 - t) for coloured transmission, the
// per-surface model colored blended OIT (Table 3) approximates. Exact methods
// composite front to back with it: C += T * a * SurfaceColour(c); T *= TransmissionFactor(a, t).
float3 TransmissionFactor(float a, float3 t) {
#if OBJECT_COLORED_TRANSMISSION
  return 1.0 - a * (1.0 - t);
#else
  return (1.0 - a).xxx;
#endif
}

// The pass that draws the object with the pixel shader `ps` and the blend state
// `blend`, depth-tested with `depth` (OBJECT_PASS: DepthTestNoWrite).
#define OBJECT_PASS_DEPTH(name, ps, blend, depth)            \
  pass name {                                                \
    SetVertexShader(CompileShader(vs_5_0, OBJECT_VS()));     \
    SetGeometryShader(OBJECT_GS);                            \
    SetPixelShader(CompileShader(ps_5_0, ps()));             \
    SetBlendState(blend, float4(0, 0, 0, 0), 0xFFFFFFFF);    \
    SetDepthStencilState(depth, 0);                          \
    SetRasterizerState(NoCull);                              \
  }
#define OBJECT_PASS(name, ps, blend) OBJECT_PASS_DEPTH(name, ps, blend, DepthTestNoWrite)

#endif
