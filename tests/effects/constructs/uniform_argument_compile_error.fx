//! An error in a uniform argument points into the CompileShader that passes it.
//! error: uniform_argument_compile_error\.fx:7:102: error: 'undefined_const' : unknown variable
#include "common.fxh"
float4 PS(VSOut i, uniform float k) : SV_Target { return k; }
technique11 T
{
    pass { SetVertexShader(CompileShader(vs_5_0, VSFull())); SetPixelShader(CompileShader(ps_5_0, PS(undefined_const))); }
}
