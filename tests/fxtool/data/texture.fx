// fxtool --texture check: each pixel loads the bound texture's texel.
Texture2D Tex;

float4 VSFullScreen(uint id : SV_VertexID) : SV_Position
{
    float2 uv = float2((id << 1) & 2, id & 2);
    return float4(uv * float2(2, -2) + float2(-1, 1), 0.5f, 1);
}

float4 PSLoad(float4 pos : SV_Position) : SV_Target { return Tex.Load(int3(pos.xy, 0)); }

technique11 Show
{
    pass P0
    {
        SetVertexShader(CompileShader(vs_5_0, VSFullScreen()));
        SetPixelShader(CompileShader(ps_5_0, PSLoad()));
    }
}
