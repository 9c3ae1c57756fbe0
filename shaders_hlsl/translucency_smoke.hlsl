// Smoke billboards of document 000 for the translucency passes: the particle
// buffer of renderer::ParticleSystem (stream-out ping-pong, drawn with DrawAuto
// or, for the sorted reference, a CPU-sorted copy drawn with Draw), expanded by
// the GS into camera-facing quads (z = (E-C)/|E-C|, x = (j x z)/|j x z|, y = z x x),
// textured with a puff whose RGB is a generated normal map lit by a directional light.
#include "particle.hlsli"
#include "translucency_outputs.hlsl"

cbuffer SmokeParams : register(b1) {
  float4x4 ViewProj;
  float3 Eye;
  float Seconds;
  float3 Acceleration;
  float Size;
  float3 LightDir;  // towards the light
  float Pad;
};

Texture2D Puff : register(t0);  // rgb: normal * 0.5 + 0.5, a: density
SamplerState Linear : register(s0);

struct Center {
  float3 center : CENTER;
  float age : AGE;
  uint kind : KIND;
};

struct Billboard {
  float4 position : SV_Position;
  float2 uv : TEXCOORD0;
  float age : AGE;
  float3 bx : BASISX;
  float3 by : BASISY;
  float3 bz : BASISZ;
};

Center VSSmoke(Particle p) {
  Center c;
  float t = p.seedAge.y * Seconds;
  c.center = 0.5 * t * t * Acceleration + t * p.velocity + p.origin;
  c.age = p.kindLife.y > 0 ? saturate(float(p.seedAge.y) / float(p.kindLife.y)) : 0;
  c.kind = p.kindLife.x;
  return c;
}

[maxvertexcount(4)]
void GSSmoke(point Center input[1], inout TriangleStream<Billboard> stream) {
  if (input[0].kind == 0) return;  // emitters are invisible
  float3 z = normalize(Eye - input[0].center);
  float3 x = normalize(cross(float3(0, 1, 0), z));
  float3 y = cross(z, x);
  float size = Size * (0.5 + input[0].age);
  float2 corners[4] = {float2(-1, -1), float2(-1, 1), float2(1, -1), float2(1, 1)};
  for (uint i = 0; i < 4; ++i) {
    Billboard b;
    float3 world = input[0].center + (corners[i].x * x + corners[i].y * y) * size;
    b.position = mul(ViewProj, float4(world, 1));
    b.uv = float2(corners[i].x, -corners[i].y) * 0.5 + 0.5;
    b.age = input[0].age;
    b.bx = x;
    b.by = y;
    b.bz = z;
    stream.Append(b);
  }
}

// Colour, alpha and transmission of a smoke fragment: hot and bright when young,
// dark and thin when old, lit through the normal map.
void Shade(Billboard b, out float3 c, out float a, out float3 t) {
  float4 puff = Puff.Sample(Linear, b.uv);
  float3 n = puff.rgb * 2.0 - 1.0;
  float3 nw = normalize(b.bx * n.x + b.by * n.y + b.bz * n.z);
  float light = saturate(dot(nw, normalize(LightDir))) * 0.75 + 0.3;
  float3 young = float3(1.0, 0.62, 0.22);
  float3 mid = float3(0.72, 0.72, 0.74);
  float3 old = float3(0.16, 0.17, 0.22);
  float3 ramp = b.age < 0.35 ? lerp(young, mid, b.age / 0.35) : lerp(mid, old, (b.age - 0.35) / 0.65);
  c = ramp * light;
  a = puff.a * saturate(1.0 - b.age * 0.7) * 0.8;
  t = ramp;
}

float4 PSSmokeOver(Billboard b) : SV_Target {
  float3 c, t;
  float a;
  Shade(b, c, a, t);
  return OverOutput(c, a);
}

WboitOut PSSmokeWboit(Billboard b) {
  float3 c, t;
  float a;
  Shade(b, c, a, t);
  return WboitOutput(c, a, b.position.z);
}

ColoredOut PSSmokeColored(Billboard b) {
  float3 c, t;
  float a;
  Shade(b, c, a, t);
  return ColoredOutput(c, a, t, b.position.z);
}
