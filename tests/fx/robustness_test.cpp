// Truncated and mutated versions of the realistic effect must never crash or
// hang: every run ends in an AST or in errors. Seeded, so it is deterministic.
#include <gtest/gtest.h>

#include <fstream>
#include <random>
#include <sstream>

#include "test_util.h"

namespace fx {
namespace {

std::string ReadData(const std::string& name) {
  std::ifstream in(std::string(FX_TEST_DATA_DIR) + "/" + name, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

class Robustness : public ::testing::Test {
 protected:
  void SetUp() override {
    scene_ = ReadData("scene.fx");
    ASSERT_GT(scene_.size(), 1000u);
    options_ = test::MemoryFiles({{"common.fxh", ReadData("common.fxh")}, {"scene.fx", scene_}});
  }

  // Parses and checks the result is well-formed; returns whether it succeeded.
  bool Check(const std::string& source) {
    Result<EffectAst> r = ParseEffect(source, "scene.fx", options_);
    if (auto* errors = std::get_if<std::vector<ParseError>>(&r)) {
      EXPECT_FALSE(errors->empty());
      for (const ParseError& e : *errors) EXPECT_FALSE(e.message.empty());
      return false;
    }
    const EffectAst& ast = std::get<EffectAst>(r);
    for (const ConstantBuffer& cb : ast.cbuffers) EXPECT_EQ(cb.defaults.size(), cb.size);
    return true;
  }

  std::string scene_;
  ParseOptions options_;
};

TEST_F(Robustness, TheUnmodifiedFileParses) { EXPECT_TRUE(Check(scene_)); }

TEST_F(Robustness, TruncatedPrefixes) {
  int ok = 0;
  for (size_t n = 0; n < scene_.size(); n += 3) ok += Check(scene_.substr(0, n));
  EXPECT_GT(ok, 0);                                   // e.g. the empty prefix
  EXPECT_LT(ok, static_cast<int>(scene_.size() / 3));  // most prefixes are broken
}

TEST_F(Robustness, RandomMutations) {
  static const char* kSnippets[] = {"{", "}", "(", ")", "<", ">", ";", ",", "\"", "'", "#", "##", "/*", "*/", "\\\n",
                                    "\n#if 1\n", "\n#endif\n", "\n#else\n", "\n#define X X X\n", "\n#include \"scene.fx\"\n",
                                    "CompileShader(", "ConstructGSWithSO(", "[", "]", "=", "0x", "1e999", "-",
                                    "float4x4", "struct", "technique11", "pass", "NULL", "\n#line 0\n", "\0"};
  std::mt19937 rng(20240611);
  int ok = 0;
  for (int i = 0; i < 2000; ++i) {
    std::string s = scene_;
    int edits = 1 + static_cast<int>(rng() % 4);
    for (int k = 0; k < edits && !s.empty(); ++k) {
      size_t at = rng() % s.size();
      switch (rng() % 4) {
        case 0:
          s[at] = static_cast<char>(rng() % 256);
          break;
        case 1:
          s.erase(at, 1 + rng() % 40);
          break;
        case 2:
          s.insert(at, s.substr(rng() % s.size(), 1 + rng() % 60));
          break;
        default: {
          const char* snippet = kSnippets[rng() % std::size(kSnippets)];
          s.insert(at, std::string(snippet, std::max<size_t>(1, std::strlen(snippet))));
          break;
        }
      }
    }
    ok += Check(s);
  }
  // Mutations that hit a comment or whitespace leave a valid effect.
  EXPECT_GT(ok, 0);
  EXPECT_LT(ok, 2000);
}

}  // namespace
}  // namespace fx
