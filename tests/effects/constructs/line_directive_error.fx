//! A glslang error after #line names the renamed file, its line and the column.
//! error: generated\.fx:200:57: error: 'undefined_thing' : unknown variable
#include "common.fxh"
#line 200 "generated.fx"
float4 PS(VSOut i) : SV_Target { return float4(i.uv, 0, undefined_thing); }
technique11 T { pass P { SetVertexShader(CompileShader(vs_5_0, VSFull())); SetPixelShader(CompileShader(ps_5_0, PS())); } }
