// Reflect(): stages, interface variables by semantic, bindings, execution modes.
#include <gtest/gtest.h>

#include <spirv/unified1/spirv.hpp11>

#include "shaders.h"
#include "spirv/reflection.h"
#include "test_compiler.h"
#include "test_util.h"

namespace {

using namespace rhi::spirv;
using spirv_test::Compile;
namespace shaders = spirv_test::shaders;

Reflection ReflectOrDie(const std::vector<uint32_t>& words) {
  Result<Reflection> r = Reflect(words);
  EXPECT_TRUE(r.ok()) << r.error;
  return std::move(r.value);
}

const InterfaceVariable& Find(const std::vector<InterfaceVariable>& list, std::string_view name, uint32_t index) {
  for (const InterfaceVariable& v : list)
    if (v.semanticName == name && v.semanticIndex == index) return v;
  ADD_FAILURE() << "no " << name << index;
  static const InterfaceVariable none;
  return none;
}

constexpr uint32_t BuiltIn(spv::BuiltIn b) { return static_cast<uint32_t>(b); }

TEST(SpirvReflection, VertexShaderInputsAndOutputs) {
  const Reflection r = ReflectOrDie(Compile(shaders::kVertex, spirv_test::Stage::Vertex));
  EXPECT_EQ(r.stage, Stage::Vertex);
  EXPECT_EQ(r.entryPoint, "main");
  ASSERT_EQ(r.inputs.size(), 4u);
  ASSERT_EQ(r.outputs.size(), 3u);

  struct Expected { const char* name; uint32_t index, components, location; };
  const Expected inputs[] = {{"POSITION", 0, 3, 0}, {"NORMAL", 0, 3, 1}, {"TEXCOORD", 0, 2, 2}, {"TEXCOORD", 1, 4, 3}};
  for (const Expected& e : inputs) {
    const InterfaceVariable& v = Find(r.inputs, e.name, e.index);
    EXPECT_EQ(v.componentCount, e.components) << e.name << e.index;
    EXPECT_EQ(v.location, e.location) << e.name << e.index;
    EXPECT_EQ(v.scalarKind, ScalarKind::Float);
    EXPECT_EQ(v.scalarWidth, 32u);
    EXPECT_EQ(v.arraySize, 0u);
    EXPECT_FALSE(v.builtIn.has_value());
  }

  const InterfaceVariable& pos = Find(r.outputs, "SV_POSITION", 0);
  EXPECT_EQ(pos.builtIn, BuiltIn(spv::BuiltIn::Position));
  EXPECT_FALSE(pos.location.has_value());
  EXPECT_EQ(pos.componentCount, 4u);
  const InterfaceVariable& uv = Find(r.outputs, "TEXCOORD", 0);
  EXPECT_EQ(uv.location, 0u);
  EXPECT_EQ(uv.componentCount, 2u);
  const InterfaceVariable& color = Find(r.outputs, "COLOR", 1);
  EXPECT_EQ(color.location, 1u);
  EXPECT_EQ(color.componentCount, 4u);
  EXPECT_EQ(color.Semantic(), "COLOR1");

  EXPECT_TRUE(r.hasPositionOutput);
  EXPECT_TRUE(r.writesPosition);
  EXPECT_FALSE(r.hasPointSizeOutput);
  EXPECT_EQ(r.FindOutput("color", 1), &color) << "look-ups ignore case";
  EXPECT_EQ(r.FindOutput("COLOR", 0), nullptr);
  EXPECT_EQ(r.FindInput("TexCoord", 1)->location, 3u);
}

TEST(SpirvReflection, IntegerAndMatrixInputs) {
  const char* source = R"(
float4 main(uint4 bones : BLENDINDICES0, int2 offs : TEXCOORD12, float4x4 world : WORLD0) : SV_Position {
  return mul(world, float4(bones.xy + offs, 0, 1));
})";
  const Reflection r = ReflectOrDie(Compile(source, spirv_test::Stage::Vertex));
  const InterfaceVariable& bones = Find(r.inputs, "BLENDINDICES", 0);
  EXPECT_EQ(bones.scalarKind, ScalarKind::UInt);
  EXPECT_EQ(bones.componentCount, 4u);
  const InterfaceVariable& offs = Find(r.inputs, "TEXCOORD", 12);
  EXPECT_EQ(offs.scalarKind, ScalarKind::SInt);
  EXPECT_EQ(offs.componentCount, 2u);
  const InterfaceVariable& world = Find(r.inputs, "WORLD", 0);
  EXPECT_EQ(world.componentCount, 4u);
  EXPECT_EQ(world.locationCount, 4u) << "a float4x4 takes four locations / semantic indices";
  EXPECT_EQ(r.FindInput("WORLD", 3), &world);
  EXPECT_EQ(r.FindInput("WORLD", 4), nullptr);
}

TEST(SpirvReflection, PixelShaderTargets) {
  const Reflection r = ReflectOrDie(Compile(shaders::kPixel, spirv_test::Stage::Pixel));
  EXPECT_EQ(r.stage, Stage::Pixel);
  ASSERT_EQ(r.outputs.size(), 2u);
  EXPECT_EQ(Find(r.outputs, "SV_TARGET", 0).location, 0u);
  EXPECT_EQ(Find(r.outputs, "SV_TARGET", 1).location, 1u);
  const InterfaceVariable& pos = Find(r.inputs, "SV_POSITION", 0);
  EXPECT_EQ(pos.builtIn, BuiltIn(spv::BuiltIn::FragCoord));
  EXPECT_EQ(Find(r.inputs, "TEXCOORD", 0).location, 0u);
  EXPECT_FALSE(r.hasPositionOutput);
}

TEST(SpirvReflection, GeometryShaderModesAndArrayedInputs) {
  const Reflection r = ReflectOrDie(Compile(shaders::kGeometry, spirv_test::Stage::Geometry));
  EXPECT_EQ(r.stage, Stage::Geometry);
  EXPECT_EQ(r.gsInput, GsInputPrimitive::Points);
  EXPECT_EQ(r.gsOutput, GsOutputPrimitive::TriangleStrip);
  EXPECT_EQ(r.gsMaxVertices, 4u);
  EXPECT_EQ(r.gsInvocations, 1u);
  const InterfaceVariable& inPos = Find(r.inputs, "SV_POSITION", 0);
  EXPECT_TRUE(inPos.perVertexArray);
  EXPECT_EQ(inPos.arraySize, 1u);
  EXPECT_EQ(inPos.componentCount, 4u);
  const InterfaceVariable& inUv = Find(r.inputs, "TEXCOORD", 0);
  EXPECT_EQ(inUv.arraySize, 1u);
  EXPECT_EQ(inUv.componentCount, 2u);
  EXPECT_EQ(Find(r.outputs, "COLOR", 0).location, 1u);
  EXPECT_FALSE(Find(r.outputs, "COLOR", 0).perVertexArray);
  EXPECT_TRUE(r.writesPosition);
}

TEST(SpirvReflection, GeometryShaderTriangleInput) {
  const char* source = R"(
struct V { float4 pos : SV_Position; };
[maxvertexcount(3)] [instance(2)]
void main(triangle V input[3], inout LineStream<V> stream) { stream.Append(input[0]); })";
  const Reflection r = ReflectOrDie(Compile(source, spirv_test::Stage::Geometry));
  EXPECT_EQ(r.gsInput, GsInputPrimitive::Triangles);
  EXPECT_EQ(r.gsOutput, GsOutputPrimitive::LineStrip);
  EXPECT_EQ(r.gsMaxVertices, 3u);
  EXPECT_EQ(r.gsInvocations, 2u);
  EXPECT_EQ(Find(r.inputs, "SV_POSITION", 0).arraySize, 3u);
}

TEST(SpirvReflection, ComputeLocalSize) {
  const Reflection r = ReflectOrDie(Compile(shaders::kCompute, spirv_test::Stage::Compute));
  EXPECT_EQ(r.stage, Stage::Compute);
  EXPECT_EQ(r.localSize, (std::array<uint32_t, 3>{8, 4, 1}));
  EXPECT_EQ(Find(r.inputs, "SV_DISPATCHTHREADID", 0).builtIn, BuiltIn(spv::BuiltIn::GlobalInvocationId));
}

TEST(SpirvReflection, DescriptorBindings) {
  const Reflection r = ReflectOrDie(Compile(shaders::kResources, spirv_test::Stage::Pixel));
  const auto binding = [&r](std::string_view name) -> const DescriptorBinding& {
    for (const DescriptorBinding& b : r.bindings)
      if (b.name == name) return b;
    ADD_FAILURE() << "no binding " << name;
    static const DescriptorBinding none;
    return none;
  };
  // glslang maps each explicit register number to the binding of set 0 (the
  // product compiler adds per-class shifts; this test compiler does not).
  struct Expected { const char* name; DescriptorKind kind; uint32_t binding, count; bool nonWritable; };
  const Expected expected[] = {
      {"Frame", DescriptorKind::UniformBuffer, 2, 1, false},
      {"albedo", DescriptorKind::SampledImage, 3, 1, false},
      {"samp", DescriptorKind::Sampler, 1, 1, false},
      {"counts", DescriptorKind::StorageBuffer, 4, 1, false},
      {"lights", DescriptorKind::StorageBuffer, 5, 1, true},
      {"texels", DescriptorKind::UniformTexelBuffer, 6, 1, false},
      {"image", DescriptorKind::StorageImage, 1, 1, false},
      {"layers", DescriptorKind::SampledImage, 8, 4, false},
      {"written", DescriptorKind::StorageTexelBuffer, 7, 1, false},
  };
  EXPECT_EQ(r.bindings.size(), std::size(expected));
  for (const Expected& e : expected) {
    const DescriptorBinding& b = binding(e.name);
    EXPECT_EQ(b.kind, e.kind) << e.name << ": " << DescriptorKindName(b.kind);
    EXPECT_EQ(b.set, 0u) << e.name;
    EXPECT_EQ(b.binding, e.binding) << e.name;
    EXPECT_EQ(b.arrayCount, e.count) << e.name;
    EXPECT_EQ(b.nonWritable, e.nonWritable) << e.name;
  }
}

TEST(SpirvReflection, GlslPerVertexBlockMembers) {
  const Reflection r =
      ReflectOrDie(Compile(shaders::kGlslVertex, spirv_test::Stage::Vertex, "main", spirv_test::Language::Glsl));
  const InterfaceVariable& pos = Find(r.outputs, "SV_POSITION", 0);
  ASSERT_TRUE(pos.member.has_value());
  EXPECT_EQ(*pos.member, 0u);
  EXPECT_EQ(pos.builtIn, BuiltIn(spv::BuiltIn::Position));
  const InterfaceVariable& clip = Find(r.outputs, "SV_CLIPDISTANCE", 0);
  EXPECT_EQ(clip.arraySize, 1u);
  EXPECT_EQ(clip.variableId, pos.variableId);
  EXPECT_TRUE(r.writesPosition);
  EXPECT_TRUE(r.hasPointSizeOutput);
  EXPECT_FALSE(r.writesPointSize) << "gl_PointSize is declared by glslang but never written";
  const InterfaceVariable& uv = *std::find_if(r.outputs.begin(), r.outputs.end(),
                                              [](const InterfaceVariable& v) { return v.location == 0u; });
  EXPECT_EQ(uv.semanticName, "") << "GLSL locations carry no semantic";
  EXPECT_EQ(uv.componentCount, 2u);
}

TEST(SpirvReflection, SplitSemantic) {
  EXPECT_EQ(SplitSemantic("TexCoord12").name, "TEXCOORD");
  EXPECT_EQ(SplitSemantic("TexCoord12").index, 12u);
  EXPECT_EQ(SplitSemantic("POSITION").index, 0u);
  EXPECT_EQ(SplitSemantic("sv_target7").name, "SV_TARGET");
  EXPECT_EQ(SplitSemantic("sv_target7").index, 7u);
}

TEST(SpirvReflection, RejectsGarbage) {
  EXPECT_NE(Reflect(std::vector<uint32_t>{1, 2, 3, 4, 5, 6}).error, "");
  EXPECT_NE(Reflect(std::vector<uint32_t>{}).error, "");
}

}  // namespace
