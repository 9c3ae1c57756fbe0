//! static const at file scope, in a cbuffer, in a tbuffer and in a function,
//! sizing arrays, a groupshared array and [numthreads]: 0.5 * 2 + 0.25 * 4 = 2.
//! pixel: T 2 2 2 2
#include "common.fxh"
static const int kTaps = 2;
static const float kWeights[kTaps] = { 0.5, 0.25 };
cbuffer Params
{
    static const uint kMaxLights = 2 * kTaps;
    float4 g_lights[kMaxLights] = { 2, 2, 2, 2, 4, 4, 4, 4, 0, 0, 0, 0, 0, 0, 0, 0 };
    static const float kAmbient = 0.25;
    float g_exposure = 1;
};
tbuffer Extra
{
    static const int kExtra = 2;
    float4 g_extra[kExtra];
};
groupshared float s_tile[kMaxLights * 16];
RWStructuredBuffer<float> g_out;
float4 PS(VSOut i) : SV_Target
{
    static const float kLocal[2] = { 1.0, 0.0 };
    const float c = kLocal[1] * kAmbient;
    float sum = 0;
    [unroll] for (int t = 0; t < kTaps; ++t) sum += kWeights[t] * g_lights[t].x;
    return sum * g_exposure + c + g_extra[kExtra - 1] * 0;
}
[numthreads(kMaxLights, 1, 1)]
void CS(uint3 id : SV_DispatchThreadID)
{
    s_tile[id.x] = g_lights[id.x].x;
    GroupMemoryBarrierWithGroupSync();
    g_out[id.x] = s_tile[kMaxLights - 1 - id.x];
}
technique11 T { pass P { SetVertexShader(CompileShader(vs_5_0, VSFull())); SetPixelShader(CompileShader(ps_5_0, PS())); } }
technique11 Compute { pass C { SetComputeShader(CompileShader(cs_5_0, CS())); } }
