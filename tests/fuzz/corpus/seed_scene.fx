//--------------------------------------------------------------------------------------
// scene.fx: a legacy Direct3D 11 SDK-style effect, written for fxc's fx_5_0 profile.
//--------------------------------------------------------------------------------------
#include "common.fxh"

#pragma warning(disable : 3571)

cbuffer cbPerFrame : register(b0)
{
    float4x4 g_mWorldViewProj : WORLDVIEWPROJECTION;
    float3   g_vLightDir = float3(0.0f, -1.0f, 0.0f);
    float    g_fTime < string UIName = "Time"; float UIMin = 0; float UIMax = 100; > = 1.5f;
    float4   g_LightColors[MAX_LIGHTS] = { float4(1, 0, 0, 1), float4(0, 1, 0, 1) };
};

cbuffer cbPerObject
{
    float4 g_vMaterialColor = float4(1, 0.5, 0.25, 1);
    bool   g_bUseTexture = true;
    int    g_nMode = -3;
};

shared float g_fGlobalScale = 2.0;
float4 g_vFogColor : FOGCOLOR = { 0.5, 0.6, 0.7, 1.0 };

string g_Description = "Scene effect";

Texture2D g_txDiffuse < string ResourceName = "diffuse.dds"; >;
TextureCube g_txEnvironment : register(t3);
StructuredBuffer<float4> g_Instances;

SamplerState g_samLinear
{
    Filter = MIN_MAG_MIP_LINEAR;
    AddressU = Wrap;
    AddressV = Wrap;
};

SamplerComparisonState g_samShadow
{
    Filter = COMPARISON_MIN_MAG_LINEAR_MIP_POINT;
    AddressU = BORDER;
    AddressV = BORDER;
    BorderColor = float4(1, 1, 1, 0);
    ComparisonFunc = LESS_EQUAL;
    MaxAnisotropy = 1;
};

BlendState AdditiveBlending
{
    AlphaToCoverageEnable = FALSE;
    BlendEnable[0] = TRUE;
    SrcBlend = SRC_ALPHA;
    DestBlend = ONE;
    BlendOp = ADD;
    SrcBlendAlpha = ZERO;
    DestBlendAlpha = ZERO;
    BlendOpAlpha = ADD;
    RenderTargetWriteMask[0] = 0x0F;
    BlendEnable[1] = true;
    DestBlend[1] = D3D11_BLEND_INV_SRC_ALPHA;
    RenderTargetWriteMask[1] = 0x07;
};

BlendState NoBlending
{
    BlendEnable[0] = FALSE;
};

DepthStencilState DisableDepth
{
    DepthEnable = FALSE;
    DepthWriteMask = ZERO;
};

DepthStencilState StencilMark
{
    DepthEnable = TRUE;
    DepthWriteMask = ALL;
    DepthFunc = LESS_EQUAL;
    StencilEnable = TRUE;
    StencilReadMask = 0xFF;
    StencilWriteMask = 0x0F;
    FrontFaceStencilFunc = Always;
    FrontFaceStencilPass = Incr_Sat;
    BackFaceStencilFail = d3d11_stencil_op_zero;
};

RasterizerState Wireframe
{
    FillMode = WIREFRAME;
    CullMode = NONE;
    FrontCounterClockwise = TRUE;
    DepthBias = -10;
    SlopeScaledDepthBias = 1.5;
};

//--------------------------------------------------------------------------------------
PSInput VSMain(VSInput input)
{
    PSInput output;
    output.Position = mul(float4(input.Position * g_fGlobalScale, 1), g_mWorldViewProj);
    output.Normal = input.Normal;
    output.TexCoord = input.TexCoord;
    return output;
}

float4 PSMain(PSInput input, uniform bool bTexture, uniform int nLights = MAX_LIGHTS) : SV_Target
{
    float4 color = g_vMaterialColor;
    if (bTexture)
        color *= g_txDiffuse.Sample(g_samLinear, input.TexCoord);
    float3 lit = 0;
    for (int i = 0; i < nLights; ++i)
        lit += g_LightColors[i].rgb * saturate(dot(input.Normal, -g_vLightDir));
    return SATURATE_COLOR(color * float4(lit, 1));
}

[maxvertexcount(3)]
void GSMain(triangle PSInput input[3], inout TriangleStream<PSInput> stream)
{
    for (int i = 0; i < 3; ++i)
        stream.Append(input[i]);
    stream.RestartStrip();
}

//--------------------------------------------------------------------------------------
VertexShader g_vsMain = CompileShader(vs_5_0, VSMain());
GeometryShader g_gsStreamOut = ConstructGSWithSO(CompileShader(gs_5_0, GSMain()),
                                                 "SV_Position.xyzw; 1:NORMAL.xyz; $SKIP.x; TEXCOORD0.xy");
GeometryShader g_gsMultiStream = ConstructGSWithSO(CompileShader(gs_5_0, GSMain()),
                                                   "SV_Position", NULL, "1:TEXCOORD2.zw", NULL, 2);

technique11 Render < string Script = "Pass=P0;"; >
{
    pass P0
    {
        SetVertexShader(g_vsMain);
        SetGeometryShader(NULL);
        SetPixelShader(CompileShader(ps_5_0, PSMain(true)));
        SetBlendState(NoBlending, float4(0.0f, 0.0f, 0.0f, 0.0f), 0xFFFFFFFF);
        SetDepthStencilState(StencilMark, 1);
        SetRasterizerState(NULL);
    }
    pass P1 < bool Wire = true; >
    {
        SetVertexShader(g_vsMain);
        SetPixelShader(CompileShader(ps_4_0, PSMain(false, 1)));
        SetBlendState(AdditiveBlending, float4(1, 1, 1, 1), 0x0000000F);
        SetDepthStencilState(DisableDepth, 0);
        SetRasterizerState(Wireframe);
    }
}

technique11 StreamOut
{
    pass P0
    {
        SetVertexShader(g_vsMain);
        SetGeometryShader(g_gsStreamOut);
        SetPixelShader(NULL);
        SetDepthStencilState(DisableDepth, 0);
    }
    pass P1
    {
        SetVertexShader(CompileShader(vs_5_0, VSMain()));
        SetGeometryShader(ConstructGSWithSO(CompileShader(gs_5_0, GSMain()), "POSITION.xyz"));
        SetPixelShader(CompileShader(ps_5_0, PSMain(true)));
    }
}
