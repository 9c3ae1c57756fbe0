// Compute: fills a structured buffer and a 2D UAV.
#define GROUP_SIZE 8

cbuffer cbParams : register(b0)
{
    uint  g_nCount = 64;
    float g_fScale = 0.5f;
};

RWStructuredBuffer<float4> g_Output : register(u0);
RWTexture2D<float4> g_Image;
Texture2D<float4> g_Input;

[numthreads(GROUP_SIZE, GROUP_SIZE, 1)]
void CSFill(uint3 id : SV_DispatchThreadID)
{
    uint index = id.y * 64 + id.x;
    if (index < g_nCount)
        g_Output[index] = float4(id.xy, g_fScale, 1);
    g_Image[id.xy] = float4(id.x / 64.0f, id.y / 64.0f, g_fScale, 1);
}

[numthreads(64, 1, 1)]
void CSScale(uint3 id : SV_DispatchThreadID, uniform float factor)
{
    g_Output[id.x] *= factor;
}

technique11 Compute
{
    pass Fill { SetComputeShader(CompileShader(cs_5_0, CSFill())); }
    pass Double { SetComputeShader(CompileShader(cs_5_0, CSScale(2.0f))); }
}
