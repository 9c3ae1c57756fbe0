// Weighted blended order-independent transparency (WBOIT, /work/shared/SPEC.md):
// technique WBOIT pass Transparency accumulates the translucent surfaces into
// two render targets (Table 1), pass Compose blends their resolve over the
// frame buffer with a full-screen triangle (Table 2).

cbuffer PerObject {
  float4x4 WorldViewProj;
  float4 Color = float4(1, 0, 0, 0.5);  // rgb, a = opacity
};

Texture2D AccumTexture;      // R16G16B16A16_FLOAT: sum of (rgb*a, a)*w
Texture2D RevealageTexture;  // R8_UNORM: product of (1 - a)

// Table 1: accum ONE/ONE, revealage ZERO/INV_SRC_COLOR. IndependentBlendEnable is TRUE:
// FX11 has no state member for it and starts every BlendState with it TRUE.
BlendState WboitAccumulate {
  BlendEnable[0] = TRUE;
  SrcBlend[0] = ONE;
  DestBlend[0] = ONE;
  BlendOp[0] = ADD;
  SrcBlendAlpha[0] = ONE;
  DestBlendAlpha[0] = ONE;
  BlendOpAlpha[0] = ADD;
  BlendEnable[1] = TRUE;
  SrcBlend[1] = ZERO;
  DestBlend[1] = INV_SRC_COLOR;
  BlendOp[1] = ADD;
  SrcBlendAlpha[1] = ZERO;
  DestBlendAlpha[1] = INV_SRC_ALPHA;
  BlendOpAlpha[1] = ADD;
};

// Table 2: SRC_ALPHA / INV_SRC_ALPHA over the frame buffer.
BlendState WboitCompose {
  BlendEnable[0] = TRUE;
  SrcBlend[0] = SRC_ALPHA;
  DestBlend[0] = INV_SRC_ALPHA;
  SrcBlendAlpha[0] = ONE;
  DestBlendAlpha[0] = INV_SRC_ALPHA;
};

// Translucent surfaces are tested against the opaque depth but never write it.
DepthStencilState DepthTestNoWrite { DepthEnable = TRUE; DepthWriteMask = ZERO; DepthFunc = LESS; };
DepthStencilState NoDepth { DepthEnable = FALSE; DepthWriteMask = ZERO; };
RasterizerState NoCull { CullMode = NONE; };

struct SurfaceIn { float4 pos : SV_Position; };

SurfaceIn VSSurface(float3 position : POSITION) {
  SurfaceIn o;
  o.pos = mul(WorldViewProj, float4(position, 1));
  return o;
}

struct AccumOut {
  float4 accum : SV_Target0;
  float revealage : SV_Target1;
};

AccumOut PSAccumulate(SurfaceIn i) {
  float a = Color.a;
  float z = i.pos.z;
  float w = clamp(pow(min(1.0, a * 10.0) + 0.01, 3.0) * 1e8 * pow(1.0 - z * 0.9, 3.0), 1e-2, 3e3);
  AccumOut o;
  o.accum = float4(Color.rgb * a, a) * w;
  o.revealage = a;
  return o;
}

// A full-screen triangle from SV_VertexID (Draw(3, 0), no vertex buffer).
float4 VSFullScreen(uint id : SV_VertexID) : SV_Position {
  float2 uv = float2((id << 1) & 2, id & 2);
  return float4(uv * float2(2, -2) + float2(-1, 1), 0, 1);
}

float4 PSCompose(float4 pos : SV_Position) : SV_Target {
  int3 texel = int3(pos.xy, 0);
  float4 accum = AccumTexture.Load(texel);
  float revealage = RevealageTexture.Load(texel).r;
  return float4(accum.rgb / max(accum.a, 0.0001), 1 - revealage);
}

technique11 WBOIT {
  pass Transparency {
    SetVertexShader(CompileShader(vs_5_0, VSSurface()));
    SetGeometryShader(NULL);
    SetPixelShader(CompileShader(ps_5_0, PSAccumulate()));
    SetBlendState(WboitAccumulate, float4(0, 0, 0, 0), 0xFFFFFFFF);
    SetDepthStencilState(DepthTestNoWrite, 0);
    SetRasterizerState(NoCull);
  }
  pass Compose {
    SetVertexShader(CompileShader(vs_5_0, VSFullScreen()));
    SetPixelShader(CompileShader(ps_5_0, PSCompose()));
    SetBlendState(WboitCompose, float4(0, 0, 0, 0), 0xFFFFFFFF);
    SetDepthStencilState(NoDepth, 0);
  }
}
