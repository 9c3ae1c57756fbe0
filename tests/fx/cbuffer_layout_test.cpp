// Constant-buffer packing and default values, checked byte by byte.
#include <gtest/gtest.h>

#include "test_util.h"

namespace fx {
namespace {

using test::FloatAt;
using test::MustFail;
using test::MustParse;
using test::UIntAt;

const ConstantVariable& Var(const ConstantBuffer& cb, std::string_view name) {
  const ConstantVariable* v = FindByName(cb.variables, name);
  if (!v) throw std::runtime_error("no variable " + std::string(name));
  return *v;
}

TEST(CBufferLayout, VectorsNeverStraddleARegister) {
  EffectAst ast = MustParse(
      "cbuffer cb\n"
      "{\n"
      "    float3 a = float3(1, 2, 3);\n"
      "    float  b = 4;\n"  // fits after the float3
      "    float2 c = {5, 6};\n"
      "    float3 d = 7;\n"  // 24 + 12 would straddle: next register
      "    float2 e;\n"  // 44 + 8 would straddle too
      "    float4 f;\n"
      "};\n");
  ASSERT_EQ(ast.cbuffers.size(), 1u);
  const ConstantBuffer& cb = ast.cbuffers[0];
  EXPECT_EQ(Var(cb, "a").offset, 0u);
  EXPECT_EQ(Var(cb, "b").offset, 12u);
  EXPECT_EQ(Var(cb, "c").offset, 16u);
  EXPECT_EQ(Var(cb, "d").offset, 32u);
  EXPECT_EQ(Var(cb, "e").offset, 48u);
  EXPECT_EQ(Var(cb, "f").offset, 64u);
  EXPECT_EQ(cb.size, 80u);
  ASSERT_EQ(cb.defaults.size(), 80u);
  for (int i = 0; i < 6; ++i) EXPECT_EQ(FloatAt(cb.defaults, i * 4), float(i + 1)) << i;
  EXPECT_EQ(FloatAt(cb.defaults, 32), 7.0f);  // a scalar fills every component
  EXPECT_EQ(FloatAt(cb.defaults, 40), 7.0f);
  EXPECT_EQ(FloatAt(cb.defaults, 44), 0.0f);
  EXPECT_TRUE(Var(cb, "d").hasInitializer);
  EXPECT_FALSE(Var(cb, "e").hasInitializer);
}

TEST(CBufferLayout, ScalarThenFloat3SharesTheRegister) {
  EffectAst ast = MustParse("cbuffer cb { float a; float3 b; float2 c; float3 d; };");
  const ConstantBuffer& cb = ast.cbuffers[0];
  EXPECT_EQ(Var(cb, "b").offset, 4u);
  EXPECT_EQ(Var(cb, "c").offset, 16u);
  EXPECT_EQ(Var(cb, "d").offset, 32u);
  EXPECT_EQ(cb.size, 48u);
}

TEST(CBufferLayout, ArraysUseOneRegisterPerElement) {
  EffectAst ast = MustParse(
      "cbuffer cb {\n"
      "  float a[3] = {1, 2, 3};\n"
      "  float b = 4;\n"  // packs after the last element
      "  float4 c[2] = { float4(5, 6, 7, 8), {9, 10, 11, 12} };\n"
      "  float2 d[2][2];\n"
      "};");
  const ConstantBuffer& cb = ast.cbuffers[0];
  const ConstantVariable& a = Var(cb, "a");
  EXPECT_EQ(a.offset, 0u);
  EXPECT_EQ(a.type.size, 36u);
  EXPECT_EQ(a.type.arrayDims, std::vector<uint32_t>{3});
  EXPECT_EQ(Var(cb, "b").offset, 36u);
  EXPECT_EQ(Var(cb, "c").offset, 48u);
  EXPECT_EQ(Var(cb, "d").offset, 80u);
  EXPECT_EQ(Var(cb, "d").type.size, 3 * 16u + 8u);
  EXPECT_EQ(cb.size, 144u);
  EXPECT_EQ(FloatAt(cb.defaults, 0), 1.0f);
  EXPECT_EQ(FloatAt(cb.defaults, 16), 2.0f);
  EXPECT_EQ(FloatAt(cb.defaults, 32), 3.0f);
  EXPECT_EQ(FloatAt(cb.defaults, 36), 4.0f);
  for (int i = 0; i < 8; ++i) EXPECT_EQ(FloatAt(cb.defaults, 48 + i * 4), float(5 + i));
}

TEST(CBufferLayout, MatricesAreColumnMajorUnlessSaidOtherwise) {
  EffectAst ast = MustParse(
      "cbuffer cb {\n"
      "  float x;\n"
      "  float4x4 m = {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16};\n"
      "  row_major float2x3 r = {1, 2, 3, 4, 5, 6};\n"
      "  float3x3 n;\n"
      "  float after;\n"
      "};");
  const ConstantBuffer& cb = ast.cbuffers[0];
  const ConstantVariable& m = Var(cb, "m");
  EXPECT_EQ(m.offset, 16u);
  EXPECT_EQ(m.type.cls, VariableType::Class::Matrix);
  EXPECT_FALSE(m.type.rowMajor);
  // column c is register c: m[r][c] (value r*4+c+1) sits at c*16 + r*4
  EXPECT_EQ(FloatAt(cb.defaults, 16 + 0), 1.0f);
  EXPECT_EQ(FloatAt(cb.defaults, 16 + 4), 5.0f);
  EXPECT_EQ(FloatAt(cb.defaults, 16 + 16), 2.0f);
  EXPECT_EQ(FloatAt(cb.defaults, 16 + 32 + 4), 7.0f);
  EXPECT_EQ(FloatAt(cb.defaults, 16 + 48 + 12), 16.0f);
  const ConstantVariable& r = Var(cb, "r");
  EXPECT_TRUE(r.type.rowMajor);
  EXPECT_EQ(r.offset, 80u);
  EXPECT_EQ(r.type.size, 28u);
  EXPECT_EQ(FloatAt(cb.defaults, 80 + 8), 3.0f);
  EXPECT_EQ(FloatAt(cb.defaults, 96), 4.0f);
  const ConstantVariable& n = Var(cb, "n");
  EXPECT_EQ(n.offset, 112u);
  EXPECT_EQ(n.type.size, 44u);
  EXPECT_EQ(Var(cb, "after").offset, 156u);
  EXPECT_EQ(cb.size, 160u);
}

TEST(CBufferLayout, PackMatrixPragma) {
  EffectAst ast = MustParse(
      "#pragma pack_matrix(row_major)\n"
      "cbuffer cb {\n"
      "  float4x4 m = {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16};\n"
      "  column_major float2x2 c = {1, 2, 3, 4};\n"
      "};");
  const ConstantBuffer& cb = ast.cbuffers[0];
  EXPECT_TRUE(Var(cb, "m").type.rowMajor);
  EXPECT_EQ(FloatAt(cb.defaults, 4), 2.0f);
  EXPECT_EQ(FloatAt(cb.defaults, 16), 5.0f);
  EXPECT_EQ(Var(cb, "c").offset, 64u);
  EXPECT_FALSE(Var(cb, "c").type.rowMajor);
  EXPECT_EQ(FloatAt(cb.defaults, 64 + 4), 3.0f);
  EXPECT_EQ(FloatAt(cb.defaults, 64 + 16), 2.0f);
  EXPECT_NE(ast.hlsl.find("#pragma pack_matrix(row_major)"), std::string::npos);
}

TEST(CBufferLayout, StructsStartARegisterAndAreNotPadded) {
  EffectAst ast = MustParse(
      "struct Light { float3 dir; float intensity; };\n"
      "struct Pair { float2 a; };\n"
      "typedef float4 Color;\n"
      "cbuffer cb {\n"
      "  float x = 1;\n"
      "  Light l = { 1, 2, 3, 4 };\n"
      "  Pair p = { 5, 6 };\n"
      "  float y = 7;\n"  // shares the struct's last register
      "  Light lights[2];\n"
      "  Color tint = 0.5;\n"
      "};");
  const ConstantBuffer& cb = ast.cbuffers[0];
  const ConstantVariable& l = Var(cb, "l");
  EXPECT_EQ(l.offset, 16u);
  EXPECT_EQ(l.type.cls, VariableType::Class::Struct);
  ASSERT_EQ(l.type.members.size(), 2u);
  EXPECT_EQ(l.type.members[1].name, "intensity");
  EXPECT_EQ(l.type.members[1].offset, 12u);
  EXPECT_EQ(Var(cb, "p").offset, 32u);
  EXPECT_EQ(Var(cb, "y").offset, 40u);
  EXPECT_EQ(Var(cb, "lights").offset, 48u);
  EXPECT_EQ(Var(cb, "lights").type.size, 32u);
  EXPECT_EQ(Var(cb, "tint").offset, 80u);
  EXPECT_EQ(Var(cb, "tint").type.name, "float4");
  EXPECT_EQ(cb.size, 96u);
  float expected[] = {1, 0, 0, 0, 1, 2, 3, 4, 5, 6, 7};
  for (int i = 0; i < 11; ++i) EXPECT_EQ(FloatAt(cb.defaults, i * 4), expected[i]) << i;
  EXPECT_EQ(FloatAt(cb.defaults, 92), 0.5f);
}

TEST(CBufferLayout, TypedDefaultValues) {
  EffectAst ast = MustParse(
      "cbuffer cb {\n"
      "  int i = -2; uint u = 0xFFFFFFFF; bool b = true; bool f = false;\n"
      "  int2 v = int2(3.9, -3.9); uint m = 1 << 4 | 1; float h = 1.0 / 4; int d = 7 / 2;\n"
      "  double x = 0.5; half q = -(2 + 1) * 2;\n"
      "};");
  const ConstantBuffer& cb = ast.cbuffers[0];
  EXPECT_EQ(UIntAt(cb.defaults, 0), 0xFFFFFFFEu);
  EXPECT_EQ(UIntAt(cb.defaults, 4), 0xFFFFFFFFu);
  EXPECT_EQ(UIntAt(cb.defaults, 8), 0xFFFFFFFFu);  // FX11 stores true as -1
  EXPECT_EQ(UIntAt(cb.defaults, 12), 0u);
  EXPECT_EQ(UIntAt(cb.defaults, 16), 3u);
  EXPECT_EQ(static_cast<int32_t>(UIntAt(cb.defaults, 20)), -3);
  EXPECT_EQ(UIntAt(cb.defaults, 24), 17u);
  EXPECT_EQ(FloatAt(cb.defaults, 28), 0.25f);
  EXPECT_EQ(UIntAt(cb.defaults, 32), 3u);
  const ConstantVariable& x = Var(cb, "x");
  EXPECT_EQ(x.offset, 40u);
  EXPECT_EQ(x.type.scalar, ScalarType::Double);
  double dx = 0;
  std::memcpy(&dx, cb.defaults.data() + 40, 8);
  EXPECT_EQ(dx, 0.5);
  EXPECT_EQ(FloatAt(cb.defaults, 48), -6.0f);
}

TEST(CBufferLayout, GlobalsGoToTheGlobalsBuffer) {
  EffectAst ast = MustParse(
      "static const float PI = 3.5;\n"
      "static const int N = 3;\n"
      "float4 arr[N] = { float4(1, 1, 1, 1), float4(2, 2, 2, 2), 3 * float4(1, 1, 1, 1) };\n"
      "float twoPi = PI * 2;\n"
      "const float k = 1;\n"
      "cbuffer cb {\n"
      "  float4 a : packoffset(c1);\n"
      "  float b : packoffset(c0.z) = 5;\n"
      "};\n");
  ASSERT_EQ(ast.cbuffers.size(), 2u);
  const ConstantBuffer& g = ast.cbuffers[0];
  EXPECT_EQ(g.name, "$Globals");
  EXPECT_EQ(Var(g, "arr").offset, 0u);
  EXPECT_EQ(Var(g, "twoPi").offset, 48u);
  EXPECT_EQ(Var(g, "k").offset, 52u);
  EXPECT_EQ(g.size, 64u);
  EXPECT_EQ(FloatAt(g.defaults, 16), 2.0f);
  EXPECT_EQ(FloatAt(g.defaults, 44), 3.0f);
  EXPECT_EQ(FloatAt(g.defaults, 48), 7.0f);
  EXPECT_EQ(FloatAt(g.defaults, 52), 1.0f);
  const ConstantBuffer& cb = ast.cbuffers[1];
  EXPECT_EQ(Var(cb, "a").offset, 16u);
  EXPECT_EQ(Var(cb, "b").offset, 8u);
  EXPECT_EQ(FloatAt(cb.defaults, 8), 5.0f);
  EXPECT_EQ(cb.size, 32u);
  // Statics stay as they are; uniforms lose const and their initializers.
  EXPECT_NE(ast.hlsl.find("static const float PI = 3.5;\n"), std::string::npos);
  EXPECT_NE(ast.hlsl.find("\nfloat twoPi         ;\n"), std::string::npos);
  EXPECT_NE(ast.hlsl.find("\n      float k    ;\n"), std::string::npos);
  EXPECT_NE(ast.hlsl.find("  float b : packoffset(c0.z)    ;"), std::string::npos);
}

TEST(CBufferLayout, Errors) {
  auto errors = MustFail("cbuffer cb {\n  float3 v = {1, 2};\n};\n");
  EXPECT_EQ(errors[0].Format(), "test.fx:2:10: initializer has 2 values, 'float3' needs 3");
  errors = MustFail("cbuffer cb {\n  float4 big[4097];\n};\n");
  EXPECT_EQ(errors[0].Format(), "test.fx:2:10: 'float4' is too large for a constant buffer (64 KB)");
  errors = MustFail("cbuffer cb {\n  Unknown u;\n};\n");
  EXPECT_EQ(errors[0].Format(), "test.fx:2:3: unknown type 'Unknown'");
  errors = MustFail("float x = Foo(2);\n");
  EXPECT_EQ(errors[0].Format(), "test.fx:1:11: invalid initializer of 'x': 'Foo' is not a constant");
  EffectAst ok = MustParse("cbuffer cb { float4 big[4096]; };");
  EXPECT_EQ(ok.cbuffers[0].size, 65536u);
}

}  // namespace
}  // namespace fx
