// Every error names file:line:column of the original source.
#include <gtest/gtest.h>

#include "test_util.h"

namespace fx {
namespace {

using test::MemoryFiles;
using test::MustFail;

std::string FirstError(const std::string& source, const ParseOptions& options = {}) {
  std::vector<ParseError> errors = MustFail(source, options);
  return errors.empty() ? "" : errors[0].Format();
}

TEST(EffectErrors, UnknownStateMember) {
  EXPECT_EQ(FirstError("BlendState b\n"
                       "{\n"
                       "    BlendEnable[0] = TRUE;\n"
                       "    SourceBlend = ONE;\n"
                       "};\n"),
            "test.fx:4:5: unknown BlendState member 'SourceBlend'");
}

TEST(EffectErrors, BadEnumValueAndIndex) {
  EXPECT_EQ(FirstError("DepthStencilState d\n"
                       "{\n"
                       "    DepthFunc =   LESSER;\n"
                       "};\n"),
            "test.fx:3:19: invalid value 'LESSER' for DepthFunc (not a comparison value)");
  EXPECT_EQ(FirstError("BlendState b { BlendEnable[ 9 ] = TRUE; };"),
            "test.fx:1:29: index 9 out of range for BlendEnable (0..7)");
  EXPECT_EQ(FirstError("RasterizerState r { FillMode = 2.5; };"),
            "test.fx:1:32: invalid value 2.5 for FillMode (not a fill mode value)");
}

TEST(EffectErrors, StateErrorsAreAllReported) {
  std::vector<ParseError> errors = MustFail(
      "SamplerState s\n"
      "{\n"
      "    Filter = LINEAR;\n"
      "    AddressU = Wrap;\n"
      "    AddressV = Repeat;\n"
      "};\n");
  ASSERT_EQ(errors.size(), 2u);
  EXPECT_EQ(errors[0].Format(), "test.fx:3:14: invalid value 'LINEAR' for Filter (not a filter value)");
  EXPECT_EQ(errors[1].Format(), "test.fx:5:16: invalid value 'Repeat' for AddressV (not a texture address mode value)");
}

TEST(EffectErrors, UnterminatedBlocks) {
  EXPECT_EQ(FirstError("SamplerState s\n"
                       "{\n"
                       "    Filter = MIN_MAG_MIP_POINT;\n"),
            "test.fx:2:1: unterminated state block: '{' is never closed");
  EXPECT_EQ(FirstError("technique11 T\n"
                       "{\n"
                       "    pass P0\n"
                       "    {\n"
                       "        SetVertexShader(NULL);\n"),
            "test.fx:4:5: unterminated pass 'P0': '{' is never closed");
  EXPECT_EQ(FirstError("cbuffer cb\n{\n  float4 x;\n"), "test.fx:2:1: unterminated cbuffer 'cb': '{' is never closed");
  EXPECT_EQ(FirstError("float4 PS() : SV_Target\n{\n  return 1;\n"), "test.fx:2:1: '{' is never closed");
  EXPECT_EQ(FirstError("float x < string a = \"b\";\n"), "test.fx:1:9: annotation block '<' is never closed");
}

TEST(EffectErrors, MissingInclude) {
  EXPECT_EQ(FirstError("float a;\n\n#include \"missing.fxh\"\n", MemoryFiles({})),
            "test.fx:3:1: cannot open include file 'missing.fxh'");
}

TEST(EffectErrors, PositionsThroughIncludesAndMacros) {
  ParseOptions options = MemoryFiles({{"states.fxh",
                                       "#define BLEND_ON(i) BlendEnable[i] = MAYBE;\n"
                                       "BlendState fromInclude\n"
                                       "{\n"
                                       "    DestBlend = SRC_COLOUR;\n"
                                       "};\n"}});
  std::vector<ParseError> errors = MustFail(
      "#include \"states.fxh\"\n"
      "BlendState b\n"
      "{\n"
      "    BLEND_ON(1)\n"
      "};\n",
      options);
  ASSERT_EQ(errors.size(), 2u);
  EXPECT_EQ(errors[0].Format(), "states.fxh:4:17: invalid value 'SRC_COLOUR' for DestBlend (not a blend value)");
  // A token of a macro body is reported at the macro's invocation.
  EXPECT_EQ(errors[1].Format(), "test.fx:4:5: invalid value 'MAYBE' for BlendEnable (expected TRUE or FALSE)");
}

TEST(EffectErrors, StreamOutputDeclarationPointsIntoTheString) {
  EXPECT_EQ(FirstError("[maxvertexcount(1)] void GS(point float4 p[1] : SV_Position, inout PointStream<float4> s) {}\n"
                       "GeometryShader g = ConstructGSWithSO(CompileShader(gs_5_0, GS()),\n"
                       "                                     \"SV_Position.xz\");\n"),
            "test.fx:3:51: stream-output declaration: mask '.xz' must name contiguous components in order");
  EXPECT_EQ(FirstError("void GS() {}\n"
                       "GeometryShader g = ConstructGSWithSO(CompileShader(gs_5_0, GS()), \"A\", \"B\");\n"),
            "test.fx:2:20: ConstructGSWithSO takes (shader, decl) or (shader, decl0, decl1, decl2, decl3, "
            "rasterizedStream)");
}

TEST(EffectErrors, ShaderErrors) {
  EXPECT_EQ(FirstError("VertexShader v = CompileShader(vs_5_0, Missing());\n"),
            "test.fx:1:40: unknown shader function 'Missing'");
  EXPECT_EQ(FirstError("float4 PS(uniform bool b) : SV_Target { return 1; }\n"
                       "PixelShader p = CompileShader(ps_5_0, PS(true, 2));\n"),
            "test.fx:2:39: 'PS' has 1 uniform parameter(s), but 2 argument(s) are given");
  EXPECT_EQ(FirstError("float4 PS(uniform bool b) : SV_Target { return 1; }\n"
                       "PixelShader p = CompileShader(ps_5_0, PS());\n"),
            "test.fx:2:39: no value for uniform parameter 'b' of 'PS'");
  EXPECT_EQ(FirstError("float4 VS() : SV_Position { return 0; }\n"
                       "technique11 T { pass P { SetPixelShader(CompileShader(vs_5_0, VS())); } }\n"),
            "test.fx:2:41: SetPixelShader needs a pixel shader, not a vertex shader");
  EXPECT_EQ(FirstError("float4 VS() : SV_Position { return 0; }\n"
                       "VertexShader v = CompileShader(vs_6_0, VS());\n"),
            "test.fx:2:32: unknown shader profile 'vs_6_0'");
  EXPECT_EQ(FirstError("technique11 T { pass P { SetVertexShader(nothing); } }\n"),
            "test.fx:1:42: unknown shader 'nothing'");
}

TEST(EffectErrors, PassErrors) {
  EXPECT_EQ(FirstError("technique11 T { pass P { SetBlendState(Missing, float4(0, 0, 0, 0), 0xFFFFFFFF); } }\n"),
            "test.fx:1:40: unknown BlendState 'Missing'");
  EXPECT_EQ(FirstError("BlendState B { };\ntechnique11 T { pass P { SetBlendState(B); } }\n"),
            "test.fx:2:26: SetBlendState takes 3 arguments: SetBlendState(state, blendFactor, sampleMask)");
  EXPECT_EQ(FirstError("technique11 T { pass P { VertexShader = NULL; } }\n"),
            "test.fx:1:26: unknown pass assignment 'VertexShader' (FX9-style state assignments are not supported; "
            "use SetVertexShader(...) etc.)");
  EXPECT_EQ(FirstError("technique11 T { pass P { SetDepthStencilState(NULL, -1); } }\n"),
            "test.fx:1:53: stencil reference must be an integer in 0..4294967295");
}

TEST(EffectErrors, SyntaxErrors) {
  EXPECT_EQ(FirstError("float4 a\nfloat4 b;\n"), "test.fx:2:1: expected ';' after 'a', found 'float4'");
  EXPECT_EQ(FirstError("cbuffer cb { float4 f(); };"), "test.fx:1:21: a function cannot be declared inside a cbuffer");
  EXPECT_EQ(FirstError("interface ILight { float3 Color(); };"),
            "test.fx:1:1: 'interface' (dynamic shader linkage) is not supported");
  EXPECT_EQ(FirstError("float a[0];"), "test.fx:1:9: array size must be an integer in 1..65536");
  EXPECT_EQ(FirstError("float4 x = float4(1, 2);"), "test.fx:1:12: invalid initializer of 'x': 'float4' needs 4 values, got 2");
  EXPECT_EQ(FirstError("Texture2D t = 1;"), "test.fx:1:13: a texture or buffer cannot have an initializer");
}

// fxc's X3502; glslang 12 would segfault on the InputPatch<T, 0> (docs/FUZZING.md, finding 1).
TEST(EffectErrors, PatchSizesOutsideOneTo32AreRefused) {
  EXPECT_EQ(FirstError("struct V { float4 p : POSITION; };\n"
                       "V HS(InputPatch<V, 0> patch, uint i : SV_OutputControlPointID) { return patch[i]; }\n"),
            "test.fx:2:20: InputPatch takes 1 to 32 control points, not 0");
  EXPECT_EQ(FirstError("struct V { float4 p : POSITION; };\n"
                       "#define POINTS 33\n"
                       "void DS(const OutputPatch<V, POINTS> patch) {}\n"),
            "test.fx:3:30: OutputPatch takes 1 to 32 control points, not 33");
}

}  // namespace
}  // namespace fx
