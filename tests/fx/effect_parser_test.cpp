// The realistic legacy effect (data/scene.fx) and the other FX syntax forms.
#include "fx/effect_parser.h"
#include "fx/state_blocks.h"

#include <gtest/gtest.h>

#include <sstream>

#include "test_util.h"

namespace fx {
namespace {

using test::FloatAt;
using test::MemoryFiles;
using test::MustFail;
using test::MustParse;
using test::UIntAt;

const std::string kDataDir = FX_TEST_DATA_DIR;
const std::string kScene = kDataDir + "/scene.fx";

class SceneEffect : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    Result<EffectAst> r = ParseEffectFile(kScene, {});
    if (auto* e = std::get_if<std::vector<ParseError>>(&r)) {
      FAIL() << test::FormatErrors(*e);
    }
    ast_ = new EffectAst(std::get<EffectAst>(std::move(r)));
  }
  static void TearDownTestSuite() {
    delete ast_;
    ast_ = nullptr;
  }
  void SetUp() override { ASSERT_NE(ast_, nullptr); }

  static const EffectAst& Ast() { return *ast_; }

  // The line of the HLSL that contains `needle`.
  static std::string HlslLineWith(const std::string& needle) {
    std::istringstream in(ast_->hlsl);
    for (std::string line; std::getline(in, line);) {
      if (line.find(needle) != std::string::npos) return line;
    }
    return "<no line with " + needle + ">";
  }

  static EffectAst* ast_;
};
EffectAst* SceneEffect::ast_ = nullptr;

TEST_F(SceneEffect, ConstantBuffersWithDefaults) {
  ASSERT_EQ(Ast().cbuffers.size(), 3u);
  const ConstantBuffer& globals = Ast().cbuffers[0];
  EXPECT_EQ(globals.name, "$Globals");
  ASSERT_EQ(globals.variables.size(), 2u);
  EXPECT_EQ(globals.variables[0].name, "g_fGlobalScale");
  EXPECT_EQ(globals.variables[0].offset, 0u);
  EXPECT_EQ(globals.variables[1].name, "g_vFogColor");
  EXPECT_EQ(globals.variables[1].offset, 16u);
  EXPECT_EQ(globals.variables[1].semantic, "FOGCOLOR");
  EXPECT_EQ(globals.size, 32u);
  EXPECT_EQ(FloatAt(globals.defaults, 0), 2.0f);
  EXPECT_EQ(FloatAt(globals.defaults, 16), 0.5f);
  EXPECT_EQ(FloatAt(globals.defaults, 20), 0.6f);
  EXPECT_EQ(FloatAt(globals.defaults, 28), 1.0f);

  const ConstantBuffer& frame = Ast().cbuffers[1];
  EXPECT_EQ(frame.name, "cbPerFrame");
  ASSERT_TRUE(frame.reg);
  EXPECT_EQ(frame.reg->kind, 'b');
  EXPECT_EQ(frame.reg->index, 0u);
  ASSERT_EQ(frame.variables.size(), 4u);
  const ConstantVariable& wvp = frame.variables[0];
  EXPECT_EQ(wvp.name, "g_mWorldViewProj");
  EXPECT_EQ(wvp.semantic, "WORLDVIEWPROJECTION");
  EXPECT_EQ(wvp.type.cls, VariableType::Class::Matrix);
  EXPECT_EQ(wvp.type.size, 64u);
  EXPECT_FALSE(wvp.hasInitializer);
  EXPECT_EQ(frame.variables[1].offset, 64u);  // g_vLightDir
  EXPECT_EQ(frame.variables[2].offset, 76u);  // g_fTime shares its register
  EXPECT_EQ(frame.variables[3].offset, 80u);  // g_LightColors[2]
  EXPECT_EQ(frame.variables[3].type.arrayDims, std::vector<uint32_t>{2});
  EXPECT_EQ(frame.size, 112u);
  std::vector<float> expected = {0, -1, 0, 1.5f, 1, 0, 0, 1, 0, 1, 0, 1};
  for (size_t i = 0; i < expected.size(); ++i) EXPECT_EQ(FloatAt(frame.defaults, 64 + i * 4), expected[i]) << i;
  for (size_t i = 0; i < 64; i += 4) EXPECT_EQ(UIntAt(frame.defaults, i), 0u);

  const auto& time = frame.variables[2].annotations;
  ASSERT_EQ(time.size(), 3u);
  EXPECT_EQ(time[0].type, "string");
  EXPECT_EQ(time[0].name, "UIName");
  EXPECT_EQ(time[0].stringValue, "Time");
  EXPECT_EQ(time[2].name, "UIMax");
  EXPECT_EQ(time[2].values, std::vector<double>{100});

  const ConstantBuffer& object = Ast().cbuffers[2];
  EXPECT_EQ(object.name, "cbPerObject");
  EXPECT_FALSE(object.reg);
  EXPECT_EQ(object.size, 32u);
  EXPECT_EQ(FloatAt(object.defaults, 4), 0.5f);
  EXPECT_EQ(FloatAt(object.defaults, 8), 0.25f);
  EXPECT_EQ(UIntAt(object.defaults, 16), 0xFFFFFFFFu);
  EXPECT_EQ(UIntAt(object.defaults, 20), static_cast<uint32_t>(-3));
}

TEST_F(SceneEffect, ResourcesStringsAndSamplers) {
  ASSERT_EQ(Ast().resources.size(), 3u);
  EXPECT_EQ(Ast().resources[0].name, "g_txDiffuse");
  EXPECT_EQ(Ast().resources[0].kind, ResourceKind::Texture2D);
  ASSERT_EQ(Ast().resources[0].annotations.size(), 1u);
  EXPECT_EQ(Ast().resources[0].annotations[0].stringValue, "diffuse.dds");
  EXPECT_EQ(Ast().resources[1].kind, ResourceKind::TextureCube);
  ASSERT_TRUE(Ast().resources[1].reg);
  EXPECT_EQ(Ast().resources[1].reg->kind, 't');
  EXPECT_EQ(Ast().resources[1].reg->index, 3u);
  EXPECT_EQ(Ast().resources[2].kind, ResourceKind::StructuredBuffer);
  EXPECT_EQ(Ast().resources[2].templateArgs, "float4");

  ASSERT_EQ(Ast().strings.size(), 1u);
  EXPECT_EQ(Ast().strings[0].name, "g_Description");
  EXPECT_EQ(Ast().strings[0].values, std::vector<std::string>{"Scene effect"});

  ASSERT_EQ(Ast().samplers.size(), 2u);
  const SamplerVariable& linear = Ast().samplers[0];
  EXPECT_FALSE(linear.comparison);
  ASSERT_EQ(linear.descs.size(), 1u);
  rhi::SAMPLER_DESC want = DefaultSamplerDesc();
  want.AddressU = rhi::TEXTURE_ADDRESS_WRAP;
  want.AddressV = rhi::TEXTURE_ADDRESS_WRAP;
  EXPECT_TRUE(test::SameDesc(linear.descs[0], want));

  const SamplerVariable& shadow = Ast().samplers[1];
  EXPECT_TRUE(shadow.comparison);
  const rhi::SAMPLER_DESC& s = shadow.descs[0];
  EXPECT_EQ(s.Filter, rhi::FILTER_COMPARISON_MIN_MAG_LINEAR_MIP_POINT);
  EXPECT_EQ(s.AddressU, rhi::TEXTURE_ADDRESS_BORDER);
  EXPECT_EQ(s.AddressW, rhi::TEXTURE_ADDRESS_CLAMP);
  EXPECT_EQ(s.ComparisonFunc, rhi::COMPARISON_LESS_EQUAL);
  EXPECT_EQ(s.MaxAnisotropy, 1u);
  EXPECT_EQ(s.BorderColor[0], 1.0f);
  EXPECT_EQ(s.BorderColor[3], 0.0f);
}

TEST_F(SceneEffect, StateObjects) {
  ASSERT_EQ(Ast().blendStates.size(), 2u);
  rhi::BLEND_DESC add = DefaultBlendDesc();
  add.RenderTarget[0] = {rhi::TRUE,         rhi::BLEND_SRC_ALPHA, rhi::BLEND_ONE, rhi::BLEND_OP_ADD,
                         rhi::BLEND_ZERO,   rhi::BLEND_ZERO,      rhi::BLEND_OP_ADD, 0x0F};
  add.RenderTarget[1].BlendEnable = rhi::TRUE;
  add.RenderTarget[1].DestBlend = rhi::BLEND_INV_SRC_ALPHA;
  add.RenderTarget[1].RenderTargetWriteMask = 0x07;
  EXPECT_EQ(Ast().blendStates[0].name, "AdditiveBlending");
  EXPECT_TRUE(test::SameDesc(Ast().blendStates[0].descs[0], add));
  EXPECT_EQ(Ast().blendStates[0].descs[0].IndependentBlendEnable, rhi::TRUE);
  rhi::BLEND_DESC none = DefaultBlendDesc();
  EXPECT_TRUE(test::SameDesc(Ast().blendStates[1].descs[0], none));

  ASSERT_EQ(Ast().depthStencilStates.size(), 2u);
  const rhi::DEPTH_STENCIL_DESC& off = Ast().depthStencilStates[0].descs[0];
  EXPECT_EQ(off.DepthEnable, rhi::FALSE);
  EXPECT_EQ(off.DepthWriteMask, rhi::DEPTH_WRITE_MASK_ZERO);
  rhi::DEPTH_STENCIL_DESC mark = DefaultDepthStencilDesc();
  mark.DepthFunc = rhi::COMPARISON_LESS_EQUAL;
  mark.StencilEnable = rhi::TRUE;
  mark.StencilWriteMask = 0x0F;
  mark.FrontFace.StencilPassOp = rhi::STENCIL_OP_INCR_SAT;
  mark.BackFace.StencilFailOp = rhi::STENCIL_OP_ZERO;
  EXPECT_TRUE(test::SameDesc(Ast().depthStencilStates[1].descs[0], mark));

  ASSERT_EQ(Ast().rasterizerStates.size(), 1u);
  rhi::RASTERIZER_DESC wire = DefaultRasterizerDesc();
  wire.FillMode = rhi::FILL_WIREFRAME;
  wire.CullMode = rhi::CULL_NONE;
  wire.FrontCounterClockwise = rhi::TRUE;
  wire.DepthBias = -10;
  wire.SlopeScaledDepthBias = 1.5f;
  EXPECT_TRUE(test::SameDesc(Ast().rasterizerStates[0].descs[0], wire));
}

TEST_F(SceneEffect, ShadersAndVariants) {
  const auto& shaders = Ast().shaders;
  ASSERT_EQ(shaders.size(), 8u);
  EXPECT_EQ(shaders[0].profile, "vs_5_0");
  EXPECT_EQ(shaders[0].function, "VSMain");
  EXPECT_EQ(shaders[0].entryPoint, "VSMain");
  EXPECT_FALSE(shaders[0].hasStreamOutput);

  const CompiledShader& so = shaders[1];
  EXPECT_EQ(so.stage, ShaderStage::Geometry);
  EXPECT_EQ(so.entryPoint, "GSMain");
  EXPECT_TRUE(so.hasStreamOutput);
  EXPECT_EQ(so.soDeclarations[0], "SV_Position.xyzw; 1:NORMAL.xyz; $SKIP.x; TEXCOORD0.xy");
  EXPECT_EQ(so.rasterizedStream, 0u);
  const auto& e = so.streamOutput.Entries();
  ASSERT_EQ(e.size(), 4u);
  EXPECT_STREQ(e[0].SemanticName, "SV_Position");
  EXPECT_EQ(e[0].ComponentCount, 4);
  EXPECT_STREQ(e[1].SemanticName, "NORMAL");
  EXPECT_EQ(e[1].OutputSlot, 1);
  EXPECT_EQ(e[1].ComponentCount, 3);
  EXPECT_EQ(e[2].SemanticName, nullptr);
  EXPECT_EQ(e[2].ComponentCount, 1);
  EXPECT_STREQ(e[3].SemanticName, "TEXCOORD");
  EXPECT_EQ(e[3].SemanticIndex, 0u);
  EXPECT_EQ(e[3].ComponentCount, 2);
  EXPECT_EQ(so.streamOutput.Strides()[0], 28u);
  EXPECT_EQ(so.streamOutput.Strides()[1], 12u);

  const CompiledShader& multi = shaders[2];
  EXPECT_EQ(multi.rasterizedStream, 2u);
  EXPECT_EQ(multi.soDeclarations[2], "1:TEXCOORD2.zw");
  ASSERT_EQ(multi.streamOutput.Entries().size(), 2u);
  const rhi::SO_DECLARATION_ENTRY& tex = multi.streamOutput.Entries()[1];
  EXPECT_EQ(tex.Stream, 2u);
  EXPECT_EQ(tex.SemanticIndex, 2u);
  EXPECT_EQ(tex.StartComponent, 2);
  EXPECT_EQ(tex.ComponentCount, 2);
  EXPECT_EQ(tex.OutputSlot, 1);

  EXPECT_EQ(shaders[3].profile, "ps_5_0");
  EXPECT_EQ(shaders[3].uniformArgs, (std::vector<std::string>{"true", "2"}));  // default of nLights
  EXPECT_EQ(shaders[3].entryPoint, "fx_variant_0");
  EXPECT_EQ(shaders[4].profile, "ps_4_0");
  EXPECT_EQ(shaders[4].uniformArgs, (std::vector<std::string>{"false", "1"}));
  EXPECT_EQ(shaders[4].entryPoint, "fx_variant_1");
  EXPECT_EQ(shaders[6].soDeclarations[0], "POSITION.xyz");
  EXPECT_EQ(shaders[7].entryPoint, "fx_variant_0");  // same arguments, same variant

  ASSERT_EQ(Ast().shaderVariables.size(), 3u);
  EXPECT_EQ(Ast().shaderVariables[0].name, "g_vsMain");
  EXPECT_EQ(Ast().shaderVariables[0].stage, ShaderStage::Vertex);
  EXPECT_EQ(Ast().shaderVariables[0].shaders, std::vector<int>{0});
  EXPECT_EQ(Ast().shaderVariables[1].stage, ShaderStage::Geometry);
  EXPECT_EQ(Ast().shaderVariables[1].shaders, std::vector<int>{1});
  EXPECT_EQ(Ast().shaderVariables[2].shaders, std::vector<int>{2});

  // Each variant's call sits on its CompileShader's line (#line), the first
  // uniform argument at its column, so that errors in arguments point there.
  const std::string line140 = "#line 140 \"" + kScene + "\"\n";
  EXPECT_NE(Ast().hlsl.find("// fx_variant_0: PSMain(true, 2)\n" + line140 +
                            "float4 fx_variant_0(PSInput input) : SV_Target {\n" + line140),
            std::string::npos)
      << Ast().hlsl;
  std::string call = HlslLineWith("return PSMain(input, true, 2); }");
  EXPECT_EQ(call.find("true"), std::string("        SetPixelShader(CompileShader(ps_5_0, PSMain(").size()) << call;
  EXPECT_NE(Ast().hlsl.find("// fx_variant_1: PSMain(false, 1)\n#line 148 \""), std::string::npos) << Ast().hlsl;
  EXPECT_NE(HlslLineWith("return PSMain(input, false, 1); }").find("return"), std::string::npos);
}

TEST_F(SceneEffect, TechniquesAndPasses) {
  ASSERT_EQ(Ast().techniques.size(), 2u);
  const Technique& render = Ast().techniques[0];
  EXPECT_EQ(render.name, "Render");
  EXPECT_EQ(render.version, 11);
  ASSERT_EQ(render.annotations.size(), 1u);
  EXPECT_EQ(render.annotations[0].stringValue, "Pass=P0;");
  ASSERT_EQ(render.passes.size(), 2u);

  const Pass& p0 = render.passes[0];
  EXPECT_EQ(p0.name, "P0");
  EXPECT_EQ(p0.where, (SourceLocation{kScene, 136, 5}));
  ASSERT_EQ(p0.assignments.size(), 6u);
  auto vs = std::get<ShaderAssignment>(p0.assignments[0].value);
  EXPECT_EQ(vs.stage, ShaderStage::Vertex);
  EXPECT_EQ(vs.shader, 0);
  EXPECT_EQ(vs.variable, "g_vsMain");
  auto gs = std::get<ShaderAssignment>(p0.assignments[1].value);
  EXPECT_EQ(gs.stage, ShaderStage::Geometry);
  EXPECT_EQ(gs.shader, -1);
  auto ps = std::get<ShaderAssignment>(p0.assignments[2].value);
  EXPECT_EQ(ps.shader, 3);
  EXPECT_EQ(ps.variable, "");
  auto blend = std::get<BlendStateAssignment>(p0.assignments[3].value);
  EXPECT_EQ(blend.state.variable, "NoBlending");
  EXPECT_EQ(blend.blendFactor, (std::array<float, 4>{0, 0, 0, 0}));
  EXPECT_EQ(blend.sampleMask, 0xFFFFFFFFu);
  auto ds = std::get<DepthStencilStateAssignment>(p0.assignments[4].value);
  EXPECT_EQ(ds.state.variable, "StencilMark");
  EXPECT_EQ(ds.stencilRef, 1u);
  auto rs = std::get<RasterizerStateAssignment>(p0.assignments[5].value);
  EXPECT_EQ(rs.state.variable, "");
  EXPECT_EQ(p0.assignments[3].where, (SourceLocation{kScene, 141, 9}));

  const Pass& p1 = render.passes[1];
  ASSERT_EQ(p1.annotations.size(), 1u);
  EXPECT_EQ(p1.annotations[0].name, "Wire");
  EXPECT_EQ(p1.annotations[0].values, std::vector<double>{1});
  ASSERT_EQ(p1.assignments.size(), 5u);
  EXPECT_EQ(std::get<ShaderAssignment>(p1.assignments[1].value).shader, 4);
  auto blend1 = std::get<BlendStateAssignment>(p1.assignments[2].value);
  EXPECT_EQ(blend1.state.variable, "AdditiveBlending");
  EXPECT_EQ(blend1.blendFactor, (std::array<float, 4>{1, 1, 1, 1}));
  EXPECT_EQ(blend1.sampleMask, 0xFu);
  EXPECT_EQ(std::get<RasterizerStateAssignment>(p1.assignments[4].value).state.variable, "Wireframe");

  const Technique& streamOut = Ast().techniques[1];
  ASSERT_EQ(streamOut.passes.size(), 2u);
  auto gs0 = std::get<ShaderAssignment>(streamOut.passes[0].assignments[1].value);
  EXPECT_EQ(gs0.variable, "g_gsStreamOut");
  EXPECT_EQ(gs0.shader, 1);
  EXPECT_EQ(std::get<ShaderAssignment>(streamOut.passes[0].assignments[2].value).shader, -1);
  const auto& p1Assign = streamOut.passes[1].assignments;
  ASSERT_EQ(p1Assign.size(), 3u);
  EXPECT_EQ(std::get<ShaderAssignment>(p1Assign[0].value).shader, 5);
  EXPECT_EQ(std::get<ShaderAssignment>(p1Assign[1].value).shader, 6);
  EXPECT_EQ(std::get<ShaderAssignment>(p1Assign[2].value).shader, 7);
}

TEST_F(SceneEffect, HlslKeepsLayoutAndDropsEffectSyntax) {
  const std::string& hlsl = Ast().hlsl;
  const std::string common = kDataDir + "/common.fxh";
  EXPECT_EQ(hlsl.rfind("#line 8 \"" + common + "\"\nstruct VSInput\n", 0), 0u) << hlsl.substr(0, 200);
  EXPECT_NE(hlsl.find("#line 6 \"" + kScene + "\"\n#pragma warning(disable : 3571)\n"), std::string::npos);
  EXPECT_EQ(HlslLineWith("g_mWorldViewProj :"), "<no line with g_mWorldViewProj :>");
  EXPECT_EQ(HlslLineWith("g_mWorldViewProj"), "    float4x4 g_mWorldViewProj" + std::string(22, ' ') + ";");
  EXPECT_EQ(HlslLineWith("g_vLightDir"), "    float3   g_vLightDir" + std::string(28, ' ') + ";");  // " = float3(0.0f, -1.0f, 0.0f)"
  EXPECT_EQ(HlslLineWith("g_fTime"), "    float    g_fTime" + std::string(71, ' ') + ";");
  EXPECT_EQ(HlslLineWith("g_fGlobalScale"), "       float g_fGlobalScale      ;");  // "shared", " = 2.0"
  EXPECT_EQ(HlslLineWith("g_txDiffuse"), "Texture2D g_txDiffuse" + std::string(41, ' ') + ";");
  EXPECT_EQ(HlslLineWith("g_samLinear"), "SamplerState g_samLinear");
  EXPECT_EQ(HlslLineWith("cbuffer cbPerFrame"), "cbuffer cbPerFrame : register(b0)");
  EXPECT_EQ(HlslLineWith("float4 PSMain("),
            "float4 PSMain(PSInput input,         bool bTexture,         int nLights = 2         ) : SV_Target");
  for (const char* gone : {"technique11", "pass ", "BlendState", "DepthStencilState", "RasterizerState", "CompileShader",
                           "ConstructGSWithSO", "string ", "Filter", "UIName", "shared", "= float3", "sampler_state"}) {
    EXPECT_EQ(hlsl.find(gone), std::string::npos) << gone;
  }
  // Code outside macros keeps its line (through the #line after the include) and column.
  std::istringstream in(hlsl);
  std::string line;
  int logical = 0;
  bool inScene = false;
  while (std::getline(in, line)) {
    if (line.rfind("#line ", 0) == 0) {
      inScene = line.find(kScene) != std::string::npos;
      logical = std::stoi(line.substr(6));
      continue;
    }
    if (inScene && line.find("PSInput VSMain(VSInput input)") != std::string::npos) {
      EXPECT_EQ(logical, 99);
      EXPECT_EQ(line, "PSInput VSMain(VSInput input)");
    }
    if (inScene && line.find("[maxvertexcount(3)]") != std::string::npos) {
      EXPECT_EQ(logical, 119);
    }
    ++logical;
  }
}

TEST(EffectParser, ArraysOfStatesSamplersAndShaders) {
  EffectAst ast = MustParse(
      "Texture2D tex;\n"
      "SamplerState samplers[2] = { sampler_state { Filter = ANISOTROPIC; MaxAnisotropy = 8; },\n"
      "                             { Texture = <tex>; AddressU = MIRROR; } };\n"
      "sampler legacy = sampler_state { Texture = (tex); MipLODBias = -0.5; MinLOD = 1; };\n"
      "BlendState blends[2] { { BlendEnable[0] = TRUE; }, { AlphaToCoverageEnable = TRUE; } };\n"
      "float4 VS(uint id : SV_VertexID) : SV_Position { return 0; }\n"
      "float4 PS() : SV_Target { return 1; }\n"
      "VertexShader shaders[2] = { CompileShader(vs_4_0, VS()), NULL };\n"
      "PixelShader ps = compile ps_4_0_level_9_3 PS();\n"
      "technique10 T10 { pass { SetVertexShader(shaders[0]); SetPixelShader(ps);\n"
      "                         SetBlendState(blends[1], float4(0, 0, 0, 0), 0xFFFFFFFF); } }\n");
  ASSERT_EQ(ast.samplers.size(), 2u);
  ASSERT_EQ(ast.samplers[0].descs.size(), 2u);
  EXPECT_EQ(ast.samplers[0].descs[0].Filter, rhi::FILTER_ANISOTROPIC);
  EXPECT_EQ(ast.samplers[0].descs[0].MaxAnisotropy, 8u);
  EXPECT_EQ(ast.samplers[0].descs[1].AddressU, rhi::TEXTURE_ADDRESS_MIRROR);
  EXPECT_EQ(ast.samplers[0].textures, (std::vector<std::string>{"", "tex"}));
  EXPECT_EQ(ast.samplers[1].textures, std::vector<std::string>{"tex"});
  EXPECT_EQ(ast.samplers[1].descs[0].MipLODBias, -0.5f);
  EXPECT_EQ(ast.samplers[1].descs[0].MinLOD, 1.0f);
  ASSERT_EQ(ast.blendStates[0].descs.size(), 2u);
  EXPECT_EQ(ast.blendStates[0].descs[0].RenderTarget[0].BlendEnable, rhi::TRUE);
  EXPECT_EQ(ast.blendStates[0].descs[1].AlphaToCoverageEnable, rhi::TRUE);
  EXPECT_EQ(ast.shaderVariables[0].shaders, (std::vector<int>{0, -1}));
  EXPECT_EQ(ast.shaders[1].profile, "ps_4_0_level_9_3");
  const Technique& t = ast.techniques[0];
  EXPECT_EQ(t.version, 10);
  EXPECT_EQ(t.passes[0].name, "");
  EXPECT_EQ(std::get<ShaderAssignment>(t.passes[0].assignments[0].value).shader, 0);
  EXPECT_EQ(std::get<ShaderAssignment>(t.passes[0].assignments[1].value).variable, "ps");
  EXPECT_EQ(std::get<BlendStateAssignment>(t.passes[0].assignments[2].value).state.element, 1u);
  EXPECT_NE(ast.hlsl.find("SamplerState samplers[2]"), std::string::npos);
  EXPECT_NE(ast.hlsl.find("sampler legacy"), std::string::npos);
  EXPECT_EQ(ast.hlsl.find("Texture ="), std::string::npos);
}

TEST(EffectParser, GroupsAndTechniqueKeywords) {
  EffectAst ast = MustParse(
      "float4 PS() : SV_Target { return 1; }\n"
      "fxgroup Shadows < string Name = \"shadow\"; > {\n"
      "  technique11 Cast { pass P { SetPixelShader(CompileShader(ps_5_0, PS())); } }\n"
      "  technique11 Receive { }\n"
      "}\n"
      "technique Plain { pass A { SetComputeShader(NULL); SetHullShader(NULL); SetDomainShader(NULL); } }\n");
  ASSERT_EQ(ast.techniques.size(), 3u);
  EXPECT_EQ(ast.techniques[0].group, "Shadows");
  EXPECT_EQ(ast.techniques[1].name, "Receive");
  EXPECT_EQ(ast.techniques[1].group, "Shadows");
  EXPECT_EQ(ast.techniques[2].group, "");
  ASSERT_EQ(ast.techniques[2].passes[0].assignments.size(), 3u);
  EXPECT_EQ(std::get<ShaderAssignment>(ast.techniques[2].passes[0].assignments[0].value).stage, ShaderStage::Compute);
  EXPECT_EQ(ast.hlsl.find("fxgroup"), std::string::npos);
  EXPECT_EQ(ast.hlsl.find("technique"), std::string::npos);
}

TEST(EffectParser, VariantsKeepAttributesAndNonUniformParameters) {
  EffectAst ast = MustParse(
      "struct V { float4 p : SV_Position; };\n"
      "[maxvertexcount(4)]\n"
      "void GS(point V input[1], inout TriangleStream<V> s, uniform float size, uniform bool flip = false)\n"
      "{ s.Append(input[0]); }\n"
      "[numthreads(8, 8, 1)]\n"
      "void CS(uint3 id : SV_DispatchThreadID, uniform int mode) { }\n"
      "GeometryShader g = ConstructGSWithSO(CompileShader(gs_5_0, GS(2.5)), \"SV_Position.xy\");\n"
      "ComputeShader c = CompileShader(cs_5_0, CS(1 + 2));\n");
  ASSERT_EQ(ast.shaders.size(), 2u);
  EXPECT_EQ(ast.shaders[0].uniformArgs, (std::vector<std::string>{"2.5", "false"}));
  EXPECT_EQ(ast.shaders[0].entryPoint, "fx_variant_0");
  EXPECT_EQ(ast.shaders[1].entryPoint, "fx_variant_1");
  // Each on one line at its CompileShader's position, so an error in an argument points there.
  // The first uniform argument lands at its column on the CompileShader's line:
  // `GeometryShader g = ConstructGSWithSO(CompileShader(gs_5_0, GS(` is 62 characters.
  EXPECT_NE(ast.hlsl.find("// fx_variant_0: GS(2.5, false)\n"
                          "#line 7 \"test.fx\"\n"
                          "[maxvertexcount(4)] void fx_variant_0(point V input[1], inout TriangleStream<V> s) {\n"
                          "#line 7 \"test.fx\"\n" +
                          std::string(62 - std::string("GS(input, s, ").size(), ' ') +
                          "GS(input, s, 2.5, false); }\n"),
            std::string::npos)
      << ast.hlsl;
  EXPECT_NE(ast.hlsl.find("#line 8 \"test.fx\"\n"
                          "[numthreads(8, 8, 1)] void fx_variant_1(uint3 id : SV_DispatchThreadID) {\n"
                          "#line 8 \"test.fx\"\n"),
            std::string::npos)
      << ast.hlsl;
  EXPECT_NE(ast.hlsl.find("CS(id, (1 + 2)); }\n"), std::string::npos) << ast.hlsl;
}

// fxc: a static inside a cbuffer is no member (the layout skips it) but sizes
// arrays; the HLSL gets it before the cbuffer, between #line directives.
TEST(EffectParser, CbufferStaticsAreHoistedOutOfTheLayout) {
  EffectAst ast = MustParse(
      "cbuffer PerFrame\n"
      "{\n"
      "    float4 tint;\n"
      "    static const int kCount = 4;\n"
      "    float4 items[kCount];\n"
      "};\n");
  ASSERT_EQ(ast.cbuffers.size(), 1u);
  const ConstantBuffer& cb = ast.cbuffers[0];
  ASSERT_EQ(cb.variables.size(), 2u);
  EXPECT_EQ(cb.variables[1].name, "items");
  EXPECT_EQ(cb.variables[1].offset, 16u);
  EXPECT_EQ(cb.variables[1].type.arrayDims, (std::vector<uint32_t>{4}));
  EXPECT_EQ(cb.size, 80u);
  EXPECT_NE(ast.hlsl.find("#line 4 \"test.fx\"\nstatic const int kCount = 4;\n#line 1 \"test.fx\"\ncbuffer PerFrame"),
            std::string::npos)
      << ast.hlsl;
  EXPECT_EQ(ast.hlsl.find("static", ast.hlsl.find("cbuffer")), std::string::npos) << ast.hlsl;
}

// PS() and PS(uniform int) in one file: each CompileShader picks its overload
// by the uniform arguments, and both compile through a wrapper (glslang finds
// no entry point by an overloaded name).
TEST(EffectParser, OverloadsArePickedByTheirUniformArguments) {
  EffectAst ast = MustParse(
      "float4 PS() : SV_Target { return 1; }\n"
      "float4 PS(uniform int index, uniform float scale = 2) : SV_Target { return index * scale; }\n"
      "float4 PS(uniform int index) : SV_Target { return index; }\n"
      "PixelShader a = CompileShader(ps_5_0, PS());\n"
      "PixelShader b = CompileShader(ps_5_0, PS(3));\n"
      "PixelShader c = CompileShader(ps_5_0, PS(3, 4));\n");
  ASSERT_EQ(ast.shaders.size(), 3u);
  EXPECT_EQ(ast.shaders[0].entryPoint, "fx_variant_0");
  EXPECT_NE(ast.hlsl.find("fx_variant_0()"), std::string::npos);
  EXPECT_NE(ast.hlsl.find("return PS();"), std::string::npos) << ast.hlsl;
  EXPECT_EQ(ast.shaders[1].uniformArgs, (std::vector<std::string>{"3"}));  // the exact overload, not the defaulted one
  EXPECT_NE(ast.hlsl.find("// fx_variant_1: PS(3)\n"), std::string::npos) << ast.hlsl;
  EXPECT_EQ(ast.shaders[2].uniformArgs, (std::vector<std::string>{"3", "4"}));
}

TEST(EffectParser, UavsAndTemplatedResources) {
  EffectAst ast = MustParse(
      "struct Particle { float3 pos; };\n"
      "RWStructuredBuffer<Particle> particles : register(u1);\n"
      "Texture2DMS<float4, 8> msaa;\n"
      "RWTexture2D<unorm float4> target;\n"
      "AppendStructuredBuffer<uint> list;\n"
      "ByteAddressBuffer raw : register(t2, space1);\n");
  ASSERT_EQ(ast.resources.size(), 5u);
  EXPECT_TRUE(IsUnorderedAccess(ast.resources[0].kind));
  EXPECT_EQ(ast.resources[0].templateArgs, "Particle");
  EXPECT_EQ(ast.resources[0].reg->kind, 'u');
  EXPECT_EQ(ast.resources[1].kind, ResourceKind::Texture2DMS);
  EXPECT_EQ(ast.resources[1].templateArgs, "float4, 8");
  EXPECT_EQ(ast.resources[2].templateArgs, "unorm float4");
  EXPECT_FALSE(IsUnorderedAccess(ast.resources[4].kind));
  EXPECT_EQ(ast.resources[4].reg->space, 1u);
  EXPECT_TRUE(ast.cbuffers.empty());
}

TEST(EffectParser, PragmasMayAppearAnywhere) {
  EffectAst ast = MustParse(
      "cbuffer cb {\n"
      "  float4x4 a;\n"
      "#pragma pack_matrix(row_major)\n"
      "  float4x4 b;\n"
      "};\n"
      "technique11 T {\n"
      "#pragma warning(disable : 1234)\n"
      "  pass P { }\n"
      "}\n");
  ASSERT_EQ(ast.cbuffers.size(), 1u);
  EXPECT_FALSE(ast.cbuffers[0].variables[0].type.rowMajor);
  EXPECT_TRUE(ast.cbuffers[0].variables[1].type.rowMajor);
  ASSERT_EQ(ast.techniques.size(), 1u);
  EXPECT_EQ(ast.techniques[0].passes.size(), 1u);
  // Blanking the technique keeps the pragma line for glslang.
  EXPECT_NE(ast.hlsl.find("\n#pragma warning(disable : 1234)\n"), std::string::npos);
  EXPECT_EQ(ast.hlsl.find("pass"), std::string::npos);
}

TEST(EffectParser, IncludeDirectoriesAndDefinesFromOptions) {
  ParseOptions options = MemoryFiles({{"/inc/states.fxh", "BlendState B { BlendEnable[0] = ENABLE; };\n"}});
  options.includeDirs = {"/inc"};
  options.defines = {{"ENABLE", "TRUE"}};
  EffectAst ast = MustParse("#include <states.fxh>\n", options, "/src/main.fx");
  ASSERT_EQ(ast.blendStates.size(), 1u);
  EXPECT_EQ(ast.blendStates[0].descs[0].RenderTarget[0].BlendEnable, rhi::TRUE);
  EXPECT_EQ(ast.blendStates[0].where, (SourceLocation{"/inc/states.fxh", 1, 12}));
}

}  // namespace
}  // namespace fx
