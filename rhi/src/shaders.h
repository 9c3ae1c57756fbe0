// Shader objects and input layouts.
//
// A shader object keeps its SPIR-V and its reflection; Vulkan shader modules
// are made per pipeline, because linking by HLSL semantic, dual-source output
// and point size patch the code for the pipeline it ends up in.
#pragma once

#include <array>
#include <memory>
#include <string>
#include <vector>

#include "device.h"
#include "rhi/shader_bindings.h"
#include "spirv/reflection.h"

namespace rhi::vk {

struct StreamOutput {
  std::array<UINT, SO_BUFFER_SLOT_COUNT> strides{};
  UINT rasterizedStream = 0;
  bool capturesStream(UINT stream) const;
  std::vector<SO_DECLARATION_ENTRY> entries;  // semantic names point into `names`
  std::vector<std::string> names;
};

class ShaderCode {
 public:
  ShaderStage stage = ShaderStage::Vertex;
  std::vector<uint32_t> words;
  spirv::Reflection reflection;
  uint64_t contentId = 0;  // equal for equal code and stream-output declaration (pipeline keys)
  // Set on objects from CreateGeometryShaderWithStreamOutput; `words` carry the
  // transform feedback decorations. Vertex-stage code here means VS-only stream output.
  std::shared_ptr<const StreamOutput> streamOutput;
};

template <class Interface>
class ShaderObject final : public DeviceChildImpl<Interface> {
 public:
  ShaderObject(DeviceImpl* device, std::shared_ptr<const ShaderCode> code)
      : DeviceChildImpl<Interface>(device), code_(std::move(code)) {}
  const std::shared_ptr<const ShaderCode>& code() const { return code_; }

 private:
  std::shared_ptr<const ShaderCode> code_;
};

// Parses, reflects and checks SPIR-V handed to a Create*Shader call.
HRESULT LoadShaderCode(DeviceImpl& device, const void* bytecode, SIZE_T length, ShaderStage expected,
                       const char* call, std::shared_ptr<ShaderCode>* out);

class InputLayoutImpl final : public DeviceChildImpl<InputLayout> {
 public:
  InputLayoutImpl(DeviceImpl* device, const INPUT_ELEMENT_DESC* elements, UINT count);
  // The elements with owned semantic names and resolved offsets (never APPEND_ALIGNED_ELEMENT).
  const std::vector<INPUT_ELEMENT_DESC>& elements() const { return elements_; }
  uint64_t contentId() const { return contentId_; }  // equal for equal elements (pipeline keys)

 private:
  uint64_t contentId_ = 0;
  std::vector<std::string> names_;
  std::vector<INPUT_ELEMENT_DESC> elements_;
};

}  // namespace rhi::vk
