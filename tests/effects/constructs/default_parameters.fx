//! Default parameter values, on helper functions and on uniform parameters
//! that CompileShader leaves out: Weight(1) + Weight(1, 3) = 2.5 + 3.5 = 6.
//! pixel: Defaults 6 6 6 6
//! pixel: GainOnly 3 3 3 3
//! pixel: Both -2 -2 -2 -2
#include "common.fxh"
float Weight(float x, float scale = 2.0, float bias = 0.5) { return x * scale + bias; }
float4 PS(VSOut i, uniform float gain = 1.0, uniform bool invert = false) : SV_Target
{
    float w = Weight(1.0) + Weight(1.0, 3.0);
    return invert ? 1 - w * gain : w * gain;
}
VertexShader g_vs = CompileShader(vs_5_0, VSFull());
technique11 Defaults { pass { SetVertexShader(g_vs); SetPixelShader(CompileShader(ps_5_0, PS())); } }
technique11 GainOnly { pass { SetVertexShader(g_vs); SetPixelShader(CompileShader(ps_5_0, PS(0.5))); } }
technique11 Both { pass { SetVertexShader(g_vs); SetPixelShader(CompileShader(ps_5_0, PS(0.5, true))); } }
