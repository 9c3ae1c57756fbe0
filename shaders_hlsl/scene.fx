// The opaque scene of the translucency demos (document 000's "opaque objects",
// drawn first): coloured stripes, floor and cubes, Lambert-lit by one directional
// light, depth tested and written (D3D11's default depth-stencil state).
//
// Two ways to draw it:
//   Opaque/Scene             forward: shaded as it is rasterized, into the frame.
//   Visibility/Ids, then Visibility/ShadeOpaque   document 004's visibility buffer: the
//       rasterizer stores only which triangle each pixel shows (SV_PrimitiveID + 1
//       into an R32_UINT target; 0 where no triangle is: the background) and the
//       depth; the shading runs later, once a pixel, from the triangle's vertices.
#include "scene_opaque.hlsl"
#include "fullscreen.hlsli"
#include "oit/deferred.hlsli"

DepthStencilState DepthDefault { DepthEnable = TRUE; DepthWriteMask = ALL; DepthFunc = LESS; };
DepthStencilState NoDepth { DepthEnable = FALSE; DepthWriteMask = ZERO; };
RasterizerState NoCull { CullMode = NONE; };

// The visibility buffer and the backdrop's vertices: a raw view of the vertex buffer
// the Ids pass draws (renderer::BackdropVertex: position, normal, colour, 36 bytes),
// three vertices a triangle in draw order, so that SV_PrimitiveID finds them.
Texture2D<uint> VisibilityIds;
ByteAddressBuffer OpaqueVertices;
static const uint kBackdropVertexBytes = 36;

uint PSVisibility(OpaquePixel p, uint primitive : SV_PrimitiveID) : SV_Target { return primitive + 1; }

OpaqueVertex LoadOpaqueVertex(uint index) {
  uint base = index * kBackdropVertexBytes;
  OpaqueVertex v;
  v.position = asfloat(OpaqueVertices.Load3(base));
  v.normal = asfloat(OpaqueVertices.Load3(base + 12));
  v.color = asfloat(OpaqueVertices.Load3(base + 24));
  return v;
}

// The pixel's triangle, its attributes interpolated at the point the pixel's ray
// meets it, lit as PSOpaque lights them. The background keeps the frame's clear colour.
float4 PSShadeVisibility(float4 position : SV_Position) : SV_Target {
  uint id = VisibilityIds.Load(int3(position.xy, 0));
  if (id == 0) discard;
  OpaqueVertex v0 = LoadOpaqueVertex(3 * (id - 1)), v1 = LoadOpaqueVertex(3 * (id - 1) + 1),
               v2 = LoadOpaqueVertex(3 * (id - 1) + 2);
  float3 w = Barycentrics(v0.position, v1.position, v2.position,
                          PixelOnTriangle(position.xy, v0.position, v1.position, v2.position));
  float3 normal = w.x * v0.normal + w.y * v1.normal + w.z * v2.normal;
  float3 color = w.x * v0.color + w.y * v1.color + w.z * v2.color;
  return float4(LitOpaque(normal, color), 1);
}

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

technique11 Visibility {
  pass Ids {
    SetVertexShader(CompileShader(vs_5_0, VSOpaque()));
    SetGeometryShader(NULL);
    SetPixelShader(CompileShader(ps_5_0, PSVisibility()));
    SetBlendState(NULL, float4(0, 0, 0, 0), 0xFFFFFFFF);
    SetDepthStencilState(DepthDefault, 0);
    SetRasterizerState(NoCull);
  }
  pass ShadeOpaque {
    SetVertexShader(CompileShader(vs_5_0, VSFullscreenTriangle()));
    SetGeometryShader(NULL);
    SetPixelShader(CompileShader(ps_5_0, PSShadeVisibility()));
    SetBlendState(NULL, float4(0, 0, 0, 0), 0xFFFFFFFF);
    SetDepthStencilState(NoDepth, 0);
    SetRasterizerState(NoCull);
  }
}
