// The opaque scene of the translucency demos (document 000's "opaque objects",
// drawn first): coloured stripes, floor and cubes, Lambert-lit by one directional
// light, depth tested and written (D3D11's default depth-stencil state).
#include "scene_opaque.hlsl"

DepthStencilState DepthDefault { DepthEnable = TRUE; DepthWriteMask = ALL; DepthFunc = LESS; };
RasterizerState NoCull { CullMode = NONE; };

technique11 Opaque {
  pass Scene {
    SetVertexShader(CompileShader(vs_5_0, VSOpaque()));
    SetGeometryShader(NULL);
    SetPixelShader(CompileShader(ps_5_0, PSOpaque()));
    SetBlendState(NULL, float4(0, 0, 0, 0), 0xFFFFFFFF);
    SetDepthStencilState(DepthDefault, 0);
    SetRasterizerState(NoCull);
  }
}
