// The 2D composing pass of document 000 (Tables 2 and 4): a full-screen triangle
// reading accum and revealage, writing (accum.rgb / max(accum.a, 0.0001), 1 - revealage).
Texture2D<float4> Accum : register(t0);
Texture2D<float4> Revealage : register(t1);

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
