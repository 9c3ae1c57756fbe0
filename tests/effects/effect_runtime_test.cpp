// Reflection, errors, the SPIR-V cache and the GS isolation of the effect runtime.
#include <filesystem>

#include "effect_test_util.h"
#include "fx/gs_isolation.h"

namespace effects_test {
namespace {

using fx::EffectVariable;

// Every .fx in shaders_hlsl/ loads, and every pass of every technique applies.
TEST_F(EffectTest, EveryShadersHlslEffectLoadsAndApplies) {
  int files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(kShaderDir)) {
    if (entry.path().extension() != ".fx") continue;
    ++files;
    SCOPED_TRACE(entry.path().string());
    auto effect = Load(entry.path().string());
    ASSERT_TRUE(effect);
    fx::EFFECT_DESC desc;
    ASSERT_EQ(effect->GetDesc(&desc), rhi::S_OK);
    ASSERT_GT(desc.Techniques, 0u);
    for (UINT t = 0; t < desc.Techniques; ++t) {
      fx::TECHNIQUE_DESC td;
      ASSERT_EQ(effect->GetTechniqueByIndex(t)->GetDesc(&td), rhi::S_OK);
      for (UINT p = 0; p < td.Passes; ++p)
        EXPECT_EQ(effect->GetTechniqueByIndex(t)->GetPassByIndex(p)->Apply(0, context.Get()), rhi::S_OK);
    }
    context->ClearState();
  }
  EXPECT_GE(files, 3);
}

TEST_F(EffectTest, ReflectsTechniquesPassesAndVariables) {
  auto effect = Load(kShaderDir + "/oit.fx");
  ASSERT_TRUE(effect);
  fx::EFFECT_DESC desc;
  effect->GetDesc(&desc);
  EXPECT_EQ(desc.Techniques, 1u);
  EXPECT_EQ(desc.ConstantBuffers, 1u);
  fx::EffectTechnique* wboit = effect->GetTechniqueByName("Wboit");
  ASSERT_TRUE(wboit->IsValid());
  fx::TECHNIQUE_DESC td;
  wboit->GetDesc(&td);
  EXPECT_STREQ(td.Name, "Wboit");
  EXPECT_EQ(td.Passes, 2u);
  fx::PASS_DESC pd;
  ASSERT_EQ(wboit->GetPassByName("Compose")->GetDesc(&pd), rhi::S_OK);
  EXPECT_STREQ(pd.Name, "Compose");
  EXPECT_NE(pd.pIAInputSignature, nullptr);
  EXPECT_EQ(pd.SampleMask, 0xFFFFFFFFu);
  EXPECT_FALSE(wboit->GetPassByName("Nope")->IsValid());
  EXPECT_FALSE(wboit->GetPassByIndex(2)->IsValid());
  EXPECT_FALSE(effect->GetTechniqueByName("Nope")->IsValid());
  EXPECT_FALSE(effect->GetTechniqueByName("Nope")->GetPassByIndex(0)->IsValid());

  // Numeric, resource and state-object variables are all found by name.
  EXPECT_TRUE(effect->GetVariableByName("WorldViewProj")->AsMatrix()->IsValid());
  EXPECT_FALSE(effect->GetVariableByName("WorldViewProj")->AsScalar()->IsValid());
  EXPECT_FALSE(effect->GetVariableByName("WorldViewProj")->AsVector()->IsValid());
  EXPECT_TRUE(effect->GetVariableByName("Color")->AsVector()->IsValid());
  EXPECT_TRUE(effect->GetVariableByName("Accum")->AsShaderResource()->IsValid());
  EXPECT_FALSE(effect->GetVariableByName("Accum")->AsSampler()->IsValid());
  EXPECT_TRUE(effect->GetVariableByName("WboitAccumulate")->AsBlend()->IsValid());
  EXPECT_TRUE(effect->GetVariableByName("DepthTestNoWrite")->AsDepthStencil()->IsValid());
  EXPECT_TRUE(effect->GetVariableByName("NoCull")->AsRasterizer()->IsValid());
  EXPECT_FALSE(effect->GetVariableByName("Missing")->IsValid());
  EXPECT_FALSE(effect->GetVariableByName("Missing")->AsScalar()->IsValid());
  EXPECT_EQ(effect->GetVariableByName("Missing")->AsScalar()->SetFloat(1), rhi::E_INVALIDARG);

  rhi::BLEND_DESC blend;
  ASSERT_EQ(effect->GetVariableByName("WboitAccumulate")->AsBlend()->GetBackingStore(0, &blend), rhi::S_OK);
  EXPECT_TRUE(blend.IndependentBlendEnable);
  EXPECT_EQ(blend.RenderTarget[0].SrcBlend, rhi::BLEND_ONE);
  EXPECT_EQ(blend.RenderTarget[0].DestBlend, rhi::BLEND_ONE);
  EXPECT_EQ(blend.RenderTarget[1].SrcBlend, rhi::BLEND_ZERO);
  EXPECT_EQ(blend.RenderTarget[1].DestBlend, rhi::BLEND_INV_SRC_COLOR);
  rhi::ComPtr<rhi::BlendState> state;
  ASSERT_EQ(effect->GetVariableByName("WboitAccumulate")->AsBlend()->GetBlendState(0, state.GetAddressOf()),
            rhi::S_OK);
  EXPECT_TRUE(state);

  fx::EffectConstantBuffer* cb = effect->GetConstantBufferByName("PerObject");
  ASSERT_TRUE(cb->IsValid());
  EXPECT_TRUE(cb->GetMemberByName("Color")->IsValid());
  EXPECT_EQ(effect->GetVariableByName("Color")->GetParentConstantBuffer(), cb);
  float color[4];
  ASSERT_EQ(effect->GetVariableByName("Color")->AsVector()->GetFloatVector(color), rhi::S_OK);
  EXPECT_EQ(color[3], 0.5f);  // the initializer
}

TEST_F(EffectTest, VariablesBySemanticElementsAndMembers) {
  auto effect = FromMemory(R"(
struct Light { float3 dir; float intensity; };
float4x4 World : WORLD;
float Weights[3] = {1, 2, 3};
Light Sun;
string Title = "sun";
float4 VS(float4 p : POSITION) : SV_Position { return mul(World, p) * Weights[1] * Sun.intensity; }
technique11 T { pass P { SetVertexShader(CompileShader(vs_5_0, VS())); } }
)");
  ASSERT_TRUE(effect);
  EXPECT_TRUE(effect->GetVariableBySemantic("world")->AsMatrix()->IsValid());
  float w = 0;
  ASSERT_EQ(effect->GetVariableByName("Weights")->GetElement(2)->AsScalar()->GetFloat(&w), rhi::S_OK);
  EXPECT_EQ(w, 3.0f);
  EXPECT_FALSE(effect->GetVariableByName("Weights")->GetElement(3)->IsValid());
  EXPECT_TRUE(effect->GetVariableByName("Sun")->GetMemberByName("intensity")->AsScalar()->IsValid());
  LPCSTR title = nullptr;
  ASSERT_EQ(effect->GetVariableByName("Title")->AsString()->GetString(&title), rhi::S_OK);
  EXPECT_STREQ(title, "sun");
  fx::EFFECT_TYPE_DESC type;
  effect->GetVariableByName("Weights")->GetTypeDesc(&type);
  EXPECT_EQ(type.Elements, 3u);
  EXPECT_EQ(type.Class, fx::SVC_SCALAR);
}

// Each error names its file, line and column.
TEST_F(EffectTest, ErrorsCarryPositions) {
  struct Case {
    const char* source;
    const char* expected;
  } cases[] = {
      // HLSL error inside a function: glslang's position through the #line directives.
      {"float4 VS() : SV_Position {\n  return undefinedThing;\n}\n"
       "technique11 T { pass P { SetVertexShader(CompileShader(vs_5_0, VS())); } }\n",
       "test.fx:2:"},
      // A missing entry point.
      {"technique11 T { pass P { SetVertexShader(CompileShader(vs_5_0, Missing())); } }\n", "test.fx:1:"},
      // An unknown state value (front end).
      {"BlendState B { SrcBlend[0] = NOT_A_BLEND; };\n", "test.fx:1:"},
      // A stream-output declaration the RHI refuses (a semantic the shader does not write).
      {"struct V { float4 p : POSITION; };\n[maxvertexcount(1)] void GS(point V i[1], inout PointStream<V> s) "
       "{ s.Append(i[0]); }\n"
       "V VS(V v) { return v; }\n"
       "technique11 T { pass P { SetVertexShader(CompileShader(vs_5_0, VS()));\n"
       "  SetGeometryShader(ConstructGSWithSO(CompileShader(gs_5_0, GS()), \"NOPE.xyz\")); } }\n",
       "test.fx:5:"},
      // A parse error.
      {"technique11 T { pass P { SetVertexShader(; } }\n", "test.fx:1:"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.source);
    fx::EFFECT_OPTIONS options;
    options.CacheDirectory = "";
    std::string errs;
    options.Errors = &errs;
    rhi::ComPtr<fx::Effect> effect;
    EXPECT_TRUE(rhi::FAILED(fx::CreateEffectFromMemory(c.source, strlen(c.source), "test.fx", options, device.Get(),
                                                       effect.GetAddressOf())));
    EXPECT_FALSE(effect);
    EXPECT_EQ(errs.rfind(c.expected, 0), 0u) << errs;
    EXPECT_NE(errs.find(": error: "), std::string::npos) << errs;
  }
  ClearMessages();  // the RHI's refusal of the SO declaration reached OnMessage
}

TEST_F(EffectTest, SecondLoadComesFromTheCache) {
  const std::string cache = (std::filesystem::temp_directory_path() / "fxrt_cache_test").string();
  std::filesystem::remove_all(cache);
  fx::EFFECT_DESC cold, warm;
  Load(kShaderDir + "/particles.fx", cache)->GetDesc(&cold);
  Load(kShaderDir + "/particles.fx", cache)->GetDesc(&warm);
  EXPECT_EQ(cold.ShadersFromCache, 0u);
  EXPECT_EQ(cold.ShadersCompiled, 5u);
  EXPECT_EQ(warm.ShadersCompiled, 0u);
  EXPECT_EQ(warm.ShadersFromCache, 5u);
  // A define changes the key.
  fx::EFFECT_OPTIONS options;
  options.CacheDirectory = cache;
  options.Defines = {{"SOMETHING", "2"}};
  rhi::ComPtr<fx::Effect> effect;
  std::string path = kShaderDir + "/particles.fx";
  ASSERT_EQ(fx::CreateEffectFromFile(path.c_str(), options, device.Get(), effect.GetAddressOf()), rhi::S_OK);
  effect->GetDesc(&warm);
  EXPECT_EQ(warm.ShadersCompiled, 5u);
  std::filesystem::remove_all(cache);
}

TEST(GsIsolation, BlanksOtherStreamTypesKeepingLines) {
  const std::string source =
      "struct A { float4 p : POSITION; };\n"
      "[maxvertexcount(1)] void GSA(point A i[1], inout PointStream<A> s) {\n  s.Append(i[0]);\n}\n"
      "[maxvertexcount(3)] void GSB(point A i[1], inout TriangleStream<A> s) {\n  s.Append(i[0]);\n}\n";
  std::string a = fx::IsolateGeometryShader(source, {"GSA"});
  EXPECT_EQ(a.size(), source.size());
  EXPECT_EQ(std::count(a.begin(), a.end(), '\n'), std::count(source.begin(), source.end(), '\n'));
  EXPECT_NE(a.find("PointStream<A> s) {\n  s.Append"), std::string::npos);
  EXPECT_EQ(a.find("TriangleStream<A> s) {\n  s.Append"), std::string::npos);
  std::string none = fx::IsolateGeometryShader(source, {"VS"});
  EXPECT_EQ(none.find("Append"), std::string::npos);
  // One stream type: unchanged.
  std::string one = source.substr(0, source.find("[maxvertexcount(3)]"));
  EXPECT_EQ(fx::IsolateGeometryShader(one, {"VS"}), one);
}

}  // namespace
}  // namespace effects_test
