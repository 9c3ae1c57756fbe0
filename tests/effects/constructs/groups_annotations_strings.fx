//! fxgroup, technique10 / technique11 / technique, annotations on groups,
//! techniques, passes and variables, string variables, lowercase texture2D.
//! pixel: Forward 1 0 0 1
//! pixel: Legacy 1 0 0 1
//! pixel: Plain 1 0 0 1
#include "common.fxh"
float4 g_color : DIFFUSE < string UIName = "Color"; float UIMin = 0; float UIMax = 1; int Steps = 10; bool Visible = true; > = { 1, 0, 0, 1 };
string g_description < string Category = "Docs"; > = "A test effect";
string g_names[2] = { "first", "second" };
texture2D g_tex < string ResourceName = "default.dds"; >;
float4 PS(VSOut i) : SV_Target { return g_color; }
fxgroup Lighting < string Purpose = "lights"; >
{
    technique11 Forward < string Mode = "forward"; int Order = 1; >
    {
        pass Main < string Blend = "none"; float4 Tint = { 1, 2, 3, 4 }; >
        {
            SetVertexShader(CompileShader(vs_5_0, VSFull()));
            SetPixelShader(CompileShader(ps_5_0, PS()));
        }
    }
}
technique10 Legacy < string Note = "fx_4_0 keyword"; > { pass { SetVertexShader(CompileShader(vs_4_0, VSFull())); SetPixelShader(CompileShader(ps_4_0, PS())); } }
technique Plain { pass { SetVertexShader(CompileShader(vs_5_0, VSFull())); SetPixelShader(CompileShader(ps_5_0, PS())); } }
