// Blend states, fxgroups, annotations, macros and the preprocessor.
#define STRINGIFY(x) #x
#define CONCAT(a, b) a##b
#define ALPHA_OF(c) (c).a
#if defined(FUZZ) && (1 + 2 * 3 == 7)
#define HAVE_FUZZ 1
#else
#define HAVE_FUZZ 0
#endif

float4 g_vColor < string UIName = "Color"; string UIWidget = "Color"; > = float4(1.0f, 0.0f, 0.0f, 0.5f);
float2 g_vScale = { 1, 1 };
row_major float2x3 g_mTransform;
int g_aValues[3] = { 1, 2, 3 };

struct VSOut { float4 Pos : SV_Position; float2 UV : TEXCOORD0; };

VSOut VSFullScreen(uint id : SV_VertexID)
{
    VSOut o;
    o.UV = float2((id << 1) & 2, id & 2);
    o.Pos = float4(o.UV * float2(2, -2) + float2(-1, 1), 0, 1);
    return o;
}

float4 PSColor(VSOut i) : SV_Target { return float4(g_vColor.rgb, ALPHA_OF(g_vColor)); }
float4 PSUV(VSOut i) : SV_Target0 { return float4(i.UV * g_vScale, HAVE_FUZZ, 1); }

BlendState AlphaBlend
{
    BlendEnable[0] = TRUE;
    SrcBlend = SRC_ALPHA;
    DestBlend = INV_SRC_ALPHA;
    BlendOp = ADD;
    SrcBlendAlpha = ONE;
    DestBlendAlpha = INV_SRC_ALPHA;
    BlendOpAlpha = ADD;
    RenderTargetWriteMask[0] = 0x0F;
};
BlendState Premultiplied { BlendEnable[0] = TRUE; SrcBlend = ONE; DestBlend = INV_SRC_ALPHA; };
BlendState MinMax[2]
{
    { BlendEnable[0] = TRUE; BlendOp = MIN; SrcBlend = ONE; DestBlend = ONE; },
    { BlendEnable[0] = TRUE; BlendOp = MAX; SrcBlend = ONE; DestBlend = ONE; }
};
DepthStencilState NoDepth { DepthEnable = FALSE; };
RasterizerState NoCull { CullMode = NONE; ScissorEnable = FALSE; MultisampleEnable = TRUE; };

VertexShader CONCAT(g_vs, FullScreen) = CompileShader(vs_5_0, VSFullScreen());

fxgroup Blending < string Description = STRINGIFY(blend tables); >
{
    technique11 Over
    {
        pass P0 < int Order = 0; >
        {
            SetVertexShader(g_vsFullScreen);
            SetPixelShader(CompileShader(ps_5_0, PSColor()));
            SetBlendState(AlphaBlend, float4(0, 0, 0, 0), 0xFFFFFFFF);
            SetDepthStencilState(NoDepth, 0);
            SetRasterizerState(NoCull);
        }
        pass P1
        {
            SetVertexShader(g_vsFullScreen);
            SetPixelShader(CompileShader(ps_4_0, PSUV()));
            SetBlendState(MinMax[1], float4(1, 1, 1, 1), 0xFFFFFFFF);
        }
    }
}

technique10 Legacy
{
    pass { SetVertexShader(g_vsFullScreen); SetPixelShader(CompileShader(ps_4_0, PSColor())); SetBlendState(Premultiplied, float4(0,0,0,0), 0xFFFFFFFF); }
}
