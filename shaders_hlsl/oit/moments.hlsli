// The moment mathematics of document 003's methods, written once: moment-based OIT
// (Münstermann, Krumpen, Klein, Peters, I3D 2018: "MBOIT") and Moment Transparency
// (Sharpe, HPG 2018), which both store four power moments of the translucent
// fragments' warped depths, weighted by their optical depth, and reconstruct the
// transmittance in front of a depth from them (the Hamburger bound of moment shadow
// mapping, Peters & Klein 2015). Every effect (oit/moment_passes.fxh) and the test
// that evaluates the reconstruction on the GPU (tests/conformance/moments_test.cpp)
// include this file. Pure functions: the caller passes the camera's planes.
//
// Depth units. `viewDepth` everywhere below is the VIEW DEPTH in scene units (the
// distance from the eye along its forward axis, as ViewDepthFromWindow gives it for
// the perspectiveLH_ZO projection of renderer::Translucency), never the window depth
// SV_Position.z: the moments use its logarithmic warp, and the minimum-depth
// correction compares view depths, so that m = 100 means "full weight one hundredth
// of a scene unit behind the nearest surface" whatever the near and far planes are.
#ifndef OIT_MOMENTS_HLSLI
#define OIT_MOMENTS_HLSLI

// The moment bias of MBOIT's Table for four power moments stored in 32-bit floats:
// the moments are pulled this far towards kMomentBiasVector (the moments of a
// distribution spread over [-1, 1]) before the reconstruction, which keeps the Hankel
// matrix positive definite against float32 rounding.
static const float kMomentBias = 5e-7;
static const float4 kMomentBiasVector = float4(0.0, 0.375, 0.0, 0.375);
// MBOIT's overestimation: the reconstruction takes the absorbance of the fragments at
// the queried depth itself with this weight (0: the lower bound, 1: the upper one).
static const float kOverestimation = 0.25;
// Below this total optical depth (-ln(1 - 0.001)) a pixel holds nothing visible:
// its transmittance is 1 and no reconstruction is attempted (MBOIT does the same).
static const float kMinTotalOpticalDepth = 0.00100050033;
// Opacity is clamped below 1 so that the optical depth -ln(1 - a) stays finite.
static const float kMaxOpacity = 0.9999;

// View depth (scene units) of a fragment from its window depth (SV_Position.z) under
// glm::perspectiveLH_ZO(fov, aspect, nearPlane, farPlane): z = f/(f-n) * (1 - n/d).
float ViewDepthFromWindow(float windowDepth, float nearPlane, float farPlane) {
  return nearPlane * farPlane / (farPlane - windowDepth * (farPlane - nearPlane));
}

// MBOIT's logarithmic depth warp: ln(view depth) mapped from [ln near, ln far] to
// [-1, 1]. Both passes warp with the same planes (the frame's camera).
float WarpDepth(float viewDepth, float nearPlane, float farPlane) {
  float t = (log(viewDepth) - log(nearPlane)) / (log(farPlane) - log(nearPlane));
  return saturate(t) * 2.0 - 1.0;
}

// The optical depth (absorbance) of a surface of opacity a: -ln(1 - a).
float OpticalDepth(float a) { return -log(1.0 - clamp(a, 0.0, kMaxOpacity)); }

// One fragment's additive contribution: b0 its optical depth, b its power moments
// (z, z^2, z^3, z^4) of the warped depth z, weighted by that optical depth.
void PowerMoments(float warpedDepth, float opticalDepth, out float b0, out float4 b) {
  float z2 = warpedDepth * warpedDepth;
  b0 = opticalDepth;
  b = float4(warpedDepth, z2, z2 * warpedDepth, z2 * z2) * opticalDepth;
}

// x, moved away from 0 to +-tiny (its sign kept): a divisor that cannot be 0.
float NonZero(float x) {
  const float tiny = 1e-12;
  return abs(x) < tiny ? (x < 0.0 ? -tiny : tiny) : x;
}

// The normalised absorbance in front of `warpedDepth` (0: none of the pixel's optical
// depth lies in front, 1: all of it), from the moments b / b0 (Hamburger 4, MBOIT's
// Algorithm: a Cholesky factorisation of the biased Hankel matrix, the canonical
// representation through the queried depth, and the bound of its two other roots).
// A pixel of one fragment (or of fragments at one depth) makes the Hankel matrix
// singular; the bias, the guarded divisors and the final clamp keep the result finite
// and within [0, 1] then (tests/conformance/moments_test.cpp).
float NormalizedAbsorbance(float4 normalizedMoments, float warpedDepth) {
  float4 b = lerp(normalizedMoments, kMomentBiasVector, kMomentBias);
  // Cholesky factorisation of the Hankel matrix ((1, b1, b2), (b1, b2, b3), (b2, b3, b4)).
  float l21d11 = b.z - b.x * b.y;
  float d11 = max(b.y - b.x * b.x, 1e-12);
  float l21 = l21d11 / d11;
  float d22 = max(b.w - b.y * b.y - l21d11 * l21, 1e-12);
  // Solve B c = (1, z, z^2) for the polynomial c whose roots are the support points.
  float z0 = warpedDepth;
  float3 c = float3(1.0, z0, z0 * z0);
  c.y -= b.x;
  c.z -= b.y + l21 * c.y;
  c.y /= d11;
  c.z /= d22;
  c.y -= l21 * c.z;
  c.x -= dot(c.yz, b.xy);
  // Its two other roots z1 <= z2.
  float p = c.y / NonZero(c.z);
  float q = c.x / NonZero(c.z);
  float r = sqrt(max(p * p * 0.25 - q, 0.0));
  float z1 = -p * 0.5 - r;
  float z2 = -p * 0.5 + r;
  // The weights of the support points in front of z0 (z0 itself: the overestimation),
  // as the quadratic interpolating them (divided differences), applied to the moments.
  float f0 = kOverestimation;
  float f1 = z1 < z0 ? 1.0 : 0.0;
  float f2 = z2 < z0 ? 1.0 : 0.0;
  float f01 = (f1 - f0) / NonZero(z1 - z0);
  float f12 = (f2 - f1) / NonZero(z2 - z1);
  float f012 = (f12 - f01) / NonZero(z2 - z0);
  // Newton form f0 + f01 (z - z0) + f012 (z - z0)(z - z1), in powers of z.
  float slope = f01 - f012 * z1;
  float3 poly = float3(f0 - slope * z0, slope - f012 * z0, f012);
  float absorbance = poly.x + dot(b.xy, poly.yz);
  return isnan(absorbance) ? kOverestimation : saturate(absorbance);
}

// The transmittance in front of `warpedDepth`, within [exp(-b0), 1], from the pixel's
// total optical depth b0 and its summed moments b (not yet divided by b0).
float TransmittanceInFront(float b0, float4 b, float warpedDepth) {
  if (!(b0 >= kMinTotalOpticalDepth)) return 1.0;
  return exp(-b0 * NormalizedAbsorbance(b / b0, warpedDepth));
}

// Document 003's minimum-depth correction, the factor of the weight of a fragment at
// view depth z in a pixel whose nearest translucent fragment is at z_min (both view
// depths, scene units): w_out = w_in * min(max(m (z - z_min), 0), 1) where z > z_min.
// The thesis applies it "where the pixel's depth z is greater than z_min" (chapter 3):
// the nearest surface itself (z == z_min, or z < z_min where z_min was stored rounded)
// keeps its weight; SPEC.md's formula alone would give it weight 0.
float MinDepthCorrection(float z, float zMin, float m) {
  return z > zMin ? saturate(m * (z - zMin)) : 1.0;
}

#endif
