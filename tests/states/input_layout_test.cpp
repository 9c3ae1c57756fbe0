#include "states/input_layout.h"

#include <gtest/gtest.h>

#include <array>
#include <vector>

namespace rhi::states {
namespace {

constexpr UINT kAppend = APPEND_ALIGNED_ELEMENT;

INPUT_ELEMENT_DESC Vertex(const char* name, UINT index, DXGI_FORMAT format, UINT slot, UINT offset = kAppend) {
  return {name, index, format, slot, offset, INPUT_PER_VERTEX_DATA, 0};
}

INPUT_ELEMENT_DESC Instance(const char* name, UINT index, DXGI_FORMAT format, UINT slot, UINT step,
                            UINT offset = kAppend) {
  return {name, index, format, slot, offset, INPUT_PER_INSTANCE_DATA, step};
}

std::string ValidateOne(const INPUT_ELEMENT_DESC& e) { return Validate(&e, 1); }

TEST(InputLayoutValidate, TypicalLayoutIsValid) {
  const INPUT_ELEMENT_DESC elements[] = {
      Vertex("POSITION", 0, DXGI_FORMAT_R32G32B32_FLOAT, 0, 0),
      Vertex("NORMAL", 0, DXGI_FORMAT_R32G32B32_FLOAT, 0),
      Vertex("TEXCOORD", 0, DXGI_FORMAT_R32G32_FLOAT, 0),
      Instance("TEXCOORD", 1, DXGI_FORMAT_R32G32B32A32_FLOAT, 1, 1),
  };
  EXPECT_EQ(Validate(elements, 4), "");
  EXPECT_EQ(Validate(nullptr, 0), "");  // an empty layout is legal (SV_VertexID-only shaders)
}

TEST(InputLayoutValidate, ElementCount) {
  std::vector<INPUT_ELEMENT_DESC> many(33, Vertex("A", 0, DXGI_FORMAT_R32_FLOAT, 0));
  for (UINT i = 0; i < many.size(); ++i) many[i].SemanticIndex = i;
  EXPECT_EQ(Validate(many.data(), 33), "NumElements: 33 exceeds D3D11_IA_VERTEX_INPUT_STRUCTURE_ELEMENT_COUNT (32)");
  EXPECT_EQ(Validate(many.data(), 32), "");
  EXPECT_EQ(Validate(nullptr, 2), "pInputElementDescs: NULL with NumElements 2");
}

TEST(InputLayoutValidate, SemanticName) {
  EXPECT_EQ(ValidateOne(Vertex(nullptr, 0, DXGI_FORMAT_R32_FLOAT, 0)),
            "INPUT_ELEMENT_DESC[0].SemanticName: must not be NULL");
  EXPECT_EQ(ValidateOne(Vertex("", 0, DXGI_FORMAT_R32_FLOAT, 0)),
            "INPUT_ELEMENT_DESC[0].SemanticName: \"\" is not a valid identifier");
  EXPECT_EQ(ValidateOne(Vertex("3D", 0, DXGI_FORMAT_R32_FLOAT, 0)),
            "INPUT_ELEMENT_DESC[0].SemanticName: \"3D\" is not a valid identifier");
  EXPECT_EQ(ValidateOne(Vertex("TEX COORD", 0, DXGI_FORMAT_R32_FLOAT, 0)),
            "INPUT_ELEMENT_DESC[0].SemanticName: \"TEX COORD\" is not a valid identifier");
  EXPECT_EQ(ValidateOne(Vertex("TEXCOORD1", 0, DXGI_FORMAT_R32_FLOAT, 0)),
            "INPUT_ELEMENT_DESC[0].SemanticName: \"TEXCOORD1\" cannot end with a number (use SemanticIndex)");
  EXPECT_EQ(ValidateOne(Vertex("_my_Attr2x", 0, DXGI_FORMAT_R32_FLOAT, 0)), "");
}

TEST(InputLayoutValidate, Format) {
  EXPECT_EQ(ValidateOne(Vertex("A", 0, DXGI_FORMAT_UNKNOWN, 0)),
            "INPUT_ELEMENT_DESC[0].Format: 0 is not a valid vertex format");
  EXPECT_EQ(ValidateOne(Vertex("A", 0, static_cast<DXGI_FORMAT>(999), 0)),
            "INPUT_ELEMENT_DESC[0].Format: 999 is not a valid vertex format");
  EXPECT_EQ(ValidateOne(Vertex("A", 0, DXGI_FORMAT_D32_FLOAT, 0)),
            "INPUT_ELEMENT_DESC[0].Format: DXGI_FORMAT_D32_FLOAT cannot be used as vertex input");
  EXPECT_EQ(ValidateOne(Vertex("A", 0, DXGI_FORMAT_R8G8B8A8_TYPELESS, 0)),
            "INPUT_ELEMENT_DESC[0].Format: DXGI_FORMAT_R8G8B8A8_TYPELESS cannot be used as vertex input");
}

TEST(InputLayoutValidate, InputSlot) {
  EXPECT_EQ(ValidateOne(Vertex("A", 0, DXGI_FORMAT_R32_FLOAT, 32)),
            "INPUT_ELEMENT_DESC[0].InputSlot: 32 is not below D3D11_IA_VERTEX_INPUT_RESOURCE_SLOT_COUNT (32)");
  EXPECT_EQ(ValidateOne(Vertex("A", 0, DXGI_FORMAT_R32_FLOAT, 31)), "");
}

TEST(InputLayoutValidate, OffsetAlignmentIsMinOfFourAndElementSize) {
  EXPECT_EQ(ValidateOne(Vertex("A", 0, DXGI_FORMAT_R32_FLOAT, 0, 6)),
            "INPUT_ELEMENT_DESC[0].AlignedByteOffset: 6 is not a multiple of 4 (the alignment of DXGI_FORMAT_R32_FLOAT)");
  EXPECT_EQ(ValidateOne(Vertex("A", 0, DXGI_FORMAT_R16G16B16A16_FLOAT, 0, 2)),
            "INPUT_ELEMENT_DESC[0].AlignedByteOffset: 2 is not a multiple of 4 (the alignment of "
            "DXGI_FORMAT_R16G16B16A16_FLOAT)");
  EXPECT_EQ(ValidateOne(Vertex("A", 0, DXGI_FORMAT_R8G8_UNORM, 0, 3)),
            "INPUT_ELEMENT_DESC[0].AlignedByteOffset: 3 is not a multiple of 2 (the alignment of DXGI_FORMAT_R8G8_UNORM)");
  EXPECT_EQ(ValidateOne(Vertex("A", 0, DXGI_FORMAT_R8G8_UNORM, 0, 6)), "");
  EXPECT_EQ(ValidateOne(Vertex("A", 0, DXGI_FORMAT_R8_UINT, 0, 7)), "");
  EXPECT_EQ(ElementAlignment(DXGI_FORMAT_R32G32B32A32_FLOAT), 4u);
  EXPECT_EQ(ElementAlignment(DXGI_FORMAT_R16_FLOAT), 2u);
  EXPECT_EQ(ElementAlignment(DXGI_FORMAT_R8_SNORM), 1u);
}

TEST(InputLayoutValidate, ClassificationAndStepRate) {
  INPUT_ELEMENT_DESC e = Vertex("A", 0, DXGI_FORMAT_R32_FLOAT, 0);
  e.InputSlotClass = static_cast<INPUT_CLASSIFICATION>(2);
  EXPECT_EQ(ValidateOne(e), "INPUT_ELEMENT_DESC[0].InputSlotClass: 2 is not a valid D3D11_INPUT_CLASSIFICATION");
  e = Vertex("A", 0, DXGI_FORMAT_R32_FLOAT, 0);
  e.InstanceDataStepRate = 1;
  EXPECT_EQ(ValidateOne(e), "INPUT_ELEMENT_DESC[0].InstanceDataStepRate: 1 must be 0 for D3D11_INPUT_PER_VERTEX_DATA");
  EXPECT_EQ(ValidateOne(Instance("A", 0, DXGI_FORMAT_R32_FLOAT, 0, 0)), "");
  EXPECT_EQ(ValidateOne(Instance("A", 0, DXGI_FORMAT_R32_FLOAT, 0, 7)), "");
}

TEST(InputLayoutValidate, DuplicateSemanticsAreCaseInsensitive) {
  const INPUT_ELEMENT_DESC elements[] = {
      Vertex("TEXCOORD", 1, DXGI_FORMAT_R32G32_FLOAT, 0),
      Vertex("TEXCOORD", 0, DXGI_FORMAT_R32G32_FLOAT, 0),
      Vertex("texcoord", 1, DXGI_FORMAT_R32G32_FLOAT, 1),
  };
  EXPECT_EQ(Validate(elements, 2), "");
  EXPECT_EQ(Validate(elements, 3),
            "INPUT_ELEMENT_DESC[2]: duplicate semantic texcoord1 (also in INPUT_ELEMENT_DESC[0])");
}

TEST(InputLayoutValidate, OneSlotOneClassification) {
  const INPUT_ELEMENT_DESC mixed[] = {
      Vertex("POSITION", 0, DXGI_FORMAT_R32G32B32_FLOAT, 0),
      Instance("WORLD", 0, DXGI_FORMAT_R32G32B32A32_FLOAT, 0, 1),
  };
  EXPECT_EQ(Validate(mixed, 2),
            "INPUT_ELEMENT_DESC[1]: InputSlotClass/InstanceDataStepRate differ from INPUT_ELEMENT_DESC[0] in input slot 0");
  const INPUT_ELEMENT_DESC rates[] = {
      Instance("WORLD", 0, DXGI_FORMAT_R32G32B32A32_FLOAT, 2, 1),
      Instance("WORLD", 1, DXGI_FORMAT_R32G32B32A32_FLOAT, 2, 2),
  };
  EXPECT_EQ(Validate(rates, 2),
            "INPUT_ELEMENT_DESC[1]: InputSlotClass/InstanceDataStepRate differ from INPUT_ELEMENT_DESC[0] in input slot 2");
}

TEST(InputLayoutOffsets, AppendAlignedAcrossTwoSlots) {
  const INPUT_ELEMENT_DESC elements[] = {
      Vertex("POSITION", 0, DXGI_FORMAT_R32G32B32_FLOAT, 0),          // slot 0: 0..12
      Vertex("TEXCOORD", 0, DXGI_FORMAT_R16G16_FLOAT, 1),             // slot 1: 0..4
      Vertex("NORMAL", 0, DXGI_FORMAT_R8G8B8A8_SNORM, 0),             // slot 0: 12..16
      Vertex("COLOR", 0, DXGI_FORMAT_R8_UNORM, 0),                    // slot 0: 16..17
      Vertex("TANGENT", 0, DXGI_FORMAT_R8G8_UNORM, 0),                // slot 0: aligned to 2 -> 18..20
      Vertex("TEXCOORD", 1, DXGI_FORMAT_R32_FLOAT, 1),                // slot 1: 4..8
      Vertex("BLENDWEIGHT", 0, DXGI_FORMAT_R32_FLOAT, 0, 24),         // explicit
      Vertex("BLENDINDICES", 0, DXGI_FORMAT_R8G8B8A8_UINT, 0),        // after the explicit one: 28
      Vertex("COLOR", 1, DXGI_FORMAT_R8_UNORM, 1),                    // slot 1: 8
      Vertex("TEXCOORD", 2, DXGI_FORMAT_R32G32B32A32_FLOAT, 1),       // slot 1: 9 -> aligned to 4 -> 12
  };
  ASSERT_EQ(Validate(elements, 10), "");
  EXPECT_EQ(ResolveOffsets(elements, 10), (std::vector<UINT>{0, 0, 12, 16, 18, 4, 24, 28, 8, 12}));
}

TEST(InputLayoutOffsets, PerInstanceSlots) {
  const INPUT_ELEMENT_DESC elements[] = {
      Vertex("POSITION", 0, DXGI_FORMAT_R32G32B32A32_FLOAT, 0),
      Instance("WORLD", 0, DXGI_FORMAT_R32G32B32A32_FLOAT, 1, 1),
      Instance("WORLD", 1, DXGI_FORMAT_R32G32B32A32_FLOAT, 1, 1),
      Instance("COLOR", 0, DXGI_FORMAT_R8G8B8A8_UNORM, 2, 4),
      Instance("SCALE", 0, DXGI_FORMAT_R32_FLOAT, 2, 4),
  };
  ASSERT_EQ(Validate(elements, 5), "");
  EXPECT_EQ(ResolveOffsets(elements, 5), (std::vector<UINT>{0, 0, 16, 0, 4}));
}

TEST(InputLayoutVulkan, AttributesBindingsAndDivisors) {
  const INPUT_ELEMENT_DESC elements[] = {
      Vertex("POSITION", 0, DXGI_FORMAT_R32G32B32_FLOAT, 0),
      Vertex("UNUSED", 0, DXGI_FORMAT_R32_FLOAT, 0),  // not read by the shader: dropped
      Vertex("TEXCOORD", 0, DXGI_FORMAT_R16G16_UNORM, 0),
      Instance("WORLD", 0, DXGI_FORMAT_R32G32B32A32_FLOAT, 1, 1),
      Instance("COLOR", 0, DXGI_FORMAT_R8G8B8A8_UNORM, 3, 4),
  };
  ASSERT_EQ(Validate(elements, 5), "");
  const ShaderInput inputs[] = {
      {"position", 0, 0},  // semantics match case-insensitively
      {"TEXCOORD", 0, 1},
      {"WORLD", 0, 2},
      {"COLOR", 0, 5},
      {"SV_VertexID", 0, 6},  // system value: needs no element
  };
  std::array<UINT, IA_VERTEX_INPUT_RESOURCE_SLOT_COUNT> strides{};
  strides[0] = 20;
  strides[1] = 64;
  strides[3] = 4;
  const VertexInputVk vk = BuildVertexInput(elements, 5, inputs, strides);
  ASSERT_EQ(vk.error, "");

  ASSERT_EQ(vk.attributes.size(), 4u);
  EXPECT_EQ(vk.attributes[0].location, 0u);
  EXPECT_EQ(vk.attributes[0].binding, 0u);
  EXPECT_EQ(vk.attributes[0].format, VK_FORMAT_R32G32B32_SFLOAT);
  EXPECT_EQ(vk.attributes[0].offset, 0u);
  EXPECT_EQ(vk.attributes[1].location, 1u);
  EXPECT_EQ(vk.attributes[1].format, VK_FORMAT_R16G16_UNORM);
  EXPECT_EQ(vk.attributes[1].offset, 16u);  // after POSITION (12) and UNUSED (4)
  EXPECT_EQ(vk.attributes[2].location, 2u);
  EXPECT_EQ(vk.attributes[2].binding, 1u);
  EXPECT_EQ(vk.attributes[3].location, 5u);
  EXPECT_EQ(vk.attributes[3].binding, 3u);
  EXPECT_EQ(vk.attributes[3].format, VK_FORMAT_R8G8B8A8_UNORM);

  ASSERT_EQ(vk.bindings.size(), 3u);
  EXPECT_EQ(vk.bindings[0].binding, 0u);
  EXPECT_EQ(vk.bindings[0].stride, 20u);
  EXPECT_EQ(vk.bindings[0].inputRate, VK_VERTEX_INPUT_RATE_VERTEX);
  EXPECT_EQ(vk.bindings[1].binding, 1u);
  EXPECT_EQ(vk.bindings[1].stride, 64u);
  EXPECT_EQ(vk.bindings[1].inputRate, VK_VERTEX_INPUT_RATE_INSTANCE);
  EXPECT_EQ(vk.bindings[2].binding, 3u);
  EXPECT_EQ(vk.bindings[2].stride, 4u);
  EXPECT_EQ(vk.bindings[2].inputRate, VK_VERTEX_INPUT_RATE_INSTANCE);

  // Step rate 1 is core Vulkan; 4 needs the divisor extension.
  ASSERT_EQ(vk.divisors.size(), 1u);
  EXPECT_EQ(vk.divisors[0].binding, 3u);
  EXPECT_EQ(vk.divisors[0].divisor, 4u);
  EXPECT_TRUE(vk.needsDivisorExt);
  EXPECT_FALSE(vk.needsZeroDivisor);
}

TEST(InputLayoutVulkan, StepRateZeroNeedsZeroDivisor) {
  const INPUT_ELEMENT_DESC elements[] = {Instance("COLOR", 0, DXGI_FORMAT_R8G8B8A8_UNORM, 0, 0)};
  const ShaderInput inputs[] = {{"COLOR", 0, 3}};
  const VertexInputVk vk = BuildVertexInput(elements, 1, inputs, {});
  ASSERT_EQ(vk.divisors.size(), 1u);
  EXPECT_EQ(vk.divisors[0].divisor, 0u);
  EXPECT_TRUE(vk.needsDivisorExt);
  EXPECT_TRUE(vk.needsZeroDivisor);
  EXPECT_EQ(vk.bindings[0].stride, 0u);  // no stride given for slot 0
}

TEST(InputLayoutVulkan, NoDivisorForPlainInstancing) {
  const INPUT_ELEMENT_DESC elements[] = {Instance("WORLD", 0, DXGI_FORMAT_R32G32B32A32_FLOAT, 0, 1)};
  const ShaderInput inputs[] = {{"WORLD", 0, 0}};
  const VertexInputVk vk = BuildVertexInput(elements, 1, inputs, {});
  EXPECT_TRUE(vk.divisors.empty());
  EXPECT_FALSE(vk.needsDivisorExt);
}

TEST(InputLayoutVulkan, ShaderInputWithoutElementIsAnError) {
  const INPUT_ELEMENT_DESC elements[] = {Vertex("POSITION", 0, DXGI_FORMAT_R32G32B32_FLOAT, 0)};
  const ShaderInput inputs[] = {{"POSITION", 0, 0}, {"TEXCOORD", 1, 1}};
  const VertexInputVk vk = BuildVertexInput(elements, 1, inputs, {});
  EXPECT_EQ(vk.error, "INPUT_ELEMENT_DESC: no element for vertex shader input TEXCOORD1");
  EXPECT_TRUE(vk.attributes.empty());
}

TEST(InputLayoutVulkan, OnlyVertexIdAndInstanceIdAreExempt) {
  const INPUT_ELEMENT_DESC elements[] = {Vertex("POSITION", 0, DXGI_FORMAT_R32G32B32_FLOAT, 0)};
  const ShaderInput generated[] = {{"POSITION", 0, 0}, {"sv_vertexid", 0, 1}, {"SV_InstanceID", 0, 2}};
  EXPECT_EQ(BuildVertexInput(elements, 1, generated, {}).error, "");
  const ShaderInput position[] = {{"SV_Position", 0, 0}};
  EXPECT_EQ(BuildVertexInput(elements, 1, position, {}).error,
            "INPUT_ELEMENT_DESC: no element for vertex shader input SV_Position0");
}

}  // namespace
}  // namespace rhi::states
