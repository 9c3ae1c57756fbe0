//! #line renames the file and renumbers the lines in every position.
//! loads
#include "common.fxh"
#line 200 "generated.fx"
float4 PS(VSOut i) : SV_Target { return float4(i.uv, 0, 1); }
#line 10
technique11 T { pass P { SetVertexShader(CompileShader(vs_5_0, VSFull())); SetPixelShader(CompileShader(ps_5_0, PS())); } }
