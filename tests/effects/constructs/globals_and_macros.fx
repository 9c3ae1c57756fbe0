//! Globals with uniform / extern / static / row_major / typedef types, a
//! shared cbuffer, token pasting in a DECLARE-style technique macro, `0` as a
//! NULL shader, NULL states with 0.0f literals, `compile` in a shader
//! variable, an unnamed technique. PS(k) = g_uniformTint * k * g_extern *
//! s_mutable = (0.5, 0.5, 0.5, 1) * k * 1 * 2.
//! pixel: TechOne 1 1 1 2
//! pixel: TechTwo 2 2 2 4
#include "common.fxh"
uniform float4 g_uniformTint = { 0.5, 0.5, 0.5, 1 };
extern float g_extern = 1;
static float s_mutable = 2;
row_major float4x4 g_rowMajor;
typedef float4 Color;
Color g_typedefColor = { 1, 1, 1, 1 };
shared cbuffer Shared { float g_shared; };
#define PASTE(a, b) a##b
#define DECLARE_TECH(name, value) technique11 PASTE(Tech, name) { pass { SetVertexShader(vsCompiled); SetGeometryShader(0); SetPixelShader(CompileShader(ps_5_0, PS(value))); SetBlendState(NULL, float4(0.0f, 0.0f, 0.0f, 0.0f), 0xFFFFFFFF); SetDepthStencilState(NULL, 0); SetRasterizerState(NULL); } }
float4 PS(VSOut i, uniform float k) : SV_Target { return g_uniformTint * k * g_extern * s_mutable + g_typedefColor * 0 + g_shared * 0 + g_rowMajor[0] * 0; }
VertexShader vsCompiled = compile vs_5_0 VSFull();
DECLARE_TECH(One, 1.0f)
DECLARE_TECH(Two, 2.0)
technique11 { pass { SetVertexShader(vsCompiled); SetPixelShader(CompileShader(ps_5_0, PS(3))); } }
