// Translucent triangle meshes (renderer/meshes.h) as a translucent object: world-space
// vertices, each with its mesh's material (front and back colour, opacity,
// transmission), lit two-sided by the scene's directional light. A transparency
// method's passes come from OIT_METHOD, the method's include
// (shaders_hlsl/oit/common.fxh gives the contract this file fulfils).

cbuffer MeshParams : register(b1) {
  float4x4 ViewProj;
  float3 LightDir;  // towards the light
  float Pad;
};

// Lambert with the opaque pass's ambient (scene.fx, Ambient = 0.45), so that a
// translucent surface and the backdrop behind it are lit alike.
static const float kAmbient = 0.45;

struct MeshVertex {
  float3 position : POSITION;
  float3 normal : NORMAL;
  float3 front : FRONTCOLOR;
  float3 back : BACKCOLOR;
  float opacity : OPACITY;
  float3 transmission : TRANSMISSION;
};

struct MeshVertexOut {
  float4 position : SV_Position;
  float3 normal : NORMAL;
  float3 front : FRONTCOLOR;
  float3 back : BACKCOLOR;
  float opacity : OPACITY;
  float3 transmission : TRANSMISSION;
};

// The pixel shader's input: the vertex shader's output and which side faces the eye.
struct MeshPixel {
  float4 position : SV_Position;
  float3 normal : NORMAL;
  float3 front : FRONTCOLOR;
  float3 back : BACKCOLOR;
  float opacity : OPACITY;
  float3 transmission : TRANSMISSION;
  bool isFrontFace : SV_IsFrontFace;
};

MeshVertexOut VSMesh(MeshVertex v) {
  MeshVertexOut o;
  o.position = mul(ViewProj, float4(v.position, 1));
  o.normal = v.normal;
  o.front = v.front;
  o.back = v.back;
  o.opacity = v.opacity;
  o.transmission = v.transmission;
  return o;
}

// Two-sided: the side facing the eye picks the colour, and the back side is lit
// with the normal flipped.
void Shade(MeshPixel p, out float3 c, out float a, out float3 t) {
  float3 n = normalize(p.normal);
  float3 albedo = p.front;
  if (!p.isFrontFace) {
    n = -n;
    albedo = p.back;
  }
  c = albedo * (kAmbient + (1.0 - kAmbient) * saturate(dot(n, normalize(LightDir))));
  a = p.opacity;
  t = p.transmission;
}

#define OBJECT_VS VSMesh
#define OBJECT_GS NULL
#define OBJECT_PIXEL MeshPixel

// Loaded on its own, as any FX file, the object is drawn with plain alpha blending.
#ifndef OIT_METHOD
#define OIT_METHOD "oit/alpha.fxh"
#endif
#include OIT_METHOD
