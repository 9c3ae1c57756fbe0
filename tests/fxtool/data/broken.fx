// fxtool error check: the state block has an unknown blend value.
float4 g_vColor = float4(1, 0, 0, 1);

float4 PS() : SV_Target { return g_vColor; }

BlendState Bad
{
    BlendEnable[0] = TRUE;
    SrcBlend = NOT_A_BLEND;
};

technique11 T { pass P { SetPixelShader(CompileShader(ps_5_0, PS())); } }
