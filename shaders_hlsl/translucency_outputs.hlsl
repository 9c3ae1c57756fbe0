// Pixel-shader outputs of the translucency passes of document 000 (SPEC.md),
// shared by the smoke and the shard shaders. One function per method:
//   OVER (alpha blending and the sorted reference): straight (c, a)
//   Table 1 (WBOIT):   RT0 accum = (c*a, a)*w, RT1 revealage = a
//   Table 3 (colored): Table 1 plus RT2 (the frame) = a*(1 - t.rgb)
// with w = clamp(pow(min(1, a*10) + 0.01, 3) * 1e8 * pow(1 - z*0.9, 3), 1e-2, 3e3), z = SV_Position.z.

// pow(x, 3.0) written as x * x * x: both bases are positive, so it is the same
// function, and glslang keeps a literal pow as SPIR-V Pow, which drivers evaluate
// as exp2(3 * log2(x)) - two transcendentals per fragment (lavapipe's are long
// polynomial sequences) for what fxc emits as two multiplies.
float Cube(float x) { return x * x * x; }

float WboitWeight(float a, float z) {
  return clamp(Cube(min(1.0, a * 10.0) + 0.01) * 1e8 * Cube(1.0 - z * 0.9), 1e-2, 3e3);
}

struct WboitOut {
  float4 accum : SV_Target0;
  float4 revealage : SV_Target1;
};

struct ColoredOut {
  float4 accum : SV_Target0;
  float4 revealage : SV_Target1;
  float4 frame : SV_Target2;
};

float4 OverOutput(float3 c, float a) { return float4(c, a); }

WboitOut WboitOutput(float3 c, float a, float z) {
  WboitOut o;
  float w = WboitWeight(a, z);
  o.accum = float4(c * a, a) * w;
  o.revealage = float4(a, a, a, a);
  return o;
}

ColoredOut ColoredOutput(float3 c, float a, float3 t, float z) {
  ColoredOut o;
  float w = WboitWeight(a, z);
  o.accum = float4(c * a, a) * w;
  o.revealage = float4(a, a, a, a);
  o.frame = float4(a * (1.0 - t), a);
  return o;
}
