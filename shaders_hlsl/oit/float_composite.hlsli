// The peeling methods composite their layers in float32 (depth_peeling.fxh,
// dual_depth_peeling.fxh): LoadFrame copies the opaque frame into an
// R32G32B32A32_FLOAT composite, the layers blend over the composite, and StoreFrame
// copies it back into the R8G8B8A8_UNORM frame, rounded once. Over the 8-bit frame
// itself every layer would round and clamp (a lit surface can exceed 1 before the
// layers in front darken it), off the exact composite by up to 54/255 on the shards.
#ifndef OIT_FLOAT_COMPOSITE_HLSLI
#define OIT_FLOAT_COMPOSITE_HLSLI

Texture2D<float4> CopySource;  // LoadFrame: the frame; StoreFrame: the composite

float4 PSCopy(float4 pos : SV_Position) : SV_Target { return CopySource.Load(int3(pos.xy, 0)); }

#endif
