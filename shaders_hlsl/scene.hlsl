// The demo scene: textured geometry lit by one directional light plus ambient (Lambert).
//
// Matrix convention: the cbuffer uses HLSL's default column_major packing, so each
// 16-byte register holds one COLUMN of the matrix. The app uploads GLM matrices
// unchanged (GLM stores column-major too), so the HLSL matrix equals the GLM matrix
// and vectors are column vectors: mul(M, v), exactly as in GLM (M * v).
// (Classic D3D code keeps row-major DirectXMath matrices and writes mul(v, M);
// that is the same product with everything transposed.)

cbuffer SceneConstants : register(b0)
{
    float4x4 World;         // object -> world
    float4x4 View;          // world -> view (left-handed, glm::lookAtLH)
    float4x4 Proj;          // view -> clip (glm::perspectiveLH_ZO: D3D depth range 0..1)
    float4   LightDir;      // xyz: direction the light travels (world, normalised)
    float4   LightColor;    // rgb: linear radiance scale
    float4   Ambient;       // rgb: linear ambient term
    float4   Tint;          // rgb: multiplies the texture (linear)
};

Texture2D    Albedo        : register(t0);
SamplerState LinearWrap    : register(s0);

struct VSInput
{
    float3 position : POSITION;
    float3 normal   : NORMAL;
    float2 uv       : TEXCOORD0;
};

struct VSOutput
{
    float4 position : SV_Position;
    float3 normal   : NORMAL;
    float2 uv       : TEXCOORD0;
};

VSOutput VSMain(VSInput input)
{
    VSOutput output;
    float4 world = mul(World, float4(input.position, 1.0));
    output.position = mul(Proj, mul(View, world));
    // World has only rotation + uniform scale here, so it transforms normals too.
    output.normal = mul((float3x3)World, input.normal);
    output.uv = input.uv;
    return output;
}

float4 PSMain(VSOutput input) : SV_Target0
{
    // The texture is sRGB: Sample returns linear values; the sRGB target encodes again.
    float3 albedo = Albedo.Sample(LinearWrap, input.uv).rgb * Tint.rgb;
    float3 n = normalize(input.normal);
    float lambert = saturate(dot(n, -LightDir.xyz));
    float3 color = albedo * (Ambient.rgb + LightColor.rgb * lambert);
    return float4(color, 1.0);
}
