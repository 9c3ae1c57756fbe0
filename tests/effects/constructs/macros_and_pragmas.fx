//! DECLARE-style macros that expand to functions and techniques; #pragma
//! lines anywhere (pack_matrix applies, warning / message are ignored).
//! pixel: Red 1 0 0 1
//! pixel: Green 0 1 0 1
#pragma warning(disable : 3571)
#pragma pack_matrix(row_major)
#include "common.fxh"
#define DECLARE_COLOR_PS(name, r, g, b) float4 name(VSOut i) : SV_Target { return mul(float4(r, g, b, 1), g_world); }
#define DECLARE_TECHNIQUE(tech, ps) \
    technique11 tech { pass P { SetVertexShader(CompileShader(vs_5_0, VSFull())); SetPixelShader(CompileShader(ps_5_0, ps())); } }
cbuffer M { float4x4 g_world = { 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1 }; };
DECLARE_COLOR_PS(PSRed, 1, 0, 0)
DECLARE_COLOR_PS(PSGreen, 0, 1, 0)
#pragma message("building techniques")
DECLARE_TECHNIQUE(Red, PSRed)
DECLARE_TECHNIQUE(Green, PSGreen)
