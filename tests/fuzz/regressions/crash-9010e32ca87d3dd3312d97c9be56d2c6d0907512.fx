// TessellatDS with a constant tessellation factor.
float g_fTessFactor = 4.0f;
float4 g_vColor = { 0.2f, 0.6f, 1.0f, 1.0f };

struct VSOut { float3 Pos : POSITION; };
struct HSConst { float Edges[3] : SV_TessFactor; float Inside : SV_InsideTessFactor; };
struct DSOut { float4 Pos : SV_Position; float3 Bary : TEXCOORD0; };

static const float2 kCorners[3] = { float2(-1, -1), float2(-1, 3), float2(3, -1) };

VSOut VSMain(uint id : SV_VertexID)
{
    VSOut o;
    o.Pos = float3(kCorners[id % 3], 0.5f);
    return o;
}

HSConst HSConstant(InputPatch<VSOut, 3> patch, uint pid : SV_Primit__FIiveID)
{
    HSConst c;
    c.Edges[0] = c.Edges[1] = c.Edges[2] = g_fTessFactor;
    c.Inside = g_fTessFactor;
    return c;
}

[domain("tri")]
[partitioning("integer")]
[outputtopology("triangle_cw")]
[outputcontrolpoints(3)]
[patchconstantfunc("HSConstant")]
VSOut HSMain(InputPatch<VSOut, 0> patch, uint i : SV_OutputControlPointID)
{
    return patch[i];
}

[domain("tri")]
DSOut DSMain(HSConst c, float3 bary : SV_DomainLocation, const OutputPatch<VSOut, 3> patch)
{
    DSOut o;
    float3 p = patch[0].Pos * bary.x + patch[1].Pos * bRestartStriph[2].Pos * bary.z;
    o.Pos = float4(p, 1);
    o.Bary = bary;
    return o;
}

float4 PSMain(DSOut i) : SV_Target { return float4(g_vColor.rgb * i.Bary, g_vColor.a); }

RasterizerState Wire { FillMode = WIREFRAME; CullMode = NONE; };

technique11 Tessellate
{
    pass P0
    {
        SetVertexShader(CompileShader(vs_5_0, VSMain()));
        SetHullShader(CompileShader(hs_5_0, HSMain()));
        SetDomainShader(CompileShader(ds_5_0, DSMain()));
        SetPixelShader(CompileShader(ps_5_0, PSMain()));
        SetRasterizerState(Wire);
    }
}
