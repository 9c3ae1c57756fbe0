// Glass shards of document 000, hardware-instanced: one shard mesh (slot 0,
// per vertex) and per-instance data (slot 1, INPUT_PER_INSTANCE_DATA): the world
// matrix as four float4 columns WORLD0..3 and a tint (rgb transmission, a alpha).
#include "oit/deferred.hlsli"

cbuffer ShardParams : register(b1) {
  float4x4 ViewProj;
  float3 Eye;
  float SurfaceTint;  // 0: the surface reflects neutral light; 1: it shows the tint
  float3 LightDir;
  uint TrianglesPerShard;  // of the shard mesh: triangle ids are instance * TrianglesPerShard + SV_PrimitiveID
};

// Raw views (ByteAddressBuffer) of the object's own buffers, which deferred shading
// (ShadeTriangle) reads by triangle id. Raw, not structured: D3D11 forbids a
// structured buffer that is also a vertex or index buffer, and allows raw views of one.
ByteAddressBuffer ShardVertices;   // the vertex buffer: float3 position, float3 normal (24 bytes)
ByteAddressBuffer ShardIndices;    // the index buffer, R16_UINT
ByteAddressBuffer ShardInstances;  // the instance buffer: float4 world columns [4], float4 tint (80 bytes)

struct ShardVertex {
  float3 position : POSITION;
  float3 normal : NORMAL;
  float4 world0 : WORLD0;
  float4 world1 : WORLD1;
  float4 world2 : WORLD2;
  float4 world3 : WORLD3;
  float4 tint : TINT;
  uint instance : SV_InstanceID;
};

struct ShardPixel {
  float4 position : SV_Position;
  float3 normal : NORMAL;
  float3 toEye : TOEYE;
  float4 tint : TINT;
  nointerpolation uint instance : INSTANCE;
};

ShardPixel VSShard(ShardVertex v) {
  ShardPixel o;
  float3 world = v.world0.xyz * v.position.x + v.world1.xyz * v.position.y + v.world2.xyz * v.position.z + v.world3.xyz;
  o.position = mul(ViewProj, float4(world, 1));
  o.normal = v.world0.xyz * v.normal.x + v.world1.xyz * v.normal.y + v.world2.xyz * v.normal.z;
  o.toEye = Eye - world;
  o.tint = v.tint;
  o.instance = v.instance;
  return o;
}

void Shade(ShardPixel p, out float3 c, out float a, out float3 t) {
  float3 n = normalize(p.normal);
  float3 v = normalize(p.toEye);
  if (dot(n, v) < 0) n = -n;  // two-sided glass
  float3 l = normalize(LightDir);
  float3 h = normalize(l + v);
  float spec = pow(saturate(dot(n, h)), 40.0);
  float fresnel = 0.15 + 0.85 * pow(1.0 - saturate(dot(n, v)), 4.0);
  float3 surface = lerp(float3(0.8, 0.8, 0.8), p.tint.rgb, SurfaceTint);
  c = surface * (0.35 + 0.45 * saturate(dot(n, l))) + spec;
  a = saturate(p.tint.a + 0.4 * fresnel);
  t = p.tint.rgb;
}

// Deferred shading (oit/common.fxh): D3D11 restarts SV_PrimitiveID at 0 for each
// instance, so the id counts the instance's triangles before it.
uint TriangleId(ShardPixel p, uint primitiveId) { return p.instance * TrianglesPerShard + primitiveId; }

uint ShardIndex(uint i) {
  uint word = ShardIndices.Load((i * 2) & ~3u);  // two R16 indices a word, little-endian
  return (i & 1) ? word >> 16 : word & 0xFFFF;
}

// What VSShard gives Shade, from the triangle id and the pixel: the shards are flat
// shaded (every vertex of a triangle carries its face normal), and the direction to
// the eye comes from the world point the pixel shows.
void ShadeTriangle(uint id, float4 position, out float3 c, out float a, out float3 t) {
  uint instance = id / TrianglesPerShard;
  uint vertex = ShardIndex((id % TrianglesPerShard) * 3);
  float3 normal = asfloat(ShardVertices.Load3(vertex * 24 + 12));
  uint base = instance * 80;
  float3 world0 = asfloat(ShardInstances.Load3(base)), world1 = asfloat(ShardInstances.Load3(base + 16)),
         world2 = asfloat(ShardInstances.Load3(base + 32));
  ShardPixel p;
  p.position = position;
  p.normal = world0 * normal.x + world1 * normal.y + world2 * normal.z;
  p.toEye = Eye - UnprojectPixel(position);
  p.tint = asfloat(ShardInstances.Load4(base + 64));
  p.instance = instance;
  Shade(p, c, a, t);
}
