//! The two failures of the legacy corpus. Entry points overloaded and told
//! apart by uniform parameters, each used by its own technique (fxc binds the
//! arguments as compile-time constants); static const members of a cbuffer
//! used as an array size and a groupshared size (fxc: not members, so the
//! layout is g_vTint at 0, g_vArray at 16, size 80).
//! pixel: Plain 0.5 1 1.5 2
//! pixel: Indexed 5 6 7 8
//! pixel: IndexedByDefault 1 1 1 1
#include "common.fxh"

cbuffer PerFrame
{
    float4 g_vTint = { 1, 2, 3, 4 };
    static const int kCount = 4;
    float4 g_vArray[kCount] = { 0, 0, 0, 0, 1, 1, 1, 1, 5, 6, 7, 8, 2, 2, 2, 2 };
    static const float kScale = 0.5;
};

groupshared float s_cache[kCount * 16];

float4 PS() : SV_Target
{
    return g_vTint * kScale;
}

float4 PS(uniform int index) : SV_Target
{
    return g_vArray[index];
}

float4 PSDefault(VSOut i, uniform int index = 1) : SV_Target
{
    return g_vArray[index];
}

technique11 Plain
{
    pass P0
    {
        SetVertexShader(CompileShader(vs_5_0, VSFull()));
        SetPixelShader(CompileShader(ps_5_0, PS()));
    }
}

technique11 Indexed
{
    pass P0
    {
        SetVertexShader(CompileShader(vs_5_0, VSFull()));
        SetPixelShader(CompileShader(ps_5_0, PS(2)));
    }
}

technique11 IndexedByDefault
{
    pass P0
    {
        SetVertexShader(CompileShader(vs_5_0, VSFull()));
        SetPixelShader(CompileShader(ps_5_0, PSDefault()));
    }
}
