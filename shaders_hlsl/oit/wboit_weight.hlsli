// The WBOIT weight of document 000's Table 1 (SPEC.md), written once: every
// effect, test shader and CPU model that needs it includes or evaluates this file.
//   w = clamp(pow(min(1, a*10) + 0.01, 3) * 1e8 * pow(1 - z*0.9, 3), 1e-2, 3e3),
// a the fragment's opacity, z = SV_Position.z.
#ifndef OIT_WBOIT_WEIGHT_HLSLI
#define OIT_WBOIT_WEIGHT_HLSLI

// pow(x, 3.0) written as x * x * x: both bases are positive, so it is the same
// function, and glslang keeps a literal pow as SPIR-V Pow, which drivers evaluate
// as exp2(3 * log2(x)) - two transcendentals per fragment (lavapipe's are long
// polynomial sequences) for what fxc emits as two multiplies.
float Cube(float x) { return x * x * x; }

float WboitWeight(float a, float z) {
  return clamp(Cube(min(1.0, a * 10.0) + 0.01) * 1e8 * Cube(1.0 - z * 0.9), 1e-2, 3e3);
}

#endif
