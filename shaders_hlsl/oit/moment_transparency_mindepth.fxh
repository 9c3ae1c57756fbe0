// Moment Transparency with document 003's minimum-depth correction: pass 1 also
// writes the fragment's view depth into a third target with MIN blending (cleared
// to the far plane), pass 2 multiplies the weight by min(max(m (z - z_min), 0), 1)
// where z > z_min (oit/moments.hlsli, MinDepthCorrection), m = MinDepthSlope.
#define MOMENT_MIN_DEPTH 1
#include "moment_transparency.fxh"
