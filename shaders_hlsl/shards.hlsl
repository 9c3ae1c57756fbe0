// Glass shards of document 000, hardware-instanced: one shard mesh (slot 0,
// per vertex) and per-instance data (slot 1, INPUT_PER_INSTANCE_DATA): the world
// matrix as four float4 columns WORLD0..3 and a tint (rgb transmission, a alpha).

cbuffer ShardParams : register(b1) {
  float4x4 ViewProj;
  float3 Eye;
  float SurfaceTint;  // 0: the surface reflects neutral light; 1: it shows the tint
  float3 LightDir;
  float Pad;
};

struct ShardVertex {
  float3 position : POSITION;
  float3 normal : NORMAL;
  float4 world0 : WORLD0;
  float4 world1 : WORLD1;
  float4 world2 : WORLD2;
  float4 world3 : WORLD3;
  float4 tint : TINT;
};

struct ShardPixel {
  float4 position : SV_Position;
  float3 normal : NORMAL;
  float3 toEye : TOEYE;
  float4 tint : TINT;
};

ShardPixel VSShard(ShardVertex v) {
  ShardPixel o;
  float3 world = v.world0.xyz * v.position.x + v.world1.xyz * v.position.y + v.world2.xyz * v.position.z + v.world3.xyz;
  o.position = mul(ViewProj, float4(world, 1));
  o.normal = v.world0.xyz * v.normal.x + v.world1.xyz * v.normal.y + v.world2.xyz * v.normal.z;
  o.toEye = Eye - world;
  o.tint = v.tint;
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
