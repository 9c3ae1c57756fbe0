float4 PS() : SV_Target { return undefined_symbol * 2; }
technique11 T { pass P { SetPixelShader(CompileShader(ps_5_0, PS())); } }
