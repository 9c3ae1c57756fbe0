// The full-screen triangle of the methods' composing passes: Draw(3, 0) with no
// vertex buffer or input layout covers the viewport.
#ifndef OIT_FULLSCREEN_HLSLI
#define OIT_FULLSCREEN_HLSLI

float4 VSFullscreen(uint id : SV_VertexID) : SV_Position {
  float2 uv = float2((id << 1) & 2, id & 2);
  return float4(uv * float2(2, -2) + float2(-1, 1), 0, 1);
}

#endif
