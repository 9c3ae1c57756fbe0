// fxtool stream-output check: N points from SV_VertexID, a GS that streams each out twice.
float g_fScale = 2.0f;

struct VSOut { float4 Pos : POSITION; uint Id : TEXCOORD0; };
struct GSOut { float4 Pos : SV_Position; float4 Data : TEXCOORD0; };

VSOut VSMain(uint id : SV_VertexID)
{
    VSOut o;
    o.Pos = float4(id, id * g_fScale, 0, 1);
    o.Id = id;
    return o;
}

[maxvertexcount(2)]
void GSMain(point VSOut input[1], inout PointStream<GSOut> stream)
{
    GSOut o;
    o.Pos = input[0].Pos;
    o.Data = float4(input[0].Id, 0, 0, 1);
    stream.Append(o);
    o.Data.y = 1;
    stream.Append(o);
}

GeometryShader g_gsSO = ConstructGSWithSO(CompileShader(gs_5_0, GSMain()), "SV_Position.xyzw; TEXCOORD0.xy");

technique11 StreamOut
{
    pass P0
    {
        SetVertexShader(CompileShader(vs_5_0, VSMain()));
        SetGeometryShader(g_gsSO);
        SetPixelShader(NULL);
    }
}
