//! FX9 pass assignments are refused with the fx_5_0 form to write instead.
//! error: fx9_pass_states\.fx:6:37: error: unknown pass assignment 'VertexShader' \(FX9-style state assignments are not supported; use SetVertexShader
#include "common.fxh"
technique11 T
{
    pass P0 { SetPixelShader(NULL); VertexShader = compile vs_5_0 VSFull(); }
}
