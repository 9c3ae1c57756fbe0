#include "fx/preprocessor.h"

#include <gtest/gtest.h>

#include "test_util.h"

namespace fx {
namespace {

using test::LineColumn;
using test::MemoryFiles;
using test::MustPreprocess;
using test::Spelling;

std::vector<ParseError> PreprocessErrors(const std::string& source, const ParseOptions& options = {}) {
  Result<PreprocessedSource> r = Preprocess(source, "main.fx", options);
  if (std::holds_alternative<PreprocessedSource>(r)) {
    ADD_FAILURE() << "expected a preprocessing error";
    return {ParseError{}};
  }
  return std::get<std::vector<ParseError>>(r);
}

TEST(Preprocessor, FunctionLikeMacrosExpandArgumentsFully) {
  PreprocessedSource pp = MustPreprocess(
      "#define MUL(a, b) ((a) * (b))\n"
      "#define TWO 2\n"
      "#define SQUARE(x) MUL(x, x)\n"
      "float f = SQUARE(TWO + 1);\n");
  EXPECT_EQ(Spelling(pp), "float f = ( ( 2 + 1 ) * ( 2 + 1 ) ) ;");
}

TEST(Preprocessor, StringizeAndPaste) {
  PreprocessedSource pp = MustPreprocess(
      "#define STR(x) #x\n"
      "#define CAT(a, b) a##b\n"
      "#define VAR(n) g_##n##_Color\n"
      "string s = STR(hello \"world\");\n"
      "float CAT(g_, Scale) = VAR(Fog);\n");
  EXPECT_EQ(Spelling(pp), "string s = \"hello \\\"world\\\"\" ; float g_Scale = g_Fog_Color ;");
}

TEST(Preprocessor, VariadicAndEmptyArguments) {
  PreprocessedSource pp = MustPreprocess(
      "#define CALL(f, ...) f(__VA_ARGS__)\n"
      "#define FIRST(a, b) a##b\n"
      "x = CALL(max, 1, 2); y = FIRST(, z); w = CALL(g);\n");
  EXPECT_EQ(Spelling(pp), "x = max ( 1 , 2 ) ; y = z ; w = g ( ) ;");
}

TEST(Preprocessor, SelfReferentialMacrosStop) {
  PreprocessedSource pp = MustPreprocess(
      "#define A A + B\n"
      "#define B A\n"
      "#define f(x) f(x + 1)\n"
      "A; f(2);\n");
  EXPECT_EQ(Spelling(pp), "A + A ; f ( 2 + 1 ) ;");
}

TEST(Preprocessor, NestedConditionals) {
  PreprocessedSource pp = MustPreprocess(
      "#define A 1\n"
      "#if A\n"
      "#  if defined(B) || (A + 1) * 2 == 4\n"
      "ok1\n"
      "#  elif 1 / 0\n"  // never evaluated: a branch was already taken
      "bad1\n"
      "#  else\n"
      "bad2\n"
      "#  endif\n"
      "#else\n"
      "bad3\n"
      "#endif\n"
      "#ifdef B\n"
      "bad4\n"
      "#elif A > 0 && !defined C && (0x10 >> 4) == 1 && -1 < 0\n"
      "ok2\n"
      "#endif\n"
      "#if 0\n"
      "#  if garbage (((\n"
      "#  endif\n"
      "@@@ 'junk in a skipped block\n"
      "#  error not reached\n"
      "#endif\n"
      "#ifndef A\n"
      "bad5\n"
      "#else\n"
      "ok3\n"
      "#endif\n");
  EXPECT_EQ(Spelling(pp), "ok1 ok2 ok3");
}

TEST(Preprocessor, DefinesFromOptions) {
  ParseOptions options;
  options.defines = {{"QUALITY", "2"}, {"USE_FOG", ""}, {"SCALE(x)", "(x * 2)"}};
  PreprocessedSource pp = MustPreprocess(
      "#if QUALITY == 2 && USE_FOG\n"
      "high SCALE(3)\n"
      "#endif\n",
      options);
  EXPECT_EQ(Spelling(pp), "high ( 3 * 2 )");
}

TEST(Preprocessor, KeepsLinesAndColumnsOutsideMacros) {
  const std::string source =
      "// header comment\n"
      "#define SIZE 4\n"
      "\n"
      "float4   values[SIZE];   /* a comment\n"
      "  spanning lines */  int\tk = 3;\n"
      "#if 0\n"
      "skipped\n"
      "#endif\n"
      "  float last;\n";
  PreprocessedSource pp = MustPreprocess(source);
  ASSERT_FALSE(pp.tokens.empty());
  for (const Token& t : pp.tokens) {
    auto [line, column] = LineColumn(pp.text, t.offset);
    EXPECT_EQ(t.where.file, "main.fx");
    if (t.fromMacro) continue;
    EXPECT_EQ(line, t.where.line) << t.text;
    EXPECT_EQ(column, t.where.column) << t.text;
  }
  // The expanded SIZE sits where SIZE was; both report its original position.
  const Token& size = pp.tokens[3];
  EXPECT_EQ(size.text, "4");
  EXPECT_TRUE(size.fromMacro);
  EXPECT_EQ(size.where, (SourceLocation{"main.fx", 4, 17}));
  EXPECT_EQ(pp.tokens.back().where, (SourceLocation{"main.fx", 9, 13}));
  // Directive and skipped lines are blank; no #line was needed.
  EXPECT_EQ(pp.text.find("#"), std::string::npos);
  EXPECT_EQ(pp.text.find("skipped"), std::string::npos);
}

TEST(Preprocessor, MacroBodyTokensPointAtTheInvocation) {
  PreprocessedSource pp = MustPreprocess(
      "#define DECLARE(type, name) type name = 0\n"
      "\n"
      "   DECLARE(float,\n"
      "           g_x);\n"
      "int after;\n");
  ASSERT_EQ(pp.tokens.size(), 8u);
  EXPECT_EQ(pp.tokens[0].where, (SourceLocation{"main.fx", 3, 12}));  // `float` from the argument
  EXPECT_EQ(pp.tokens[1].where, (SourceLocation{"main.fx", 4, 12}));  // `g_x` from the argument
  EXPECT_EQ(pp.tokens[2].where, (SourceLocation{"main.fx", 3, 4}));   // `=` from the body
  EXPECT_EQ(pp.tokens[3].where, (SourceLocation{"main.fx", 3, 4}));   // `0` from the body
  // The code after the invocation is back at its own line and column.
  EXPECT_EQ(LineColumn(pp.text, pp.tokens[5].offset), std::make_pair(5, 1));
}

TEST(Preprocessor, IncludesRelativeThenIncludeDirectories) {
  ParseOptions options = MemoryFiles({
      {"/proj/shaders/local.fxh", "float fromLocal;\n"},
      {"/proj/shaders/sub/nested.fxh", "#include \"../local2.fxh\"\nfloat fromNested;\n"},
      {"/proj/shaders/local2.fxh", "float fromLocal2;\n"},
      {"/proj/include/lib.fxh", "#pragma once\nfloat fromLib;\n"},
      {"/proj/include/local.fxh", "float wrongLocal;\n"},
  });
  options.includeDirs = {"/proj/include"};
  PreprocessedSource pp = MustPreprocess(
      "#include \"local.fxh\"\n"
      "#include \"lib.fxh\"\n"
      "#include <lib.fxh>\n"  // #pragma once: not again
      "#include \"sub/nested.fxh\"\n"
      "float fromMain;\n",
      options, "/proj/shaders/main.fx");
  EXPECT_EQ(Spelling(pp),
            "float fromLocal ; float fromLib ; float fromLocal2 ; float fromNested ; float fromMain ;");
  ASSERT_EQ(pp.tokens.size(), 15u);
  EXPECT_EQ(pp.tokens[1].where, (SourceLocation{"/proj/shaders/local.fxh", 1, 7}));
  EXPECT_EQ(pp.tokens[4].where, (SourceLocation{"/proj/include/lib.fxh", 2, 7}));
  EXPECT_EQ(pp.tokens[7].where, (SourceLocation{"/proj/shaders/local2.fxh", 1, 7}));
  EXPECT_EQ(pp.tokens[10].where, (SourceLocation{"/proj/shaders/sub/nested.fxh", 2, 7}));
  EXPECT_EQ(pp.tokens[13].where, (SourceLocation{"/proj/shaders/main.fx", 5, 7}));
}

TEST(Preprocessor, LineDirectivesWhereIncludesStartAndEnd) {
  ParseOptions options = MemoryFiles({{"inc.fxh", "// comment\nfloat b;\n"}});
  PreprocessedSource pp = MustPreprocess("float a;\n#include \"inc.fxh\"\nfloat c;\n", options);
  EXPECT_EQ(pp.text,
            "float a;\n"
            "#line 2 \"inc.fxh\"\n"
            "float b;\n"
            "#line 3 \"main.fx\"\n"
            "float c;\n");
}

TEST(Preprocessor, LineDirectiveRenumbers) {
  PreprocessedSource pp = MustPreprocess(
      "float a;\n"
      "#line 100 \"renamed.fx\"\n"
      "float b;\n"
      "#line 7\n"
      "  float c;\n");
  ASSERT_EQ(pp.tokens.size(), 9u);
  EXPECT_EQ(pp.tokens[3].where, (SourceLocation{"renamed.fx", 100, 1}));
  EXPECT_EQ(pp.tokens[6].where, (SourceLocation{"renamed.fx", 7, 3}));
  EXPECT_NE(pp.text.find("#line 100 \"renamed.fx\"\nfloat b;"), std::string::npos);
  EXPECT_NE(pp.text.find("#line 7 \"renamed.fx\"\n  float c;"), std::string::npos);
}

TEST(Preprocessor, PragmasStayOnTheirLines) {
  PreprocessedSource pp = MustPreprocess("float a;\n#pragma pack_matrix( row_major )\nfloat b;\n");
  EXPECT_EQ(pp.text, "float a;\n#pragma pack_matrix( row_major )\nfloat b;\n");
  ASSERT_EQ(pp.tokens.size(), 7u);
  EXPECT_EQ(pp.tokens[3].kind, TokenKind::Pragma);
  EXPECT_EQ(pp.tokens[3].text, "pack_matrix( row_major )");
  EXPECT_EQ(pp.tokens[3].where, (SourceLocation{"main.fx", 2, 1}));
}

TEST(Preprocessor, LineAndFileBuiltins) {
  PreprocessedSource pp = MustPreprocess("\n#define HERE __LINE__\nint a = __LINE__ + HERE; string f = __FILE__;\n");
  EXPECT_EQ(Spelling(pp), "int a = 3 + 3 ; string f = \"main.fx\" ;");
}

TEST(Preprocessor, ErrorDirectiveThroughAnIncludeHasItsPosition) {
  ParseOptions options = MemoryFiles({{"dir/inc.fxh", "float ok;\n\n  #error Unsupported  quality\n"}});
  std::vector<ParseError> errors = PreprocessErrors("float a;\n#include \"dir/inc.fxh\"\n", options);
  ASSERT_EQ(errors.size(), 1u);
  EXPECT_EQ(errors[0].Format(), "dir/inc.fxh:3:3: #error Unsupported quality");
}

TEST(Preprocessor, InvalidCharacterInsideAMacroArgumentInAnInclude) {
  ParseOptions options = MemoryFiles({{"inc.fxh", "#define ID(x) x\nfloat v = ID(1 @ 2);\n"}});
  std::vector<ParseError> errors = PreprocessErrors("#include \"inc.fxh\"\n", options);
  ASSERT_EQ(errors.size(), 1u);
  EXPECT_EQ(errors[0].Format(), "inc.fxh:2:16: unexpected character '@'");
}

TEST(Preprocessor, MissingIncludeAndCycleAreErrors) {
  std::vector<ParseError> missing = PreprocessErrors("\n  #include \"nowhere.fxh\"\n", MemoryFiles({}));
  ASSERT_EQ(missing.size(), 1u);
  EXPECT_EQ(missing[0].Format(), "main.fx:2:3: cannot open include file 'nowhere.fxh'");

  ParseOptions cycle = MemoryFiles({{"a.fxh", "#include \"b.fxh\"\n"}, {"b.fxh", "\n#include \"a.fxh\"\n"}});
  std::vector<ParseError> errors = PreprocessErrors("#include \"a.fxh\"\n", cycle);
  ASSERT_EQ(errors.size(), 1u);
  EXPECT_EQ(errors[0].Format(), "b.fxh:2:1: recursive #include of 'a.fxh'");
}

TEST(Preprocessor, ConditionalErrors) {
  EXPECT_EQ(PreprocessErrors("#if 1\nfloat a;\n")[0].Format(), "main.fx:1:1: unterminated conditional directive");
  EXPECT_EQ(PreprocessErrors("float a;\n#endif\n")[0].Format(), "main.fx:2:1: #endif without #if");
  EXPECT_EQ(PreprocessErrors("#if 1 +\n#endif\n")[0].Format(), "main.fx:1:1: #if expression ends unexpectedly");
  EXPECT_EQ(PreprocessErrors("#if 4 / (2 - 2)\n#endif\n")[0].Format(),
            "main.fx:1:1: division by zero in #if expression");
  EXPECT_EQ(PreprocessErrors("#if 1\n#else\n#else\n#endif\n")[0].Format(), "main.fx:3:1: #else after #else");
}

TEST(Preprocessor, MacroErrors) {
  EXPECT_EQ(PreprocessErrors("#define F(a, b) a\nF(1);\n")[0].Format(),
            "main.fx:2:1: macro 'F' expects 2 arguments, got 1");
  EXPECT_EQ(PreprocessErrors("#define F(a) a\n  F(1, (2);\n")[0].Format(),
            "main.fx:2:3: unterminated argument list invoking macro 'F'");
  EXPECT_EQ(PreprocessErrors("#define S(a) #b\n")[0].Format(),
            "main.fx:1:14: '#' is not followed by a macro parameter");
  EXPECT_EQ(PreprocessErrors("#define P(a) a ## +\nP(x);\n")[0].Format(),
            "main.fx:2:3: pasting 'x' and '+' does not give a valid token");
  EXPECT_EQ(PreprocessErrors("#frobnicate\n")[0].Format(), "main.fx:1:2: unknown preprocessor directive '#frobnicate'");
}

TEST(Preprocessor, ExponentialMacrosHitTheLimitInsteadOfHanging) {
  std::string source = "#define M0 x x\n";
  for (int i = 1; i <= 40; ++i) {
    source += "#define M" + std::to_string(i) + " M" + std::to_string(i - 1) + " M" + std::to_string(i - 1) + "\n";
  }
  source += "M40\n";
  std::vector<ParseError> errors = PreprocessErrors(source);
  ASSERT_FALSE(errors.empty());
  EXPECT_EQ(errors[0].message, "macro expansion too large");
}

TEST(Preprocessor, DeepIncludeChainStops) {
  std::map<std::string, std::string> files;
  files["self.fxh"] = "#include \"self2.fxh\"\n";
  for (int i = 2; i < 100; ++i) {
    files["self" + std::to_string(i) + ".fxh"] = "#include \"self" + std::to_string(i + 1) + ".fxh\"\n";
  }
  std::vector<ParseError> errors = PreprocessErrors("#include \"self.fxh\"\n", MemoryFiles(files));
  ASSERT_EQ(errors.size(), 1u);
  EXPECT_EQ(errors[0].message, "#include nested too deeply");
}

}  // namespace
}  // namespace fx
