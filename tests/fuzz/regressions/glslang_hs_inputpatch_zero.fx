// glslang 12 segfaults (HlslParseContext::handleAssign, null TIntermTyped) on a hull
// shader entry point whose InputPatch has 0 control points.
struct VSOut { float3 Pos : POSITION; };
struct HSConst { float Edges[3] : SV_TessFactor; float Inside : SV_InsideTessFactor; };

HSConst HSConstant(InputPatch<VSOut, 3> patch)
{
    HSConst c;
    c.Edges[0] = c.Edges[1] = c.Edges[2] = 1;
    c.Inside = 1;
    return c;
}

[domain("tri")]
[partitioning("integer")]
[outputtopology("triangle_cw")]
[outputcontrolpoints(3)]
[patchconstantfunc("HSConstant")]
VSOut HSMain(InputPatch<VSOut, 0> patch, uint i : SV_OutputControlPointID) { return patch[i]; }

technique11 T { pass P { SetHullShader(CompileShader(hs_5_0, HSMain())); } }
