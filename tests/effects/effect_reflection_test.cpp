// FX11's reflection that tools use: annotations (technique, pass, variable) as
// read-only variables, and EffectPass::Get*ShaderDesc with
// EffectShaderVariable::GetShaderDesc. Over the construct files (constructs/).
#include "effect_test_util.h"

namespace effects_test {
namespace {

const std::string kConstructs = CONSTRUCTS_DIR;
constexpr uint32_t kSpirvMagic = 0x07230203;

std::string StringOf(fx::EffectVariable* v) {
  rhi::LPCSTR s = nullptr;
  EXPECT_EQ(v->AsString()->GetString(&s), rhi::S_OK);
  return s ? s : "";
}

fx::EFFECT_SHADER_DESC ShaderDescOf(const fx::PASS_SHADER_DESC& pass) {
  fx::EFFECT_SHADER_DESC desc;
  EXPECT_TRUE(pass.pShaderVariable && pass.pShaderVariable->IsValid());
  if (pass.pShaderVariable) {
    EXPECT_EQ(pass.pShaderVariable->GetShaderDesc(pass.ShaderIndex, &desc), rhi::S_OK);
  }
  return desc;
}

TEST_F(EffectTest, AnnotationsOfTechniquesPassesAndVariables) {
  auto effect = Load(kConstructs + "/groups_annotations_strings.fx");
  ASSERT_TRUE(effect);
  fx::EFFECT_DESC ed;
  ASSERT_EQ(effect->GetDesc(&ed), rhi::S_OK);
  EXPECT_EQ(ed.Techniques, 3u);
  EXPECT_EQ(ed.Groups, 1u);  // fxgroup Lighting
  fx::EffectTechnique* forward = effect->GetTechniqueByName("Forward");
  fx::TECHNIQUE_DESC td;
  ASSERT_EQ(forward->GetDesc(&td), rhi::S_OK);
  EXPECT_EQ(td.Annotations, 2u);
  EXPECT_EQ(StringOf(forward->GetAnnotationByName("Mode")), "forward");
  int order = 0;
  EXPECT_EQ(forward->GetAnnotationByIndex(1)->AsScalar()->GetInt(&order), rhi::S_OK);
  EXPECT_EQ(order, 1);
  EXPECT_FALSE(forward->GetAnnotationByIndex(2)->IsValid());
  EXPECT_FALSE(forward->GetAnnotationByName("Nope")->IsValid());
  EXPECT_FALSE(forward->GetAnnotationByName("Mode")->AsScalar()->IsValid());  // a string is no scalar

  fx::EffectPass* main = forward->GetPassByName("Main");
  fx::PASS_DESC pd;
  ASSERT_EQ(main->GetDesc(&pd), rhi::S_OK);
  EXPECT_EQ(pd.Annotations, 2u);
  EXPECT_EQ(StringOf(main->GetAnnotationByIndex(0)), "none");
  float tint[4] = {};
  EXPECT_EQ(main->GetAnnotationByName("Tint")->AsVector()->GetFloatVector(tint), rhi::S_OK);
  EXPECT_EQ(std::vector<float>(tint, tint + 4), (std::vector<float>{1, 2, 3, 4}));
  EXPECT_FALSE(effect->GetTechniqueByName("Nope")->GetAnnotationByIndex(0)->IsValid());

  fx::EffectVariable* color = effect->GetVariableByName("g_color");
  fx::EFFECT_VARIABLE_DESC vd;
  ASSERT_EQ(color->GetDesc(&vd), rhi::S_OK);
  EXPECT_EQ(vd.Annotations, 5u);
  fx::EffectVariable* uiName = color->GetAnnotationByName("UIName");
  EXPECT_EQ(StringOf(uiName), "Color");
  ASSERT_EQ(uiName->GetDesc(&vd), rhi::S_OK);
  EXPECT_STREQ(vd.Name, "UIName");
  float uiMax = 0;
  EXPECT_EQ(color->GetAnnotationByName("UIMax")->AsScalar()->GetFloat(&uiMax), rhi::S_OK);
  EXPECT_EQ(uiMax, 1.0f);
  int steps = 0;
  EXPECT_EQ(color->GetAnnotationByIndex(3)->AsScalar()->GetInt(&steps), rhi::S_OK);
  EXPECT_EQ(steps, 10);
  bool visible = false;
  EXPECT_EQ(color->GetAnnotationByName("Visible")->AsScalar()->GetBool(&visible), rhi::S_OK);
  EXPECT_TRUE(visible);
  // Read-only, as in FX11.
  EXPECT_NE(color->GetAnnotationByName("UIMax")->AsScalar()->SetFloat(5), rhi::S_OK);
  EXPECT_EQ(color->GetAnnotationByName("UIMax")->AsScalar()->GetFloat(&uiMax), rhi::S_OK);
  EXPECT_EQ(uiMax, 1.0f);

  EXPECT_EQ(StringOf(effect->GetVariableByName("g_description")->GetAnnotationByName("Category")), "Docs");
  EXPECT_EQ(StringOf(effect->GetVariableByName("g_description")), "A test effect");
  EXPECT_EQ(StringOf(effect->GetVariableByName("g_names")->GetElement(1)), "second");
  EXPECT_EQ(StringOf(effect->GetVariableByName("g_tex")->GetAnnotationByIndex(0)), "default.dds");
  EXPECT_FALSE(effect->GetVariableByName("g_tex")->GetAnnotationByIndex(1)->IsValid());
}

TEST_F(EffectTest, PassShaderDescsNameVariablesElementsInlineAndNullShaders) {
  auto effect = Load(kConstructs + "/shader_arrays_states_null.fx");
  ASSERT_TRUE(effect);
  fx::EffectShaderVariable* vs = effect->GetVariableByName("g_vs")->AsShader();
  fx::EffectShaderVariable* ps = effect->GetVariableByName("g_ps")->AsShader();
  fx::EffectPass* blue = effect->GetTechniqueByName("Blue")->GetPassByIndex(0);
  fx::PASS_SHADER_DESC d;
  ASSERT_EQ(blue->GetVertexShaderDesc(&d), rhi::S_OK);
  EXPECT_EQ(d.pShaderVariable, vs);
  EXPECT_EQ(d.ShaderIndex, 0u);
  fx::EFFECT_SHADER_DESC sd = ShaderDescOf(d);
  EXPECT_FALSE(sd.IsInline);
  ASSERT_GT(sd.BytecodeLength, 4u);
  EXPECT_EQ(*static_cast<const uint32_t*>(sd.pBytecode), kSpirvMagic);
  EXPECT_EQ(sd.pInputSignature, sd.pBytecode);

  ASSERT_EQ(blue->GetPixelShaderDesc(&d), rhi::S_OK);
  EXPECT_EQ(d.pShaderVariable, ps);
  EXPECT_EQ(d.ShaderIndex, 2u);  // g_ps[kBlue]
  fx::EFFECT_SHADER_DESC blueDesc = ShaderDescOf(d);
  fx::EFFECT_SHADER_DESC redDesc;
  ASSERT_EQ(ps->GetShaderDesc(0, &redDesc), rhi::S_OK);
  EXPECT_NE(blueDesc.pBytecode, redDesc.pBytecode);  // PS(2) and PS(0) are two shaders
  EXPECT_EQ(ps->GetShaderDesc(3, &redDesc), rhi::E_INVALIDARG);

  // NULL, in a variable (g_gsNull) and inline, and a stage the pass leaves alone.
  ASSERT_EQ(blue->GetGeometryShaderDesc(&d), rhi::S_OK);
  EXPECT_EQ(d.pShaderVariable, effect->GetVariableByName("g_gsNull")->AsShader());
  EXPECT_EQ(ShaderDescOf(d).BytecodeLength, 0u);
  fx::EffectPass* noPs = effect->GetTechniqueByName("NoPixelShader")->GetPassByIndex(0);
  ASSERT_EQ(noPs->GetPixelShaderDesc(&d), rhi::S_OK);
  sd = ShaderDescOf(d);
  EXPECT_EQ(sd.BytecodeLength, 0u);
  EXPECT_EQ(sd.pBytecode, nullptr);
  EXPECT_TRUE(sd.IsInline);
  ASSERT_EQ(noPs->GetComputeShaderDesc(&d), rhi::S_OK);
  EXPECT_EQ(ShaderDescOf(d).BytecodeLength, 0u);
  EXPECT_EQ(effect->GetTechniqueByName("Nope")->GetPassByIndex(0)->GetPixelShaderDesc(&d), rhi::E_FAIL);
}

TEST_F(EffectTest, InlineAndStreamOutputShaderDescs) {
  auto effect = Load(kConstructs + "/groups_annotations_strings.fx");
  ASSERT_TRUE(effect);
  fx::PASS_SHADER_DESC d;
  ASSERT_EQ(effect->GetTechniqueByName("Forward")->GetPassByIndex(0)->GetPixelShaderDesc(&d), rhi::S_OK);
  fx::EFFECT_SHADER_DESC sd = ShaderDescOf(d);
  EXPECT_TRUE(sd.IsInline);
  EXPECT_GT(sd.BytecodeLength, 0u);
  fx::EFFECT_VARIABLE_DESC vd;
  ASSERT_EQ(d.pShaderVariable->GetDesc(&vd), rhi::S_OK);
  EXPECT_STREQ(vd.Name, "$Anonymous");

  auto so = Load(kConstructs + "/stream_output.fx");
  ASSERT_TRUE(so);
  fx::EffectTechnique* t = so->GetTechniqueByName("T");
  ASSERT_EQ(t->GetPassByName("P0")->GetGeometryShaderDesc(&d), rhi::S_OK);
  sd = ShaderDescOf(d);
  ASSERT_NE(sd.SODecls[0], nullptr);
  EXPECT_STREQ(sd.SODecls[0], "SV_Position.xyzw; TEXCOORD0.xy");
  EXPECT_EQ(sd.SODecls[1], nullptr);
  EXPECT_EQ(sd.RasterizedStream, 0u);
  ASSERT_EQ(t->GetPassByName("P1")->GetGeometryShaderDesc(&d), rhi::S_OK);
  EXPECT_STREQ(ShaderDescOf(d).SODecls[0], "SV_Position.xyzw");
  ASSERT_EQ(t->GetPassByName("P2")->GetGeometryShaderDesc(&d), rhi::S_OK);
  EXPECT_EQ(ShaderDescOf(d).RasterizedStream, rhi::SO_NO_RASTERIZED_STREAM);
}

TEST_F(EffectTest, TemplatedObjectTypeNamesKeepTheirArguments) {
  auto effect = Load(kConstructs + "/static_const_scopes.fx");
  ASSERT_TRUE(effect);
  fx::EFFECT_TYPE_DESC t;
  ASSERT_EQ(effect->GetVariableByName("g_out")->GetTypeDesc(&t), rhi::S_OK);
  EXPECT_STREQ(t.TypeName, "RWStructuredBuffer<float>");
}

}  // namespace
}  // namespace effects_test
