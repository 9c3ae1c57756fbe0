#include "states/input_layout.h"

#include <algorithm>
#include <cctype>
#include <string_view>

#include "states/formats.h"

namespace rhi::states {
namespace {

std::string Prefix(UINT i) { return "INPUT_ELEMENT_DESC[" + std::to_string(i) + "]"; }

bool EqualNoCase(std::string_view a, std::string_view b) {
  return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](char x, char y) {
           return std::tolower(static_cast<unsigned char>(x)) == std::tolower(static_cast<unsigned char>(y));
         });
}

bool IsIdentifier(std::string_view s) {
  if (s.empty() || std::isdigit(static_cast<unsigned char>(s[0]))) return false;
  return std::all_of(s.begin(), s.end(), [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; });
}

std::string CheckSemanticName(UINT i, const char* name) {
  const std::string field = Prefix(i) + ".SemanticName: ";
  if (!name) return field + "must not be NULL";
  const std::string_view s(name);
  if (!IsIdentifier(s)) return field + "\"" + name + "\" is not a valid identifier";
  // "TEXCOORD1" would be parsed by HLSL as TEXCOORD index 1, so a layout name
  // ending in a digit can never match a shader input. Judgement: we refuse it
  // like the D3D11 debug runtime reports it; the release runtime's behaviour for
  // an unused element with such a name is not confirmed.
  if (std::isdigit(static_cast<unsigned char>(s.back())))
    return field + "\"" + name + "\" cannot end with a number (use SemanticIndex)";
  return {};
}

std::string CheckFormat(UINT i, DXGI_FORMAT format) {
  const FormatInfo* info = GetFormatInfo(format);
  if (!info) return Prefix(i) + ".Format: " + std::to_string(format) + " is not a valid vertex format";
  if (!(info->bindFlags & BIND_VERTEX_BUFFER))
    return Prefix(i) + ".Format: " + info->name + " cannot be used as vertex input";
  return {};
}

std::string CheckElement(UINT i, const INPUT_ELEMENT_DESC& e) {
  if (std::string error = CheckSemanticName(i, e.SemanticName); !error.empty()) return error;
  if (std::string error = CheckFormat(i, e.Format); !error.empty()) return error;
  if (e.InputSlot >= IA_VERTEX_INPUT_RESOURCE_SLOT_COUNT)
    return Prefix(i) + ".InputSlot: " + std::to_string(e.InputSlot) +
           " is not below D3D11_IA_VERTEX_INPUT_RESOURCE_SLOT_COUNT (32)";
  const UINT align = ElementAlignment(e.Format);
  if (e.AlignedByteOffset != APPEND_ALIGNED_ELEMENT && e.AlignedByteOffset % align != 0)
    return Prefix(i) + ".AlignedByteOffset: " + std::to_string(e.AlignedByteOffset) + " is not a multiple of " +
           std::to_string(align) + " (the alignment of " + FormatName(e.Format) + ")";
  if (e.InputSlotClass != INPUT_PER_VERTEX_DATA && e.InputSlotClass != INPUT_PER_INSTANCE_DATA)
    return Prefix(i) + ".InputSlotClass: " + std::to_string(e.InputSlotClass) +
           " is not a valid D3D11_INPUT_CLASSIFICATION";
  if (e.InputSlotClass == INPUT_PER_VERTEX_DATA && e.InstanceDataStepRate != 0)
    return Prefix(i) + ".InstanceDataStepRate: " + std::to_string(e.InstanceDataStepRate) +
           " must be 0 for D3D11_INPUT_PER_VERTEX_DATA";
  return {};
}

// Rules between element i and the earlier ones.
std::string CheckAgainstEarlier(const INPUT_ELEMENT_DESC* elements, UINT i) {
  const INPUT_ELEMENT_DESC& e = elements[i];
  for (UINT j = 0; j < i; ++j) {
    const INPUT_ELEMENT_DESC& prev = elements[j];
    if (prev.SemanticIndex == e.SemanticIndex && EqualNoCase(prev.SemanticName, e.SemanticName))
      return Prefix(i) + ": duplicate semantic " + e.SemanticName + std::to_string(e.SemanticIndex) +
             " (also in " + Prefix(j) + ")";
    // One Vulkan binding (and one D3D11 slot) has a single input rate.
    if (prev.InputSlot == e.InputSlot &&
        (prev.InputSlotClass != e.InputSlotClass || prev.InstanceDataStepRate != e.InstanceDataStepRate))
      return Prefix(i) + ": InputSlotClass/InstanceDataStepRate differ from " + Prefix(j) + " in input slot " +
             std::to_string(e.InputSlot);
  }
  return {};
}

UINT AlignUp(UINT value, UINT align) { return (value + align - 1) / align * align; }

const ShaderInput* FindShaderInput(std::span<const ShaderInput> inputs, const INPUT_ELEMENT_DESC& e) {
  for (const ShaderInput& in : inputs) {
    if (in.semanticIndex == e.SemanticIndex && EqualNoCase(in.semanticName, e.SemanticName)) return &in;
  }
  return nullptr;
}

bool HasElement(const INPUT_ELEMENT_DESC* elements, UINT count, const ShaderInput& in) {
  return std::any_of(elements, elements + count, [&](const INPUT_ELEMENT_DESC& e) {
    return e.SemanticIndex == in.semanticIndex && EqualNoCase(e.SemanticName, in.semanticName);
  });
}

// The only system-generated vertex shader inputs. Other SV_ names (SV_Position
// as a VS input) are ordinary inputs that need an element (Wine's tests of
// native CreateInputLayout, wine MR 618).
bool IsGeneratedByIA(std::string_view name) {
  return EqualNoCase(name, "SV_VertexID") || EqualNoCase(name, "SV_InstanceID");
}

void AddBinding(VertexInputVk& out, const INPUT_ELEMENT_DESC& e, std::span<const UINT> strides) {
  for (const VkVertexInputBindingDescription& b : out.bindings) {
    if (b.binding == e.InputSlot) return;
  }
  const bool instanced = e.InputSlotClass == INPUT_PER_INSTANCE_DATA;
  out.bindings.push_back({e.InputSlot, e.InputSlot < strides.size() ? strides[e.InputSlot] : 0,
                          instanced ? VK_VERTEX_INPUT_RATE_INSTANCE : VK_VERTEX_INPUT_RATE_VERTEX});
  // Core Vulkan advances instance data every instance (divisor 1); any other
  // step rate needs VK_EXT_vertex_attribute_divisor.
  if (instanced && e.InstanceDataStepRate != 1) {
    out.divisors.push_back({e.InputSlot, e.InstanceDataStepRate});
    out.needsDivisorExt = true;
    out.needsZeroDivisor |= e.InstanceDataStepRate == 0;
  }
}

}  // namespace

UINT ElementAlignment(DXGI_FORMAT format) {
  const FormatInfo* info = GetFormatInfo(format);
  return info ? std::min<UINT>(4, info->bytesPerElement) : 4;
}

std::string Validate(const INPUT_ELEMENT_DESC* elements, UINT count) {
  if (count > IA_VERTEX_INPUT_STRUCTURE_ELEMENT_COUNT)
    return "NumElements: " + std::to_string(count) + " exceeds D3D11_IA_VERTEX_INPUT_STRUCTURE_ELEMENT_COUNT (32)";
  if (count > 0 && !elements) return "pInputElementDescs: NULL with NumElements " + std::to_string(count);
  for (UINT i = 0; i < count; ++i) {
    if (std::string error = CheckElement(i, elements[i]); !error.empty()) return error;
    if (std::string error = CheckAgainstEarlier(elements, i); !error.empty()) return error;
  }
  return {};
}

std::vector<UINT> ResolveOffsets(const INPUT_ELEMENT_DESC* elements, UINT count) {
  std::vector<UINT> offsets(count, 0);
  for (UINT i = 0; i < count; ++i) {
    const INPUT_ELEMENT_DESC& e = elements[i];
    if (e.AlignedByteOffset != APPEND_ALIGNED_ELEMENT) {
      offsets[i] = e.AlignedByteOffset;
      continue;
    }
    for (UINT j = i; j-- > 0;) {  // the previous element of the same slot
      if (elements[j].InputSlot != e.InputSlot) continue;
      const FormatInfo* prev = GetFormatInfo(elements[j].Format);
      offsets[i] = AlignUp(offsets[j] + (prev ? prev->bytesPerElement : 0), ElementAlignment(e.Format));
      break;
    }
  }
  return offsets;
}

VertexInputVk BuildVertexInput(const INPUT_ELEMENT_DESC* elements, UINT count, std::span<const ShaderInput> shaderInputs,
                               std::span<const UINT> strides) {
  VertexInputVk out;
  for (const ShaderInput& in : shaderInputs) {
    if (!IsGeneratedByIA(in.semanticName) && !HasElement(elements, count, in)) {
      out.error = "INPUT_ELEMENT_DESC: no element for vertex shader input " + in.semanticName +
                  std::to_string(in.semanticIndex);
      return out;
    }
  }
  const std::vector<UINT> offsets = ResolveOffsets(elements, count);
  for (UINT i = 0; i < count; ++i) {
    const INPUT_ELEMENT_DESC& e = elements[i];
    const ShaderInput* in = FindShaderInput(shaderInputs, e);
    if (!in) continue;
    const FormatInfo* format = GetFormatInfo(e.Format);  // null only for unvalidated elements
    out.attributes.push_back({in->location, e.InputSlot, format ? format->vkFormat : VK_FORMAT_UNDEFINED, offsets[i]});
    AddBinding(out, e, strides);
  }
  return out;
}

}  // namespace rhi::states
