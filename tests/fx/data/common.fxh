// Shared declarations of scene.fx, included relative to it.
#ifndef COMMON_FXH
#define COMMON_FXH

#define MAX_LIGHTS 2
#define SATURATE_COLOR(c) saturate(c)

struct VSInput
{
    float3 Position : POSITION;
    float3 Normal   : NORMAL;
    float2 TexCoord : TEXCOORD0;
};

struct PSInput
{
    float4 Position : SV_Position;
    float3 Normal   : NORMAL;
    float2 TexCoord : TEXCOORD0;
};

#endif
