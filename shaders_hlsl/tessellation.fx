// Tessellation and compute through the effect runtime.
// technique Tessellate: a pass-through hull shader with constant factors and a
// domain shader placing the barycentric points of one triangle patch
// (PRIMITIVE_TOPOLOGY_3_CONTROL_POINT_PATCHLIST); the pixel shader writes Color.
// technique Fill: a compute shader writing Scale * index + Offset[variant] into a RWStructuredBuffer.

cbuffer Params {
  float4 Color = float4(0, 1, 0, 1);
  float TessFactor = 4;
  uint Scale = 3;
};

RWStructuredBuffer<uint> Output;

struct ControlPoint { float3 position : POSITION; };
struct DomainOut { float4 position : SV_Position; };
struct PatchConstants {
  float edges[3] : SV_TessFactor;
  float inside : SV_InsideTessFactor;
};

ControlPoint VSControlPoint(ControlPoint p) { return p; }

PatchConstants HSConstants(InputPatch<ControlPoint, 3> patch) {
  PatchConstants c;
  c.edges[0] = c.edges[1] = c.edges[2] = TessFactor;
  c.inside = TessFactor;
  return c;
}

[domain("tri")]
[partitioning("integer")]
[outputtopology("triangle_cw")]
[outputcontrolpoints(3)]
[patchconstantfunc("HSConstants")]
ControlPoint HSMain(InputPatch<ControlPoint, 3> patch, uint i : SV_OutputControlPointID) { return patch[i]; }

[domain("tri")]
DomainOut DSMain(PatchConstants c, float3 uvw : SV_DomainLocation, const OutputPatch<ControlPoint, 3> patch) {
  DomainOut o;
  float3 p = uvw.x * patch[0].position + uvw.y * patch[1].position + uvw.z * patch[2].position;
  o.position = float4(p, 1);
  return o;
}

float4 PSColor(DomainOut i) : SV_Target { return Color; }

[numthreads(64, 1, 1)]
void CSFill(uint3 id : SV_DispatchThreadID, uniform uint offset) {
  Output[id.x] = id.x * Scale + offset;
}

technique11 Tessellate {
  pass P0 {
    SetVertexShader(CompileShader(vs_5_0, VSControlPoint()));
    SetHullShader(CompileShader(hs_5_0, HSMain()));
    SetDomainShader(CompileShader(ds_5_0, DSMain()));
    SetGeometryShader(NULL);
    SetPixelShader(CompileShader(ps_5_0, PSColor()));
  }
}

technique11 Fill {
  pass Plus0 { SetComputeShader(CompileShader(cs_5_0, CSFill(0))); }
  pass Plus1000 { SetComputeShader(CompileShader(cs_5_0, CSFill(1000))); }
}
