// The GPU particle system of document 000 as one effect: technique Update
// streams the particles out through a geometry shader (nothing rasterized),
// technique Alpha expands them into alpha-blended billboards. Both geometry
// shaders live here although glslang 12 crashes on a source holding a
// PointStream GS and a TriangleStream GS: the effect runtime blanks the other
// stream-type GS before compiling each entry.
#include "particle.hlsli"
#include "particle_rule.hlsli"

cbuffer UpdateParams : register(b0) {
  uint Frame;              // index of this update, from 1
  uint SpawnPerFrame = 10; // children per emitter per update
  uint MinLife = 50;
  uint LifeRange = 100;
  float3 Spread = float3(1, 1, 1);  // random initial velocity range
  float SpeedUp = 2;                // initial upward speed
};

cbuffer DrawParams : register(b1) {
  float4x4 ViewProj;
  float3 Eye;
  float Seconds = 0.016;  // seconds per update
  float3 Acceleration = float3(0, -0.5, 0);
  float Size = 0.05;
};

Texture2D Puff;
SamplerState Linear { Filter = MIN_MAG_MIP_LINEAR; AddressU = Clamp; AddressV = Clamp; };

// NoDepth, DepthTestNoWrite and NoCull (billboards face the eye either way round).
#include "oit/common.fxh"

// ---------------------------------------------------------------------------
// Update

#include "particle_update.hlsli"

// ---------------------------------------------------------------------------
// Draw

struct Billboard {
  float4 position : SV_Position;
  float2 uv : TEXCOORD0;
  float alpha : ALPHA;
};

struct Center {
  float3 center : CENTER;
  float age : AGE;  // 0..1 of its life
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

// The billboards as a translucent object of the transparency methods (oit/common.fxh).
void Shade(Billboard b, out float3 c, out float a, out float3 t) {
  float4 puff = Puff.Sample(Linear, b.uv);
  c = puff.rgb;
  a = puff.a * b.alpha;
  t = c;
}

technique11 Update {
  pass StreamOut {
    SetVertexShader(CompileShader(vs_5_0, VSPassThrough()));
    SetGeometryShader(ConstructGSWithSO(CompileShader(gs_5_0, GSUpdate()),
                                        "ORIGIN.xyz; VELOCITY.xyz; SEEDAGE.xy; KINDLIFE.xy"));
    SetPixelShader(NULL);
    SetDepthStencilState(NoDepth, 0);
  }
}

// The draw pass: technique Alpha, pass Transparency, plain alpha blending (OVER), depth
// tested and not written, no culling.
#define OBJECT_VS VSParticle
#define OBJECT_GS CompileShader(gs_5_0, GSBillboard())
#define OBJECT_PIXEL Billboard
#include "oit/alpha.fxh"
