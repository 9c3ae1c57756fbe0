// A transparency "method" for tests/replay/fragment_buffer_test.cpp: it records every
// translucent fragment that passes the opaque depth test, with what the forward Shade
// and the deferred ShadeTriangle (oit/common.fxh) give it, into an append buffer. It
// composites nothing, so the frame keeps the opaque pass.
#include "oit/common.fxh"

// float4s only: glslang lays a structured buffer's float3 out on 16 bytes (std430),
// where D3D11 packs it on 4; float4 members agree on both.
struct FragmentRecord {
  uint pixel;  // y * width + x
  uint id;     // TriangleId
  float depth;
  uint unused;
  float4 forward;               // Shade: colour, alpha
  float4 forwardTransmission;   // xyz
  float4 deferred;              // ShadeTriangle: colour, alpha
  float4 deferredTransmission;  // xyz
};

cbuffer RecordParams {
  uint RecordWidth;
};

#ifdef OBJECT_VS
AppendStructuredBuffer<FragmentRecord> Records : register(u0);

[earlydepthstencil]
void PSRecord(OBJECT_PIXEL p, uint primitiveId : SV_PrimitiveID) {
  FragmentRecord r;
  r.pixel = uint(p.position.y) * RecordWidth + uint(p.position.x);
  r.id = TriangleId(p, primitiveId);
  r.depth = p.position.z;
  r.unused = 0;
  float3 c, t;
  float a;
  Shade(p, c, a, t);
  r.forward = float4(c, a);
  r.forwardTransmission = float4(t, 0);
  ShadeTriangle(r.id, float4(p.position.xy, p.position.z, 1), c, a, t);
  r.deferred = float4(c, a);
  r.deferredTransmission = float4(t, 0);
  Records.Append(r);
}

technique11 Record {
  pass Record {
    SetVertexShader(CompileShader(vs_5_0, OBJECT_VS()));
    SetGeometryShader(OBJECT_GS);
    SetPixelShader(CompileShader(ps_5_0, PSRecord()));
    SetBlendState(NULL, float4(0, 0, 0, 0), 0xFFFFFFFF);
    SetDepthStencilState(DepthTestNoWrite, 0);
    SetRasterizerState(NoCull);
  }
}
#endif
