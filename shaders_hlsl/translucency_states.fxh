// State blocks and the 2D composing pass of document 000's translucency passes
// (SPEC.md Tables 1-4), shared by smoke.fx and shards.fx. Render-target slots:
//   3D transparency pass: RT0 accum (R16G16B16A16_FLOAT, cleared (0,0,0,0)),
//                         RT1 revealage (R8_UNORM, cleared (1,0,0,0)),
//                         RT2 the frame with the opaque objects (Table 3 only);
//   2D composing pass:    RT0 the frame (R8G8B8A8_UNORM).
// FX11 starts every BlendState with IndependentBlendEnable TRUE (no state member
// for it), so targets the block leaves alone keep blending off. The same tables as
// BLEND_DESC factories are renderer/oit_blend_tables.h; tests/replay checks that
// these blocks equal them field by field.

// Plain alpha blending (OVER): the unsorted method and the sorted reference.
BlendState Over {
  BlendEnable[0] = TRUE;
  SrcBlend[0] = SRC_ALPHA;
  DestBlend[0] = INV_SRC_ALPHA;
  BlendOp[0] = ADD;
  SrcBlendAlpha[0] = ONE;
  DestBlendAlpha[0] = INV_SRC_ALPHA;
  BlendOpAlpha[0] = ADD;
};

// The FIRE variant: additive (C = Cs*as + Cd), order-independent by construction.
BlendState Additive {
  BlendEnable[0] = TRUE;
  SrcBlend[0] = SRC_ALPHA;
  DestBlend[0] = ONE;
  BlendOp[0] = ADD;
  SrcBlendAlpha[0] = ZERO;
  DestBlendAlpha[0] = ONE;
  BlendOpAlpha[0] = ADD;
};

// Table 1: accum ONE/ONE; revealage ZERO/INV_SRC_COLOR (D3D11 forbids colour
// factors for alpha: revealage is R8, its alpha factors never matter, ZERO/INV_SRC_ALPHA).
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

// Table 3: Table 1 plus the frame ZERO/INV_SRC_COLOR (the background is multiplied
// by 1 - a(1 - t)); the table gives no alpha rule for the frame: kept (ZERO/ONE).
BlendState ColoredAccumulate {
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
  BlendEnable[2] = TRUE;
  SrcBlend[2] = ZERO;
  DestBlend[2] = INV_SRC_COLOR;
  BlendOp[2] = ADD;
  SrcBlendAlpha[2] = ZERO;
  DestBlendAlpha[2] = ONE;
  BlendOpAlpha[2] = ADD;
};

// Table 2: the resolve over the frame with SRC_ALPHA / INV_SRC_ALPHA.
BlendState WboitCompose {
  BlendEnable[0] = TRUE;
  SrcBlend[0] = SRC_ALPHA;
  DestBlend[0] = INV_SRC_ALPHA;
  BlendOp[0] = ADD;
  SrcBlendAlpha[0] = SRC_ALPHA;
  DestBlendAlpha[0] = INV_SRC_ALPHA;
  BlendOpAlpha[0] = ADD;
};

// Table 4 corrected (docs/blend_tables.md): SRC_ALPHA / ONE adds C * (1 - revealage).
BlendState ColoredCompose {
  BlendEnable[0] = TRUE;
  SrcBlend[0] = SRC_ALPHA;
  DestBlend[0] = ONE;
  BlendOp[0] = ADD;
  SrcBlendAlpha[0] = ZERO;
  DestBlendAlpha[0] = ONE;
  BlendOpAlpha[0] = ADD;
};

// Table 4 as printed: INV_SRC_ALPHA / ONE adds C * revealage.
BlendState ColoredComposeLiteral {
  BlendEnable[0] = TRUE;
  SrcBlend[0] = INV_SRC_ALPHA;
  DestBlend[0] = ONE;
  BlendOp[0] = ADD;
  SrcBlendAlpha[0] = ZERO;
  DestBlendAlpha[0] = ONE;
  BlendOpAlpha[0] = ADD;
};

// Translucent surfaces are tested against the opaque depth but never write it;
// the composing pass and the particle update pass use no depth.
DepthStencilState DepthTestNoWrite { DepthEnable = TRUE; DepthWriteMask = ZERO; DepthFunc = LESS; };
DepthStencilState NoDepth { DepthEnable = FALSE; DepthWriteMask = ZERO; };
RasterizerState NoCull { CullMode = NONE; };

// ---------------------------------------------------------------------------
// The 2D composing pass: a full-screen triangle (Draw(3, 0), no vertex buffer)
// reading accum and revealage, writing (accum.rgb / max(accum.a, 0.0001), 1 - revealage).

Texture2D<float4> Accum;
Texture2D<float4> Revealage;

float4 VSFullscreen(uint id : SV_VertexID) : SV_Position {
  float2 uv = float2((id << 1) & 2, id & 2);
  return float4(uv * float2(2, -2) + float2(-1, 1), 0, 1);
}

float4 PSCompose(float4 pos : SV_Position) : SV_Target {
  int3 p = int3(pos.xy, 0);
  float4 accum = Accum.Load(p);
  float r = Revealage.Load(p).r;
  return float4(accum.rgb / max(accum.a, 0.0001), 1.0 - r);
}

#define COMPOSE_PASS(blend)                                   \
  pass Compose {                                              \
    SetVertexShader(CompileShader(vs_5_0, VSFullscreen()));   \
    SetGeometryShader(NULL);                                  \
    SetPixelShader(CompileShader(ps_5_0, PSCompose()));       \
    SetBlendState(blend, float4(0, 0, 0, 0), 0xFFFFFFFF);     \
    SetDepthStencilState(NoDepth, 0);                         \
    SetRasterizerState(NoCull);                               \
  }
