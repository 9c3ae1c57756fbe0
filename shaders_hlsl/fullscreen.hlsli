// The full-screen passes' vertex shader: one triangle from SV_VertexID (Draw(3, 0),
// no vertex buffer) whose clip-space corners (-1, 1), (3, 1), (-1, -3) cover the
// viewport.
#ifndef FULLSCREEN_HLSLI
#define FULLSCREEN_HLSLI

float4 VSFullscreenTriangle(uint id : SV_VertexID) : SV_Position {
  float2 uv = float2((id << 1) & 2, id & 2);
  return float4(uv * float2(2, -2) + float2(-1, 1), 0, 1);
}

#endif
