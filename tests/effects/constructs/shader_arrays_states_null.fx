//! Shader arrays filled by CompileShader with uniform arguments, indexed by a
//! literal or a static const; SetRasterizerState / SetBlendState /
//! SetDepthStencilState in a pass; NULL shaders, inline and in a variable.
//! pixel: Red 1 0 0 1
//! pixel: Blue 0 0 1 1
#include "common.fxh"
float4 PS(VSOut i, uniform int mode) : SV_Target { return mode == 0 ? float4(1, 0, 0, 1) : mode == 1 ? float4(0, 1, 0, 1) : float4(0, 0, 1, 1); }
VertexShader g_vs = CompileShader(vs_5_0, VSFull());
PixelShader g_ps[3] = { CompileShader(ps_5_0, PS(0)), CompileShader(ps_5_0, PS(1)), CompileShader(ps_5_0, PS(2)) };
static const int kBlue = 2;
RasterizerState NoCull { CullMode = NONE; };
BlendState NoBlend { BlendEnable[0] = FALSE; };
DepthStencilState NoDepth { DepthEnable = FALSE; };
GeometryShader g_gsNull = NULL;
technique11 Red
{
    pass { SetVertexShader(g_vs); SetPixelShader(g_ps[0]); SetGeometryShader(NULL); SetHullShader(NULL); SetDomainShader(NULL); SetRasterizerState(NoCull); }
}
technique11 Blue
{
    pass { SetVertexShader(g_vs); SetGeometryShader(g_gsNull); SetPixelShader(g_ps[kBlue]); SetRasterizerState(NoCull); SetBlendState(NoBlend, float4(0, 0, 0, 0), 0xFFFFFFFF); SetDepthStencilState(NoDepth, 0); }
}
technique11 NoPixelShader { pass { SetVertexShader(g_vs); SetPixelShader(NULL); } }
