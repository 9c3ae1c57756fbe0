//! Dynamic shader linkage is refused where it starts.
//! error: interface\.fx:4:1: error: 'interface' \(dynamic shader linkage\) is not supported
#include "common.fxh"
interface ILight { float3 Illuminate(float3 n); };
