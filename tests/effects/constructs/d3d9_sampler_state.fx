//! D3D9-style samplers: their state names and tex2D are refused with the fix.
//! error: d3d9_sampler_state\.fx:9:5: error: 'MinFilter' is a D3D9 sampler state, not fx_5_0's: write Filter = MIN_MAG_MIP_LINEAR
//! error: d3d9_sampler_state\.fx:10:5: error: 'MagFilter' is a D3D9 sampler state
//! error: d3d9_sampler_state\.fx:13:41: error: 'tex2D' is a D3D9 texture function, which fx_5_0 shaders do not take: declare a Texture2D and a SamplerState
#include "common.fxh"
texture g_tex;
sampler2D g_sampler = sampler_state
{
    MinFilter = Linear;
    MagFilter = Linear;
    AddressU = Wrap;
};
float4 PS(VSOut i) : SV_Target { return tex2D(g_sampler, i.uv); }
