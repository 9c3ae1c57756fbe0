//! FX10/FX11 samplers: `= sampler_state { Texture = <t>; ... }` (the Texture
//! binding is FX10's and ignored by D3D11), a bare block, untyped `texture`.
//! loads
#include "common.fxh"
Texture2D g_tex;
texture g_untyped;
SamplerState g_sampler = sampler_state { Texture = <g_untyped>; Filter = MIN_MAG_MIP_POINT; AddressU = Wrap; AddressV = Clamp; };
SamplerState g_plain { Filter = ANISOTROPIC; MaxAnisotropy = 4; };
float4 PS(VSOut i) : SV_Target { return g_tex.Sample(g_sampler, i.uv) + g_tex.Sample(g_plain, i.uv); }
technique11 T { pass { SetVertexShader(CompileShader(vs_5_0, VSFull())); SetPixelShader(CompileShader(ps_5_0, PS())); } }
