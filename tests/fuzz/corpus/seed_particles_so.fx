// Stream-output particles: a pass-through VS, a GS that expands/streams out.
cbuffer cbFrame
{
    float  g_fTime = 0.0f;
    float  g_fElapsed = 0.016f;
    float3 g_vGravity = float3(0, -9.8f, 0);
    uint   g_nMaxParticles = 1024;
};

struct Particle
{
    float3 Position : POSITION;
    float3 Velocity : VELOCITY;
    float  Age      : AGE;
    uint   Type     : TYPE;
};

Particle VSPassThrough(Particle p) { return p; }

[maxvertexcount(2)]
void GSUpdate(point Particle input[1], inout PointStream<Particle> stream)
{
    Particle p = input[0];
    p.Age += g_fElapsed;
    p.Velocity += g_vGravity * g_fElapsed;
    p.Position += p.Velocity * g_fElapsed;
    if (p.Type == 0u)
    {
        Particle child = p;
        child.Type = 1u;
        child.Age = 0;
        stream.Append(child);
    }
    if (p.Age < 3.0f)
        stream.Append(p);
}

struct DrawVertex { float4 Pos : SV_Position; float4 Color : COLOR0; };

DrawVertex VSDraw(Particle p)
{
    DrawVertex o;
    o.Pos = float4(p.Position, 1);
    o.Color = float4(saturate(p.Age / 3.0f).xxx, 1);
    return o;
}

float4 PSDraw(DrawVertex v) : SV_Target { return v.Color; }

GeometryShader g_gsUpdate = ConstructGSWithSO(CompileShader(gs_5_0, GSUpdate()),
                                              "POSITION.xyz; VELOCITY.xyz; AGE.x; TYPE.x");

DepthStencilState NoDepth { DepthEnable = FALSE; DepthWriteMask = ZERO; };
BlendState Additive { BlendEnable[0] = TRUE; SrcBlend = ONE; DestBlend = ONE; };

technique11 Particles
{
    pass Update
    {
        SetVertexShader(CompileShader(vs_5_0, VSPassThrough()));
        SetGeometryShader(g_gsUpdate);
        SetPixelShader(NULL);
        SetDepthStencilState(NoDepth, 0);
    }
    pass Draw
    {
        SetVertexShader(CompileShader(vs_5_0, VSDraw()));
        SetGeometryShader(NULL);
        SetPixelShader(CompileShader(ps_5_0, PSDraw()));
        SetBlendState(Additive, float4(0, 0, 0, 0), 0xFFFFFFFF);
        SetDepthStencilState(NoDepth, 0);
    }
}
