// The draw pass of the GPU particle system (document 000): each particle
// becomes a camera-facing billboard textured with a smoke puff.
#include "particle.hlsli"

cbuffer DrawParams : register(b1) {
  float4x4 ViewProj;
  float3 Eye;
  float Seconds;        // seconds per update
  float3 Acceleration;  // a of p(t) = 1/2 t^2 a + t v0 + p0
  float Size;
};

Texture2D Puff : register(t0);
SamplerState Linear : register(s0);

struct Billboard {
  float4 position : SV_Position;
  float2 uv : TEXCOORD0;
  float alpha : ALPHA;
};

struct Center {
  float3 center : CENTER;
  float age : AGE;      // 0..1 of its life
  uint kind : KIND;
};

Center VSParticle(Particle p) {
  Center c;
  float t = p.seedAge.y * Seconds;
  c.center = 0.5 * t * t * Acceleration + t * p.velocity + p.origin;
  c.age = p.kindLife.y > 0 ? float(p.seedAge.y) / float(p.kindLife.y) : 0;
  c.kind = p.kindLife.x;
  return c;
}

// Expands a point into a quad facing the eye: z = (E-C)/|E-C|, x = (j x z)/|j x z|, y = z x x.
[maxvertexcount(4)]
void GSBillboard(point Center input[1], inout TriangleStream<Billboard> stream) {
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
    b.uv = corners[i] * 0.5 + 0.5;
    b.alpha = saturate(1 - input[0].age) * 0.6;
    stream.Append(b);
  }
}

float4 PSSmoke(Billboard b) : SV_Target {
  float4 puff = Puff.Sample(Linear, b.uv);
  return float4(puff.rgb, puff.a * b.alpha);
}
