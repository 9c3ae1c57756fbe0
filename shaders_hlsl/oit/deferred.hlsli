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

// The world-space barycentric weights of `world`, a point on the triangle's plane,
// for vertices p0, p1, p2: what perspective-correct interpolation of the triangle's
// attributes gives at the pixel that shows `world`.
float3 Barycentrics(float3 p0, float3 p1, float3 p2, float3 world) {
  float3 n = cross(p1 - p0, p2 - p0);
  float w0 = dot(cross(p2 - p1, world - p1), n) / dot(n, n);
  float w1 = dot(cross(p0 - p2, world - p2), n) / dot(n, n);
  return float3(w0, w1, 1.0 - w0 - w1);
}

// Where the ray through the pixel centre `pixel` meets the plane of the triangle
// p0, p1, p2: the point a visibility buffer's pixel shows, without its depth.
float3 PixelOnTriangle(float2 pixel, float3 p0, float3 p1, float3 p2) {
  float3 nearPoint = UnprojectPixel(float4(pixel, 0, 1)), farPoint = UnprojectPixel(float4(pixel, 1, 1));
  float3 ray = farPoint - nearPoint, n = cross(p1 - p0, p2 - p0);
  return nearPoint + ray * (dot(p0 - nearPoint, n) / dot(ray, n));
}

#endif
