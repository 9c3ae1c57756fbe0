// The opaque background of the translucency demos: coloured stripes, floor and
// cubes, Lambert-lit by one directional light.
cbuffer OpaqueParams : register(b0) {
  float4x4 ViewProj;
  float3 LightDir;
  float Ambient;
};

struct OpaqueVertex {
  float3 position : POSITION;
  float3 normal : NORMAL;
  float3 color : COLOR;
};

struct OpaquePixel {
  float4 position : SV_Position;
  float3 normal : NORMAL;
  float3 color : COLOR;
};

OpaquePixel VSOpaque(OpaqueVertex v) {
  OpaquePixel o;
  o.position = mul(ViewProj, float4(v.position, 1));
  o.normal = v.normal;
  o.color = v.color;
  return o;
}

// Lambert with an ambient floor: forward (PSOpaque) and deferred (scene.fx's
// visibility-buffer shading) alike.
float3 LitOpaque(float3 normal, float3 color) {
  float d = saturate(dot(normalize(normal), normalize(LightDir)));
  return color * (Ambient + (1.0 - Ambient) * d);
}

float4 PSOpaque(OpaquePixel p) : SV_Target { return float4(LitOpaque(p.normal, p.color), 1); }
