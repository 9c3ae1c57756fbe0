// The smoke and the flames of document 000 (SPEC.md) as a translucent object:
// the particles that particles.fx's update pass streams out (renderer's
// ParticleSystem), expanded by a geometry shader into camera-facing billboards
// (basis z = (E-C)/|E-C|, x = (j x z)/|j x z|, y = z x x) and shaded with a
// textured, normal-map-lit puff. A transparency method's passes come from
// OIT_METHOD, the method's include (shaders_hlsl/oit/common.fxh gives the
// contract this file fulfils).
// Flame = 1 turns the smoke colour ramp into a flame ramp; built with FIRE
// defined (the fire demo), OVER means additive blending, order-independent by
// construction, in technique Fire.
#include "particle.hlsli"
#include "oit/deferred.hlsli"

cbuffer SmokeParams : register(b1) {
  float4x4 ViewProj;
  float3 Eye;
  float Seconds;
  float3 Acceleration;
  float Size;
  float3 LightDir;  // towards the light
  float Flame;      // 0: smoke, 1: flames
};

Texture2D Puff;  // rgb: normal * 0.5 + 0.5, a: density
// A raw view of the particle buffer the frame draws (40-byte Particles), which
// deferred shading (ShadeTriangle) reads by particle index. Raw: D3D11 allows raw
// views of a stream-output and vertex buffer, not structured ones.
ByteAddressBuffer Particles;
SamplerState Linear { Filter = MIN_MAG_MIP_LINEAR; AddressU = Clamp; AddressV = Clamp; AddressW = Clamp; };

struct Center {
  float3 center : CENTER;
  float age : AGE;
  uint kind : KIND;
};

struct Billboard {
  float4 position : SV_Position;
  float2 uv : TEXCOORD0;
  float age : AGE;
  // LightDir in the billboard's basis (x, y, z): the PS lights the normal map in
  // that basis, which passes 3 values to every fragment where the basis is 9.
  nointerpolation float3 light : LIGHT;
  nointerpolation uint particle : PARTICLE;  // its index in the buffer drawn: the triangle id of deferred shading
};

Center VSSmoke(Particle p) {
  Center c;
  float t = p.seedAge.y * Seconds;
  c.center = 0.5 * t * t * Acceleration + t * p.velocity + p.origin;  // p(t) = t^2 a / 2 + t v0 + p0
  c.age = p.kindLife.y > 0 ? saturate(float(p.seedAge.y) / float(p.kindLife.y)) : 0;
  c.kind = p.kindLife.x;
  return c;
}

// The billboard's camera-facing basis and half size, and LightDir in that basis.
struct BillboardFrame {
  float3 x, y, z;
  float size;
  float3 light;
};

BillboardFrame FrameOf(Center c) {
  BillboardFrame f;
  f.z = normalize(Eye - c.center);
  f.x = normalize(cross(float3(0, 1, 0), f.z));
  f.y = cross(f.z, f.x);
  f.size = Size * (0.5 + c.age);
  float3 l = normalize(LightDir);
  f.light = float3(dot(f.x, l), dot(f.y, l), dot(f.z, l));
  return f;
}

// Vertex `corner` of the billboard: GSBillboard's triangle strip, (-1,-1), (-1,1), (1,-1), (1,1).
Billboard BillboardCorner(Center c, BillboardFrame f, uint corner, uint particle) {
  float2 xy = float2(corner & 2 ? 1 : -1, corner & 1 ? 1 : -1);
  float3 world = c.center + (xy.x * f.x + xy.y * f.y) * f.size;
  Billboard b;
  b.position = mul(ViewProj, float4(world, 1));
  b.uv = float2(xy.x, -xy.y) * 0.5 + 0.5;
  b.age = c.age;
  b.light = f.light;
  b.particle = particle;
  return b;
}

[maxvertexcount(4)]
void GSBillboard(point Center input[1], uint particle : SV_PrimitiveID, inout TriangleStream<Billboard> stream) {
  if (input[0].kind == 0) return;  // emitters are invisible
  BillboardFrame f = FrameOf(input[0]);
  for (uint i = 0; i < 4; ++i) stream.Append(BillboardCorner(input[0], f, i, particle));
}

// Colour, alpha and transmission of a fragment. Smoke: hot and bright when young,
// dark and thin when old, lit through the normal map. Flames: white-yellow core
// fading through orange to dark red, self-lit (the normal map only modulates).
// `puff` is the puff texture at the fragment's uv.
void ShadePuff(float4 puff, Billboard b, out float3 c, out float a, out float3 t) {
  float3 n = puff.rgb * 2.0 - 1.0;
  // The basis is orthonormal, so dot(normalize(basis * n), l) = dot(normalize(n), basis^T l).
  float light = saturate(dot(normalize(n), b.light)) * 0.75 + 0.3;
  if (Flame > 0.5) {
    float3 core = float3(1.0, 0.9, 0.55);
    float3 mid = float3(1.0, 0.45, 0.08);
    float3 tip = float3(0.35, 0.05, 0.02);
    float3 ramp = b.age < 0.3 ? lerp(core, mid, b.age / 0.3) : lerp(mid, tip, (b.age - 0.3) / 0.7);
    c = ramp * (0.8 + 0.2 * light);
    a = puff.a * saturate(1.0 - b.age) * 0.18;
    t = ramp;
  } else {
    float3 young = float3(1.0, 0.62, 0.22);
    float3 mid = float3(0.72, 0.72, 0.74);
    float3 old = float3(0.16, 0.17, 0.22);
    float3 ramp = b.age < 0.35 ? lerp(young, mid, b.age / 0.35) : lerp(mid, old, (b.age - 0.35) / 0.65);
    c = ramp * light;
    a = puff.a * saturate(1.0 - b.age * 0.7) * 0.8;
    t = ramp;
  }
}

void Shade(Billboard b, out float3 c, out float a, out float3 t) { ShadePuff(Puff.Sample(Linear, b.uv), b, c, a, t); }

// Deferred shading (oit/common.fxh): the GS passes the particle's index (its input
// SV_PrimitiveID: one point per particle) to every fragment of its billboard.
uint TriangleId(Billboard b, uint primitiveId) { return b.particle; }

// What GSBillboard gives Shade, from the particle and the pixel: the uv is the point
// where the eye's ray through the pixel meets the billboard's plane, projected onto
// its basis (the ray's direction comes from the unprojected pixel; intersecting the
// plane avoids the depth's precision, which 1/255 of the puff's shading needs). SampleLevel 0, not
// Sample: a resolve's neighbouring pixels shade other particles, so derivatives mean
// nothing there; the puff has one mip level, where both read the same texels.
// The particle of index `id` in the buffer the frame draws.
Center LoadCenter(uint id) {
  uint base = id * 40;
  Particle p;
  p.origin = asfloat(Particles.Load3(base));
  p.velocity = asfloat(Particles.Load3(base + 12));
  p.seedAge = Particles.Load2(base + 24);
  p.kindLife = Particles.Load2(base + 32);
  return VSSmoke(p);
}

// Shade without derivatives, for passes where neighbouring pixels shade other
// particles (a resolve, a compute tile): SampleLevel 0, not Sample; the puff has one
// mip level, where both read the same texels.
void ShadeAt(Billboard b, out float3 c, out float a, out float3 t) {
  ShadePuff(Puff.SampleLevel(Linear, b.uv, 0), b, c, a, t);
}

void ShadeTriangle(uint id, float4 position, out float3 c, out float a, out float3 t) {
  Center center = LoadCenter(id);
  BillboardFrame f = FrameOf(center);
  float3 ray = UnprojectPixel(position) - Eye;
  float3 world = Eye + ray * (dot(center.center - Eye, f.z) / dot(ray, f.z));
  float3 offset = (world - center.center) / f.size;
  Billboard b;
  b.position = position;
  b.uv = float2(dot(offset, f.x), -dot(offset, f.y)) * 0.5 + 0.5;
  b.age = center.age;
  b.light = f.light;
  b.particle = id;
  ShadeAt(b, c, a, t);
}

// Quads (oit/common.fxh), for the compute-tile methods: the strip GSBillboard emits
// for particle `id`, and its view depth (the centre's w: the sorted order's key).
bool QuadOf(uint id, out Billboard v[4], out float viewDepth) {
  Center c = LoadCenter(id);
  BillboardFrame f = FrameOf(c);
  for (uint i = 0; i < 4; ++i) v[i] = BillboardCorner(c, f, i, id);
  viewDepth = mul(ViewProj, float4(c.center, 1)).w;
  return c.kind != 0;
}

// The rasterizer's interpolation: uv with the perspective-correct weights `w` of
// the triangle a, b, c; the flat attributes (age, light, particle) from a.
Billboard InterpolateQuad(Billboard a, Billboard b, Billboard c, float3 w) {
  Billboard p = a;
  p.uv = w.x * a.uv + w.y * b.uv + w.z * c.uv;
  return p;
}

#define OBJECT_VS VSSmoke
#define OBJECT_DEFERRED 1
#define OBJECT_QUADS 1
#define OBJECT_GS CompileShader(gs_5_0, GSBillboard())
#define OBJECT_PIXEL Billboard

#ifdef FIRE
// The FIRE variant: additive (C = Cs*as + Cd).
BlendState Additive {
  BlendEnable[0] = TRUE;
  SrcBlend[0] = SRC_ALPHA;
  DestBlend[0] = ONE;
  BlendOp[0] = ADD;
  SrcBlendAlpha[0] = ZERO;
  DestBlendAlpha[0] = ONE;
  BlendOpAlpha[0] = ADD;
};
#define OVER_TECHNIQUE Fire
#define OVER_BLEND Additive
#define OBJECT_ADDITIVE 1  // the compute-tile methods' OVER: Additive's arithmetic
#endif

// Loaded on its own, as any FX file, the object is drawn with plain alpha blending.
#ifndef OIT_METHOD
#define OIT_METHOD "oit/alpha.fxh"
#endif
#include OIT_METHOD
