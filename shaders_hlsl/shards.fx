// The instanced glass shards of document 000 as a translucent object: one shard
// mesh (slot 0, per vertex) and per-instance data (slot 1,
// INPUT_PER_INSTANCE_DATA): the world matrix as four float4 columns WORLD0..3
// and a tint (rgb transmission, a alpha), drawn with one DrawIndexedInstanced.
// A transparency method's passes come from OIT_METHOD, the method's include
// (shaders_hlsl/oit/common.fxh gives the contract this file fulfils).
#include "shards.hlsl"

#define OBJECT_VS VSShard
#define OBJECT_GS NULL
#define OBJECT_PIXEL ShardPixel
#define OBJECT_COLORED_TRANSMISSION 1  // glass filters the light behind it by its tint
#define OBJECT_DEFERRED 1              // TriangleId and ShadeTriangle (shards.hlsl)

// Loaded on its own, as any FX file, the object is drawn with plain alpha blending.
#ifndef OIT_METHOD
#define OIT_METHOD "oit/alpha.fxh"
#endif
#include OIT_METHOD
