// Translucent triangle meshes (renderer/meshes.h) as a translucent object: world-space
// vertices, each with its mesh's material (front and back colour, opacity,
// transmission), lit two-sided by the scene's directional light. A transparency
// method's passes come from OIT_METHOD, the method's include
// (shaders_hlsl/oit/common.fxh gives the contract this file fulfils).
#include "oit/deferred.hlsli"

cbuffer MeshParams : register(b1) {
  float4x4 ViewProj;
  float3 LightDir;  // towards the light
  float Pad;
  float3 Eye;       // deferred shading: which side of a triangle faces the eye
  float Pad2;
};

// Raw views of the object's vertex and index buffers (R32_UINT), which deferred
// shading (ShadeTriangle) reads by triangle id. Raw: D3D11 forbids structured
// vertex or index buffers and allows raw views of them.
ByteAddressBuffer MeshVertices;  // 64-byte MeshVertex (below)
ByteAddressBuffer MeshIndices;

// Lambert with the opaque pass's ambient (scene.fx, Ambient = 0.45), so that a
// translucent surface and the backdrop behind it are lit alike.
static const float kAmbient = 0.45;

struct MeshVertex {
  float3 position : POSITION;
  float3 normal : NORMAL;
  float3 front : FRONTCOLOR;
  float3 back : BACKCOLOR;
  float opacity : OPACITY;
  float3 transmission : TRANSMISSION;
};

struct MeshVertexOut {
  float4 position : SV_Position;
  float3 normal : NORMAL;
  float3 front : FRONTCOLOR;
  float3 back : BACKCOLOR;
  float opacity : OPACITY;
  float3 transmission : TRANSMISSION;
};

// The pixel shader's input: the vertex shader's output and which side faces the eye.
struct MeshPixel {
  float4 position : SV_Position;
  float3 normal : NORMAL;
  float3 front : FRONTCOLOR;
  float3 back : BACKCOLOR;
  float opacity : OPACITY;
  float3 transmission : TRANSMISSION;
  bool isFrontFace : SV_IsFrontFace;
};

MeshVertexOut VSMesh(MeshVertex v) {
  MeshVertexOut o;
  o.position = mul(ViewProj, float4(v.position, 1));
  o.normal = v.normal;
  o.front = v.front;
  o.back = v.back;
  o.opacity = v.opacity;
  o.transmission = v.transmission;
  return o;
}

// Two-sided: the side facing the eye picks the colour, and the back side is lit
// with the normal flipped.
void Shade(MeshPixel p, out float3 c, out float a, out float3 t) {
  float3 n = normalize(p.normal);
  float3 albedo = p.front;
  if (!p.isFrontFace) {
    n = -n;
    albedo = p.back;
  }
  c = albedo * (kAmbient + (1.0 - kAmbient) * saturate(dot(n, normalize(LightDir))));
  a = p.opacity;
  t = p.transmission;
}

// Deferred shading (oit/common.fxh): one DrawIndexed, so SV_PrimitiveID numbers the triangles.
uint TriangleId(MeshPixel p, uint primitiveId) { return primitiveId; }

MeshVertexOut LoadMeshVertex(uint index) {
  uint base = index * 64;
  MeshVertexOut v;
  v.position = 0;  // not interpolated: the caller has the pixel
  v.normal = asfloat(MeshVertices.Load3(base + 12));
  v.front = asfloat(MeshVertices.Load3(base + 24));
  v.back = asfloat(MeshVertices.Load3(base + 36));
  v.opacity = asfloat(MeshVertices.Load(base + 48));
  v.transmission = asfloat(MeshVertices.Load3(base + 52));
  return v;
}

// What the rasterizer gives Shade, from the triangle and the pixel: the attributes
// interpolated with the world-space barycentrics of the point the pixel shows (what
// perspective-correct interpolation computes), and the side facing the eye, which is
// the front when the triangle is wound clockwise as the eye sees it (D3D11's default).
void ShadeTriangle(uint id, float4 position, out float3 c, out float a, out float3 t) {
  uint3 index = MeshIndices.Load3(id * 12);
  float3 p0 = asfloat(MeshVertices.Load3(index.x * 64)), p1 = asfloat(MeshVertices.Load3(index.y * 64)),
         p2 = asfloat(MeshVertices.Load3(index.z * 64));
  const float3 w = Barycentrics(p0, p1, p2, UnprojectPixel(position));
  const float w0 = w.x, w1 = w.y, w2 = w.z;
  MeshVertexOut v0 = LoadMeshVertex(index.x), v1 = LoadMeshVertex(index.y), v2 = LoadMeshVertex(index.z);
  MeshPixel p;
  p.position = position;
  p.normal = w0 * v0.normal + w1 * v1.normal + w2 * v2.normal;
  p.front = w0 * v0.front + w1 * v1.front + w2 * v2.front;
  p.back = w0 * v0.back + w1 * v1.back + w2 * v2.back;
  p.opacity = w0 * v0.opacity + w1 * v1.opacity + w2 * v2.opacity;
  p.transmission = w0 * v0.transmission + w1 * v1.transmission + w2 * v2.transmission;
  p.isFrontFace = dot(cross(p1 - p0, p2 - p0), Eye - p0) > 0;
  Shade(p, c, a, t);
}

#define OBJECT_VS VSMesh
#define OBJECT_DEFERRED 1
#define OBJECT_GS NULL
#define OBJECT_PIXEL MeshPixel

// Loaded on its own, as any FX file, the object is drawn with plain alpha blending.
#ifndef OIT_METHOD
#define OIT_METHOD "oit/alpha.fxh"
#endif
#include OIT_METHOD
