// Effect creation as D3D11 programs call it: fx::CreateEffectFromMemory in the shape of
// D3DX11CreateEffectFromMemory (source bytes, a name for messages, an include folder, FXFlags)
// and CreateEffectFromFile with wide-character and std::filesystem paths.
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>

#include <unistd.h>

#include "effect_test_util.h"

namespace effects_test {
namespace {

namespace fs = std::filesystem;

// A full-screen pass whose colour comes from an included header.
const std::string kPortedEffect = R"(#include "colors.fxh"
float4 VS(uint id : SV_VertexID) : SV_Position {
  float2 uv = float2((id << 1) & 2, id & 2);
  return float4(uv * float2(2, -2) + float2(-1, 1), 0.5, 1);
}
float4 PS(float4 p : SV_Position) : SV_Target { return kTeal; }
technique11 Render { pass P0 {
  SetVertexShader(CompileShader(vs_5_0, VS()));
  SetPixelShader(CompileShader(ps_5_0, PS()));
} }
)";

class EffectCreationTest : public EffectTest {
 protected:
  void SetUp() override {
    EffectTest::SetUp();
    // Outside the SPIR-V cache's default folder: these tests must not write to $HOME.
    setenv("XDG_CACHE_HOME", SuiteCache().c_str(), 1);
    folder = fs::temp_directory_path() / ("fx_creation_" + std::to_string(::getpid()));
    fs::create_directories(folder);
    Write(folder / "colors.fxh", "static const float4 kTeal = float4(0, 0.5, 0.5, 1);\n");
  }
  void TearDown() override {
    fs::remove_all(folder);
    EffectTest::TearDown();
  }
  static void Write(const fs::path& path, const std::string& text) { std::ofstream(path) << text; }
  fs::path folder;
};

TEST_F(EffectCreationTest, FromMemoryFindsIncludesInTheIncludeFolder) {
  rhi::ComPtr<fx::Effect> effect;
  std::string errors;
  ASSERT_EQ(fx::CreateEffectFromMemory(kPortedEffect.data(), kPortedEffect.size(), "ported.fx", folder, 0,
                                       device.Get(), effect.GetAddressOf(), &errors),
            rhi::S_OK)
      << errors;
  EXPECT_TRUE(effect->GetTechniqueByName("Render")->GetPassByName("P0")->IsValid());
  EXPECT_EQ(errors, "");
}

TEST_F(EffectCreationTest, FromMemoryErrorsNameTheSourceName) {
  const std::string broken = "float4 Color;\nfloat4 PS() : SV_Target { return Colour; }\n"
                             "technique11 T { pass P { SetPixelShader(CompileShader(ps_5_0, PS())); } }\n";
  rhi::ComPtr<fx::Effect> effect;
  std::string errors;
  EXPECT_EQ(fx::CreateEffectFromMemory(broken.data(), broken.size(), "particles.fx", {}, 0, device.Get(),
                                       effect.GetAddressOf(), &errors),
            rhi::E_FAIL);
  EXPECT_EQ(effect.Get(), nullptr);
  EXPECT_TRUE(std::regex_search(errors, std::regex("particles\\.fx:2:[0-9]+: error: .*Colour"))) << errors;
}

TEST_F(EffectCreationTest, FromMemoryWithoutAnErrorStringWritesErrorsToStderr) {
  const std::string broken = "technique11 T { pass P { SetPixelShader(Nope); } }\n";
  rhi::ComPtr<fx::Effect> effect;
  testing::internal::CaptureStderr();
  EXPECT_EQ(fx::CreateEffectFromMemory(broken.data(), broken.size(), nullptr, {}, 0, device.Get(),
                                       effect.GetAddressOf()),
            rhi::E_FAIL);
  const std::string stderrText = testing::internal::GetCapturedStderr();
  EXPECT_NE(stderrText.find("<memory>:1:"), std::string::npos) << stderrText;
}

TEST_F(EffectCreationTest, FromMemoryTakesFx11EffectFlags) {
  const fs::path noFolder;
  rhi::ComPtr<fx::Effect> effect, child, unknown;
  std::string errors;
  EXPECT_EQ(fx::CreateEffectFromMemory(kPortedEffect.data(), kPortedEffect.size(), "ported.fx", folder,
                                       fx::COMPILE_EFFECT_ALLOW_SLOW_OPS, device.Get(), effect.GetAddressOf(),
                                       &errors),
            rhi::S_OK)
      << errors;
  EXPECT_EQ(fx::CreateEffectFromMemory(kPortedEffect.data(), kPortedEffect.size(), "ported.fx", folder,
                                       fx::COMPILE_EFFECT_CHILD_EFFECT, device.Get(), child.GetAddressOf(), &errors),
            rhi::E_NOTIMPL);
  EXPECT_EQ(child.Get(), nullptr);
  EXPECT_NE(errors.find("ported.fx: error: effect pools"), std::string::npos) << errors;
  EXPECT_EQ(fx::CreateEffectFromMemory(kPortedEffect.data(), kPortedEffect.size(), "ported.fx", noFolder, 0x100,
                                       device.Get(), unknown.GetAddressOf(), &errors),
            rhi::E_INVALIDARG);
  EXPECT_NE(errors.find("unknown FXFlags bits 0x100"), std::string::npos) << errors;
}

// D3D11 programs pass LPCWSTR paths; non-ASCII ones must work whatever the C locale is.
TEST_F(EffectCreationTest, FromFileTakesWideAndFilesystemPaths) {
  const fs::path file = folder / reinterpret_cast<const char*>(u8"effet_\u00e9t\u00e9_\u6587.fx");
  Write(file, kPortedEffect);
  fx::EFFECT_OPTIONS options;
  options.CacheDirectory = SuiteCache();
  options.Errors = &errors;
  const std::string asciiFolder = folder.string();
  std::wstring wide(asciiFolder.begin(), asciiFolder.end());
  wide += L"/effet_\u00e9t\u00e9_\u6587.fx";
  rhi::ComPtr<fx::Effect> fromWide, fromPath;
  ASSERT_EQ(fx::CreateEffectFromFile(wide.c_str(), options, device.Get(), fromWide.GetAddressOf()), rhi::S_OK)
      << errors;
  ASSERT_EQ(fx::CreateEffectFromFile(file, options, device.Get(), fromPath.GetAddressOf()), rhi::S_OK) << errors;
  EXPECT_TRUE(fromWide->GetTechniqueByName("Render")->IsValid());
  EXPECT_TRUE(fromPath->GetTechniqueByName("Render")->IsValid());
}

}  // namespace
}  // namespace effects_test
