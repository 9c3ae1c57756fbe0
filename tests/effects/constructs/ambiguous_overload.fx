//! Overloads that the uniform arguments cannot tell apart are refused, as fxc does.
//! error: ambiguous_overload\.fx:9:99: error: ambiguous call to 'PS': the overloads at line 5 and line 6 both take 0 uniform argument\(s\)
#include "common.fxh"
struct Other { float4 pos : SV_Position; float4 color : COLOR0; };
float4 PS(VSOut i) : SV_Target { return 1; }
float4 PS(Other o) : SV_Target { return o.color; }
technique11 T
{
    pass { SetVertexShader(CompileShader(vs_5_0, VSFull())); SetPixelShader(CompileShader(ps_5_0, PS())); }
}
