// Moment-based order-independent transparency (Münstermann, Krumpen, Klein, Peters,
// I3D 2018), document 003's base: four power moments in float32, additively blended;
// the Hamburger reconstruction with the moment bias 5e-7 (the paper's value for four
// power moments in 32-bit floats), overestimation 0.25 and the logarithmic depth
// warp (oit/moments.hlsli). Passes, in the paper's order:
//   GenerateMoments  b0 (R32_FLOAT) and b1..b4 (R32G32B32A32_FLOAT)
//   ResolveMoments   accum += (c a, a) T(z), T reconstructed from the moments
//   Compose          accum.rgb / accum.a over the frame with opacity 1 - exp(-b0)
// The slots and blend states: oit/moment_passes.fxh.
#include "moment_passes.fxh"

technique11 Mboit {
#ifdef OBJECT_VS
  OBJECT_PASS(GenerateMoments, PSMoments, MomentsAccumulate)
  OBJECT_PASS(ResolveMoments, PSWeighted, WeightedAccumulate)
#endif
  MOMENTS_COMPOSE_PASS
}
