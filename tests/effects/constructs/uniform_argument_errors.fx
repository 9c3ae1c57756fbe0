//! CompileShader's arguments must fit some overload's uniform parameters.
//! error: uniform_argument_errors\.fx:7:99: error: 'PS' has 1 uniform parameter\(s\), but 2 argument\(s\) are given
#include "common.fxh"
float4 PS(VSOut i, uniform int mode) : SV_Target { return mode; }
technique11 T
{
    pass { SetVertexShader(CompileShader(vs_5_0, VSFull())); SetPixelShader(CompileShader(ps_5_0, PS(1, 2))); }
}
