// Dear ImGui through the RHI (app/imgui_rhi.cpp), the shaders of imgui_impl_dx11 in
// shader-model-5 form, plus the replay window's scene blit (app/replay_window.cpp).
//
// VSMain / PSMain: ImGui's vertex layout (ImDrawVert: float2 pos, float2 uv, RGBA8 col),
// an orthographic projection from display coordinates to clip space, the font atlas
// (or any texture an ImTextureID names) modulated by the vertex colour.
//
// BlitVS / BlitPS: a full-screen triangle from SV_VertexID (no vertex buffer) that samples
// the scene texture; the viewport places it (letterboxed) in the back buffer.

cbuffer ImGuiConstants : register(b0)
{
    float4x4 ProjectionMatrix;  // column_major (HLSL default): columns as uploaded
};

struct VSInput
{
    float2 pos : POSITION;
    float2 uv  : TEXCOORD0;
    float4 col : COLOR0;
};

struct PSInput
{
    float4 pos : SV_POSITION;
    float4 col : COLOR0;
    float2 uv  : TEXCOORD0;
};

Texture2D Texture0 : register(t0);
SamplerState Sampler0 : register(s0);

PSInput VSMain(VSInput input)
{
    PSInput output;
    output.pos = mul(ProjectionMatrix, float4(input.pos.xy, 0.0f, 1.0f));
    output.col = input.col;
    output.uv = input.uv;
    return output;
}

float4 PSMain(PSInput input) : SV_Target
{
    return input.col * Texture0.Sample(Sampler0, input.uv);
}

struct BlitOutput
{
    float4 pos : SV_POSITION;
    float2 uv  : TEXCOORD0;
};

BlitOutput BlitVS(uint id : SV_VertexID)
{
    // (0,0) (2,0) (0,2) in uv: one triangle that covers the viewport.
    BlitOutput output;
    output.uv = float2((id << 1) & 2, id & 2);
    output.pos = float4(output.uv * float2(2.0f, -2.0f) + float2(-1.0f, 1.0f), 0.0f, 1.0f);
    return output;
}

float4 BlitPS(BlitOutput input) : SV_Target
{
    return float4(Texture0.Sample(Sampler0, input.uv).rgb, 1.0f);
}
