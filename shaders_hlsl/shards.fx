// The instanced glass shard effect of document 000: one shard mesh (slot 0, per
// vertex) and per-instance data (slot 1, INPUT_PER_INSTANCE_DATA): the world
// matrix as four float4 columns WORLD0..3 and a tint (rgb transmission, a alpha),
// drawn with one DrawIndexedInstanced.
//   technique Alpha   pass Transparency: OVER (also the sorted reference, instances reordered)
//   technique Wboit   pass Transparency (Table 1) + pass Compose (Table 2)
//   technique Colored pass Transparency (Table 3) + pass Compose (Table 4 corrected);
//   technique ColoredLiteral: Table 4 as printed.
#include "translucency_states.fxh"
#include "shards.hlsl"

#define SHARD_TRANSPARENCY(ps, blend)                          \
  pass Transparency {                                          \
    SetVertexShader(CompileShader(vs_5_0, VSShard()));         \
    SetGeometryShader(NULL);                                   \
    SetPixelShader(CompileShader(ps_5_0, ps()));               \
    SetBlendState(blend, float4(0, 0, 0, 0), 0xFFFFFFFF);      \
    SetDepthStencilState(DepthTestNoWrite, 0);                 \
    SetRasterizerState(NoCull);                                \
  }

technique11 Alpha { SHARD_TRANSPARENCY(PSShardOver, Over) }
technique11 Wboit { SHARD_TRANSPARENCY(PSShardWboit, WboitAccumulate) COMPOSE_PASS(WboitCompose) }
technique11 Colored { SHARD_TRANSPARENCY(PSShardColored, ColoredAccumulate) COMPOSE_PASS(ColoredCompose) }
technique11 ColoredLiteral { SHARD_TRANSPARENCY(PSShardColored, ColoredAccumulate) COMPOSE_PASS(ColoredComposeLiteral) }
