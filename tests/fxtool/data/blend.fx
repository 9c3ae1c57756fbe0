// fxtool blend-table check: SrcBlend = SRC_ALPHA, DestBlend = INV_SRC_ALPHA over a cleared target.
float4 g_vColor = float4(1.0f, 0.0f, 0.0f, 0.75f);

struct VSOut { float4 Pos : SV_Position; };

VSOut VSFullScreen(uint id : SV_VertexID)
{
    VSOut o;
    float2 uv = float2((id << 1) & 2, id & 2);
    o.Pos = float4(uv * float2(2, -2) + float2(-1, 1), 0.5f, 1);
    return o;
}

float4 PSColor(VSOut i) : SV_Target { return g_vColor; }

BlendState AlphaOver
{
    BlendEnable[0] = TRUE;
    SrcBlend = SRC_ALPHA;
    DestBlend = INV_SRC_ALPHA;
    BlendOp = ADD;
    SrcBlendAlpha = ONE;
    DestBlendAlpha = INV_SRC_ALPHA;
    BlendOpAlpha = ADD;
};
DepthStencilState NoDepth { DepthEnable = FALSE; DepthWriteMask = ZERO; };
RasterizerState NoCull { CullMode = NONE; };

technique11 Over
{
    pass P0
    {
        SetVertexShader(CompileShader(vs_5_0, VSFullScreen()));
        SetGeometryShader(NULL);
        SetPixelShader(CompileShader(ps_5_0, PSColor()));
        SetBlendState(AlphaOver, float4(0, 0, 0, 0), 0xFFFFFFFF);
        SetDepthStencilState(NoDepth, 0);
        SetRasterizerState(NoCull);
    }
}
