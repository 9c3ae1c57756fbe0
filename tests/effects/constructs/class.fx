//! Dynamic shader linkage is refused where it starts.
//! error: class\.fx:4:1: error: 'class' \(dynamic shader linkage\) is not supported
#include "common.fxh"
class Ambient { float3 color; float3 Illuminate(float3 n) { return color; } };
