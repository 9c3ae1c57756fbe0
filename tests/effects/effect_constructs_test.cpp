// The fx_5_0 / HLSL constructs that real effect files use, one data file each
// in constructs/ (vkd3d-shader's *.shader_test idea). A file says what fxc
// does with it in `//!` lines:
//   //! loads                       it loads, and every pass of every technique applies;
//   //! pixel: TECH r g b a         and so does this: TECH's passes, drawn as one
//                                   full-screen triangle (3 vertices, no input
//                                   layout) over a cleared 4x4 R32G32B32A32_FLOAT
//                                   target, leave (r, g, b, a) at pixel (1, 1);
//   //! error: REGEX                loading fails and the errors match REGEX
//                                   (one line per expected error; they name file:line:column).
// The expected colours are worked out by hand in each file's comment.
#include <fstream>
#include <regex>

#include "effect_test_util.h"

namespace effects_test {
namespace {

const std::string kConstructDir = CONSTRUCTS_DIR;

struct Expectations {
  bool loads = false;
  std::vector<std::pair<std::string, std::array<float, 4>>> pixels;
  std::vector<std::string> errors;
};

Expectations ReadExpectations(const std::string& path) {
  Expectations e;
  std::ifstream in(path);
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("//! ", 0) != 0) continue;
    std::string body = line.substr(4);
    if (body == "loads") {
      e.loads = true;
    } else if (body.rfind("pixel: ", 0) == 0) {
      std::istringstream words(body.substr(7));
      std::pair<std::string, std::array<float, 4>> p;
      words >> p.first >> p.second[0] >> p.second[1] >> p.second[2] >> p.second[3];
      EXPECT_TRUE(words) << path << ": bad pixel line: " << line;
      e.pixels.push_back(p);
    } else if (body.rfind("error: ", 0) == 0) {
      e.errors.push_back(body.substr(7));
    }
  }
  return e;
}

std::vector<std::string> ConstructFiles() {
  std::vector<std::string> files;
  for (const auto& entry : std::filesystem::directory_iterator(kConstructDir)) {
    if (entry.path().extension() == ".fx") files.push_back(entry.path().filename().string());
  }
  std::sort(files.begin(), files.end());
  return files;
}

class EffectConstruct : public EffectTest, public ::testing::WithParamInterface<std::string> {
 protected:
  std::array<float, 4> DrawPixel(fx::Effect* effect, const std::string& technique) {
    constexpr UINT kSize = 4;
    Target target = MakeRenderTarget(kSize, kSize, rhi::DXGI_FORMAT_R32G32B32A32_FLOAT);
    const float clear[4] = {-100, -100, -100, -100};
    context->ClearRenderTargetView(target.rtv.Get(), clear);
    rhi::RenderTargetView* rtv = target.rtv.Get();
    context->OMSetRenderTargets(1, &rtv, nullptr);
    SetViewport(kSize, kSize);
    context->IASetPrimitiveTopology(rhi::PRIMITIVE_TOPOLOGY_TRIANGLELIST);
    fx::EffectTechnique* tech = effect->GetTechniqueByName(technique.c_str());
    EXPECT_TRUE(tech->IsValid()) << "no technique " << technique;
    fx::TECHNIQUE_DESC td;
    tech->GetDesc(&td);
    for (UINT p = 0; p < td.Passes; ++p) {
      EXPECT_EQ(tech->GetPassByIndex(p)->Apply(0, context.Get()), rhi::S_OK);
      context->Draw(3, 0);
    }
    std::vector<uint8_t> rows = ReadTexture(target.texture.Get());
    std::array<float, 4> pixel{};
    std::memcpy(pixel.data(), rows.data() + (1 * kSize + 1) * 16, 16);
    context->ClearState();
    return pixel;
  }
};

TEST_P(EffectConstruct, BehavesAsFxc) {
  const std::string path = kConstructDir + "/" + GetParam();
  Expectations expect = ReadExpectations(path);
  ASSERT_TRUE(expect.loads || !expect.pixels.empty() || !expect.errors.empty()) << path << " has no //! expectation";
  fx::EFFECT_OPTIONS options;
  options.CacheDirectory = SuiteCache();
  options.Errors = &errors;
  rhi::ComPtr<fx::Effect> effect;
  rhi::HRESULT hr = fx::CreateEffectFromFile(path.c_str(), options, device.Get(), effect.GetAddressOf());
  if (!expect.errors.empty()) {
    EXPECT_NE(hr, rhi::S_OK);
    for (const std::string& pattern : expect.errors) {
      EXPECT_TRUE(std::regex_search(errors, std::regex(pattern))) << "expected /" << pattern << "/ in:\n" << errors;
    }
    return;
  }
  ASSERT_EQ(hr, rhi::S_OK) << errors;
  fx::EFFECT_DESC desc;
  ASSERT_EQ(effect->GetDesc(&desc), rhi::S_OK);
  for (UINT t = 0; t < desc.Techniques; ++t) {
    fx::EffectTechnique* tech = effect->GetTechniqueByIndex(t);
    fx::TECHNIQUE_DESC td;
    ASSERT_EQ(tech->GetDesc(&td), rhi::S_OK);
    for (UINT p = 0; p < td.Passes; ++p) EXPECT_EQ(tech->GetPassByIndex(p)->Apply(0, context.Get()), rhi::S_OK);
    context->ClearState();
  }
  for (const auto& [technique, rgba] : expect.pixels) {
    std::array<float, 4> got = DrawPixel(effect.Get(), technique);
    EXPECT_EQ(got, rgba) << technique << ": got (" << got[0] << ", " << got[1] << ", " << got[2] << ", " << got[3] << ")";
  }
}

INSTANTIATE_TEST_SUITE_P(Files, EffectConstruct, ::testing::ValuesIn(ConstructFiles()),
                         [](const ::testing::TestParamInfo<std::string>& info) {
                           std::string name = info.param.substr(0, info.param.size() - 3);
                           for (char& c : name) c = std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
                           return name;
                         });

}  // namespace
}  // namespace effects_test
