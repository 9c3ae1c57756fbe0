// D3D11 input layouts: validation, APPEND_ALIGNED_ELEMENT resolution, and the
// Vulkan vertex-input descriptions.
#pragma once

#include <vulkan/vulkan_core.h>

#include <span>
#include <string>
#include <vector>

#include "rhi/d3d11_types.h"

namespace rhi::states {

inline constexpr UINT IA_VERTEX_INPUT_STRUCTURE_ELEMENT_COUNT = 32;  // D3D11_IA_...

// Empty when CreateInputLayout accepts the elements (the shader-signature
// match is BuildVertexInput's job), else the reason, e.g.
// "INPUT_ELEMENT_DESC[1].InputSlot: 32 is not below D3D11_IA_VERTEX_INPUT_RESOURCE_SLOT_COUNT (32)".
// Rules: at most 32 elements; SemanticName non-null, an identifier, not ending
// in a digit (the index goes in SemanticIndex); Format usable as vertex input;
// InputSlot < 32; an explicit AlignedByteOffset is a multiple of
// ElementAlignment(Format); InputSlotClass valid; per-vertex elements have
// InstanceDataStepRate 0; no duplicate SemanticName+SemanticIndex (names
// compare case-insensitively); all elements of one slot share InputSlotClass
// and InstanceDataStepRate.
std::string Validate(const INPUT_ELEMENT_DESC* elements, UINT count);

// min(4, element size): D3D11 aligns vertex elements to 4 bytes, or to their own
// size when that is smaller (R8G8 -> 2, R8 -> 1).
UINT ElementAlignment(DXGI_FORMAT format);

// Concrete byte offsets, one per element. APPEND_ALIGNED_ELEMENT places an
// element right after the previous element *of the same input slot* (in
// declaration order), rounded up to ElementAlignment; the first element of a
// slot starts at 0. Expects elements that passed Validate.
std::vector<UINT> ResolveOffsets(const INPUT_ELEMENT_DESC* elements, UINT count);

// One vertex shader input, from the shader's input signature.
struct ShaderInput {
  std::string semanticName;
  UINT semanticIndex = 0;
  uint32_t location = 0;
};

struct VertexInputVk {
  std::vector<VkVertexInputBindingDescription> bindings;
  std::vector<VkVertexInputAttributeDescription> attributes;
  // Chain a VkPipelineVertexInputDivisorStateCreateInfoEXT when non-empty.
  std::vector<VkVertexInputBindingDivisorDescriptionEXT> divisors;
  bool needsDivisorExt = false;   // an InstanceDataStepRate other than 1: VK_EXT_vertex_attribute_divisor
  bool needsZeroDivisor = false;  // step rate 0 (never advance): vertexAttributeInstanceRateZeroDivisor
  // Non-empty when a shader input has no element, which makes CreateInputLayout
  // fail ("INPUT_ELEMENT_DESC: no element for vertex shader input TEXCOORD1").
  std::string error;
};

// Elements the shader does not read are dropped (D3D11 allows them). Shader
// inputs SV_VertexID / SV_InstanceID need no element; every other input does
// (SV_Position included, as on native D3D11). `strides` is
// indexed by input slot (missing slots get stride 0); with
// VK_DYNAMIC_STATE_VERTEX_INPUT_BINDING_STRIDE the values are only defaults.
VertexInputVk BuildVertexInput(const INPUT_ELEMENT_DESC* elements, UINT count, std::span<const ShaderInput> shaderInputs,
                               std::span<const UINT> strides);

}  // namespace rhi::states
