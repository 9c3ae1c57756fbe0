// fxtool compute check: each thread writes its id into a RWTexture2D (the first --target).
float4 g_vTint = float4(1, 1, 1, 1);
RWTexture2D<float4> g_Output;

[numthreads(4, 4, 1)]
void CSMain(uint3 id : SV_DispatchThreadID)
{
    g_Output[id.xy] = float4(id.x, id.y, 0.5f, 1) * g_vTint;
}

technique11 Compute
{
    pass P0 { SetComputeShader(CompileShader(cs_5_0, CSMain())); }
}
