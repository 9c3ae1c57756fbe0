// Moment Transparency (Sharpe, HPG 2018) as document 003 describes it: pass 1
// accumulates the power moments 1..4 of the fragments' depths weighted by their
// optical depth -ln(1 - a), and the total optical depth; pass 2 reconstructs the
// transmittance in front of each fragment from them and uses it as the weight,
// accumulating (c a, a) w as WBOIT does; a final pass composites. Its moment code
// is MBOIT's (oit/moments.hlsli, the same bias, overestimation and depth warp):
// as document 003 tells it, the two methods differ in name and history, not in the
// passes (oit/moment_passes.fxh has the slots and blend states).
// With MOMENT_MIN_DEPTH 1 (oit/moment_transparency_mindepth.fxh) pass 1 also keeps
// the nearest translucent view depth and pass 2 applies document 003's correction.
#include "moment_passes.fxh"

technique11 MomentTransparency {
#ifdef OBJECT_VS
  OBJECT_PASS(Moments, PSMoments, MomentsAccumulate)
  OBJECT_PASS(Weights, PSWeighted, WeightedAccumulate)
#endif
  MOMENTS_COMPOSE_PASS
}
