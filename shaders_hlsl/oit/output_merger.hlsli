// The output merger's arithmetic on the targets the ROP methods blend into, in the
// models renderer/output_merger_probe.h chooses between. D3D11 leaves blend precision
// to the hardware (at least the target format's); the compute-tile methods
// (compute_tiles.fxh) replay the device's model, and the probe (blend_probe.fx)
// computes both models here to compare with what the device blended.
#ifndef OIT_OUTPUT_MERGER_HLSLI
#define OIT_OUTPUT_MERGER_HLSLI

uint4 ToUnorm8(float4 x) { return uint4(floor(saturate(x) * 255.0 + 0.5)); }
uint4 MulUnorm8(uint4 x, uint4 y) {  // round(x * y / 255)
  uint4 p = x * y + 128;
  return (p + (p >> 8)) >> 8;
}

// A blend into an 8-bit UNORM target: dst' = src * srcFactor + dst * (1 - inverse),
// all in [0, 1] (the destination factor an INV_* factor, or ONE with inverse 0); `dst`
// holds 8-bit values. The source's values and the factors are taken in 8 bits (an
// 8-bit INV_* factor is 255 minus its value's 8 bits), then each product is rounded to
// 8 bits (roundsEachTerm: lavapipe), or their exact sum once.
uint4 BlendUnorm8(float4 src, float4 srcFactor, uint4 dst, float4 inverse, bool roundsEachTerm) {
  uint4 s = ToUnorm8(src), f = ToUnorm8(srcFactor), g = 255 - ToUnorm8(inverse);
  if (roundsEachTerm) return min(MulUnorm8(s, f) + MulUnorm8(dst, g), 255);
  return ToUnorm8((s * f + dst * g) / 65025.0);
}

// x as an R16G16B16A16_FLOAT target stores it: a sum past the largest half held there
// (the paper's weights overflow it in dense smoke; both devices measured hold it), the
// others rounded toward zero (lavapipe) or to nearest even. The sums are never negative.
float4 Half(float4 x, bool towardZero) {
  uint4 h = f32tof16(min(x, 65504.0));  // to nearest even
  float4 nearest = f16tof32(h);
  return towardZero && nearest > x ? f16tof32(h - 1) : nearest;
}

#endif
