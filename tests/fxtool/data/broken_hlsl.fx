// fxtool error check: the HLSL of a pass does not compile.
float4 g_vColor = float4(1, 0, 0, 1);

float4 PS() : SV_Target
{
    return g_vColor * undefined_symbol;
}

technique11 T { pass P { SetPixelShader(CompileShader(ps_5_0, PS())); } }
