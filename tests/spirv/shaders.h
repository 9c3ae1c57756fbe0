// HLSL / GLSL sources shared by the spirv tests.
#pragma once

namespace spirv_test::shaders {

// VS with struct inputs/outputs, the way D3D samples write them.
inline constexpr const char* kVertex = R"(
struct VSIn { float3 pos : POSITION; float3 nrm : NORMAL; float2 uv0 : TEXCOORD0; float4 uv1 : TEXCOORD1; };
struct VSOut { float4 pos : SV_Position; float2 uv : TEXCOORD0; float4 col : COLOR1; };
VSOut main(VSIn i) {
  VSOut o;
  o.pos = float4(i.pos + i.nrm, 1);
  o.uv = i.uv0;
  o.col = i.uv1;
  return o;
}
)";

// VS reading SV_InstanceID.
inline constexpr const char* kVertexInstanced = R"(
struct VSOut { float4 pos : SV_Position; float id : TEXCOORD0; };
VSOut main(float4 pos : POSITION, uint iid : SV_InstanceID) {
  VSOut o;
  o.pos = pos + float4(iid, 0, 0, 0);
  o.id = (float)iid;
  return o;
}
)";

inline constexpr const char* kPixel = R"(
struct PSOut { float4 c0 : SV_Target0; float4 c1 : SV_Target1; };
PSOut main(float4 pos : SV_Position, float2 uv : TEXCOORD0) {
  PSOut o;
  o.c0 = float4(uv, 0, 1);
  o.c1 = pos;
  return o;
}
)";

// Points in, triangle strip out, 4 vertices: a point-sprite expander.
inline constexpr const char* kGeometry = R"(
struct GSIn { float4 pos : SV_Position; float2 uv : TEXCOORD0; };
struct GSOut { float4 pos : SV_Position; float2 uv : TEXCOORD0; float4 col : COLOR0; };
[maxvertexcount(4)]
void main(point GSIn input[1], inout TriangleStream<GSOut> stream) {
  for (int k = 0; k < 4; ++k) {
    GSOut o;
    o.pos = input[0].pos + float4(k & 1, k >> 1, 0, 0);
    o.uv = input[0].uv;
    o.col = float4(k, 0, 0, 1);
    stream.Append(o);
  }
  stream.RestartStrip();
}
)";

inline constexpr const char* kCompute = R"(
RWStructuredBuffer<uint> result : register(u0);
[numthreads(8, 4, 1)]
void main(uint3 id : SV_DispatchThreadID) { result[id.x] = id.y; }
)";

// One resource of each kind, with explicit registers.
inline constexpr const char* kResources = R"(
cbuffer Frame : register(b2) { float4x4 view; float4 tint; };
Texture2D<float4> albedo : register(t3);
SamplerState samp : register(s1);
RWStructuredBuffer<uint> counts : register(u4);
StructuredBuffer<float4> lights : register(t5);
Buffer<float4> texels : register(t6);
RWTexture2D<float4> image : register(u1);
Texture2D layers[4] : register(t8);
RWBuffer<float> written : register(u7);
float4 main(float4 pos : SV_Position, float2 uv : TEXCOORD0) : SV_Target {
  float4 c = albedo.Sample(samp, uv) * tint + lights[0] + texels[1] + layers[2].Sample(samp, uv);
  InterlockedAdd(counts[0], 1);
  image[uint2(0, 0)] = c;
  written[0] = c.x;
  return mul(view, c);
}
)";

// GLSL VS: glslang puts gl_Position in a gl_PerVertex block (with an unwritten gl_PointSize member).
inline constexpr const char* kGlslVertex = R"(#version 450
layout(location = 0) in vec4 p;
layout(location = 0) out vec2 uv;
void main() { gl_Position = p; uv = p.xy; }
)";

// GLSL VS with a redeclared gl_PerVertex that has no gl_PointSize member.
inline constexpr const char* kGlslVertexPositionOnly = R"(#version 450
layout(location = 0) in vec4 p;
out gl_PerVertex { vec4 gl_Position; };
void main() { gl_Position = p; }
)";

// GLSL VS that writes its own point size.
inline constexpr const char* kGlslVertexPointSize = R"(#version 450
layout(location = 0) in vec4 p;
void main() { gl_Position = p; gl_PointSize = 3.0; }
)";

// GLSL GS with two vertex streams (HLSL through glslang cannot express streams).
inline constexpr const char* kGlslGeometryStreams = R"(#version 450
layout(points) in;
layout(points, max_vertices = 2) out;
layout(location = 0, stream = 0) out vec4 color;
layout(location = 1, stream = 1) out vec3 extra;
void main() {
  gl_Position = gl_in[0].gl_Position;
  color = vec4(1, 2, 3, 4);
  EmitStreamVertex(0);
  extra = vec3(5, 6, 7);
  EmitStreamVertex(1);
}
)";

}  // namespace spirv_test::shaders
