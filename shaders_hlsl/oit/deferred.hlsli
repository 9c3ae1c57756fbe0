// What an object that supports deferred shading (OBJECT_DEFERRED, oit/common.fxh)
// includes before its ShadeTriangle: the frame's inverse view-projection and size,
// which the object sets in its Draw and DrawFullscreen, and the unprojection of a
// pixel back to the world point it shows.
#ifndef OIT_DEFERRED_HLSLI
#define OIT_DEFERRED_HLSLI

cbuffer DeferredFrame : register(b2) {
  float4x4 InvViewProj;  // world = InvViewProj * clip (then / w)
  float2 FrameSize;      // pixels: the viewport the frame is rendered with (origin 0, 0)
  float2 DeferredPad;
};

// The world position of the surface point seen at `position` (as SV_Position: the
// pixel centre in xy, the fragment's depth in z), through the D3D11 viewport
// transform (y down) and the inverse view-projection.
float3 UnprojectPixel(float4 position) {
  float2 ndc = float2(position.x / FrameSize.x * 2.0 - 1.0, 1.0 - position.y / FrameSize.y * 2.0);
  float4 world = mul(InvViewProj, float4(ndc, position.z, 1.0));
  return world.xyz / world.w;
}

#endif
