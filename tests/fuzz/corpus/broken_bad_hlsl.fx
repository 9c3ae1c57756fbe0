#include "missing_header.fxh"
float4 PS() : SV_Target { return undefined_symbol; }
technique11 T { pass P { SetPixelShader(CompileShader(ps_5_0, PS())); } }
