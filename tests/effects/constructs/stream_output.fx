//! GeometryShader variables from ConstructGSWithSO: an inline gs with a
//! uniform argument, a vertex shader variable, the fx_5_0 four-stream form
//! with -1 for D3D11_SO_NO_RASTERIZED_STREAM.
//! loads
struct V { float4 pos : SV_Position; float2 uv : TEXCOORD0; };
V VS(uint id : SV_VertexID) { V v; v.pos = float4(id, 0, 0, 1); v.uv = float2(id, 1); return v; }
[maxvertexcount(2)]
void GS(point V p[1], inout PointStream<V> s, uniform float offset) { V v = p[0]; s.Append(v); v.uv.y += offset; s.Append(v); }
VertexShader vsSO = CompileShader(vs_5_0, VS());
GeometryShader gsSO = ConstructGSWithSO(CompileShader(gs_5_0, GS(1.0)), "SV_Position.xyzw; TEXCOORD0.xy");
GeometryShader gsVS = ConstructGSWithSO(vsSO, "SV_Position.xyzw");
GeometryShader gs5 = ConstructGSWithSO(CompileShader(gs_5_0, GS(2.0)), "SV_Position.xyzw; TEXCOORD0.xy", NULL, NULL, NULL, -1);
technique11 T
{
    pass P0 { SetVertexShader(vsSO); SetGeometryShader(gsSO); SetPixelShader(NULL); }
    pass P1 { SetVertexShader(vsSO); SetGeometryShader(gsVS); SetPixelShader(NULL); }
    pass P2 { SetVertexShader(vsSO); SetGeometryShader(gs5); SetPixelShader(NULL); }
}
