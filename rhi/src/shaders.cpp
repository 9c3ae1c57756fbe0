#include "shaders.h"

#include <algorithm>
#include <cctype>
#include <cstring>

#include "object_caches.h"
#include "spirv/patches.h"
#include "spirv/stream_output.h"
#include "states/input_layout.h"

namespace rhi::vk {

namespace {

const char* StageName(ShaderStage stage) {
  switch (stage) {
    case ShaderStage::Vertex: return "vertex";
    case ShaderStage::Hull: return "hull";
    case ShaderStage::Domain: return "domain";
    case ShaderStage::Geometry: return "geometry";
    case ShaderStage::Pixel: return "pixel";
    case ShaderStage::Compute: return "compute";
  }
  return "?";
}

// The first register the shader writes through (a UAV), if any.
const spirv::DescriptorBinding* FirstWritableBinding(const spirv::Reflection& reflection) {
  for (const spirv::DescriptorBinding& b : reflection.bindings) {
    const bool storage = b.kind == spirv::DescriptorKind::StorageBuffer ||
                         b.kind == spirv::DescriptorKind::StorageImage ||
                         b.kind == spirv::DescriptorKind::StorageTexelBuffer;
    if (storage && !b.nonWritable) return &b;
  }
  return nullptr;
}

// Vulkan lets graphics stages write storage resources only with the
// fragmentStoresAndAtomics / vertexPipelineStoresAndAtomics features.
std::string CheckUavSupport(const Gpu& gpu, ShaderStage stage, const spirv::Reflection& reflection) {
  if (stage == ShaderStage::Compute) return {};
  const spirv::DescriptorBinding* uav = FirstWritableBinding(reflection);
  if (!uav) return {};
  const bool pixel = stage == ShaderStage::Pixel;
  if (pixel ? gpu.Caps().fragmentStoresAndAtomics : gpu.Caps().vertexPipelineStoresAndAtomics) return {};
  return std::string("the ") + StageName(stage) + " shader writes unordered access view '" + uav->name + "', but " +
         gpu.AdapterName() + " lacks " + (pixel ? "fragmentStoresAndAtomics" : "vertexPipelineStoresAndAtomics");
}

// A pixel shader that reads SV_SampleIndex (Vulkan's SampleId) or the sample
// position runs per sample, in D3D11 as in Vulkan.
bool RunsPerSample(const spirv::Reflection& reflection) {
  static constexpr uint32_t kBuiltInSampleId = 18, kBuiltInSamplePosition = 19;
  return std::any_of(reflection.inputs.begin(), reflection.inputs.end(), [](const spirv::InterfaceVariable& input) {
    return input.builtIn == kBuiltInSampleId || input.builtIn == kBuiltInSamplePosition;
  });
}

template <class T>
void AppendBytes(std::string& out, const T& value) {
  out.append(reinterpret_cast<const char*>(&value), sizeof value);
}

// Everything a pipeline takes from the shader: the (patched) code and the stream-output declaration.
void AssignContentId(DeviceImpl& device, ShaderCode& code) {
  std::string content(reinterpret_cast<const char*>(code.words.data()), code.words.size() * sizeof(uint32_t));
  if (const StreamOutput* so = code.streamOutput.get()) {
    AppendBytes(content, so->rasterizedStream);
    AppendBytes(content, so->strides);
    for (const SO_DECLARATION_ENTRY& e : so->entries) {
      content += e.SemanticName ? e.SemanticName : "";
      for (UINT field : {e.Stream, e.SemanticIndex, UINT(e.StartComponent), UINT(e.ComponentCount), UINT(e.OutputSlot)})
        AppendBytes(content, field);
    }
  }
  code.contentId = device.caches().shaders.IdOf(device, std::move(content));
}

template <class Interface>
HRESULT CreateShaderObject(DeviceImpl& device, const void* bytecode, SIZE_T length, ClassLinkage* linkage,
                           ShaderStage stage, const char* call, Interface** out) {
  if (linkage) return device.gpu().Refuse(std::string(call) + ": class linkage is not supported");
  std::shared_ptr<ShaderCode> code;
  if (HRESULT hr = LoadShaderCode(device, bytecode, length, stage, call, &code); FAILED(hr)) return hr;
  AssignContentId(device, *code);
  *out = new ShaderObject<Interface>(&device, std::move(code));
  return S_OK;
}

}  // namespace

bool StreamOutput::capturesStream(UINT stream) const {
  return std::any_of(entries.begin(), entries.end(), [&](const auto& e) { return e.Stream == stream; });
}

HRESULT LoadShaderCode(DeviceImpl& device, const void* bytecode, SIZE_T length, ShaderStage expected,
                       const char* call, std::shared_ptr<ShaderCode>* out) {
  Gpu& gpu = device.gpu();
  if (!bytecode || length < 20 || length % 4)
    return gpu.Refuse(std::string(call) + ": bytecode must be SPIR-V (a non-empty multiple of 4 bytes)");
  auto code = std::make_shared<ShaderCode>();
  code->words.resize(length / 4);
  std::memcpy(code->words.data(), bytecode, length);
  // A UAV's hidden counter is bound by the UAV's slot (before reflection, which reports the moved binding).
  spirv::WordsResult counters =
      spirv::MoveHiddenCounters(code->words, kUnorderedAccessCounterBase - kUnorderedAccessBase);
  if (!counters) return gpu.Refuse(std::string(call) + ": " + counters.error);
  code->words = std::move(*counters);
  spirv::Result<spirv::Reflection> reflected = spirv::Reflect(code->words);
  if (!reflected) return gpu.Refuse(std::string(call) + ": " + reflected.error);
  code->reflection = std::move(*reflected);
  if (code->reflection.stage == spirv::Stage::Unknown)
    return gpu.Refuse(std::string(call) + ": the SPIR-V has no entry point of a D3D11 shader stage");
  // spirv::Stage lists the stages in rhi::ShaderStage's order.
  code->stage = static_cast<ShaderStage>(code->reflection.stage);
  if (code->stage != expected)
    return gpu.Refuse(std::string(call) + ": the SPIR-V holds a " + StageName(code->stage) + " shader, not a " +
                      StageName(expected) + " shader");
  if ((expected == ShaderStage::Geometry && !gpu.Caps().geometryShader) ||
      ((expected == ShaderStage::Hull || expected == ShaderStage::Domain) && !gpu.Caps().tessellationShader))
    return gpu.Refuse(std::string(call) + ": " + gpu.AdapterName() + " has no " + StageName(expected) + " shaders");
  if (std::string reason = CheckUavSupport(gpu, code->stage, code->reflection); !reason.empty())
    return gpu.Refuse(std::string(call) + ": " + reason);
  if (expected == ShaderStage::Pixel && RunsPerSample(code->reflection) && !gpu.Caps().sampleRateShading)
    return gpu.Refuse(std::string(call) +
                      ": the shader reads SV_SampleIndex (or the sample position), so it runs once per sample, "
                      "which needs Vulkan's sampleRateShading feature; " + gpu.AdapterName() + " lacks it");
  // D3D11's SV_InstanceID counts from 0 in every draw; Vulkan's InstanceIndex includes firstInstance.
  if (expected == ShaderStage::Vertex) code->words = spirv::RebaseInstanceIndex(code->words).value;
  *out = std::move(code);
  return S_OK;
}

// ---------------------------------------------------------------------------
// Device entry points

HRESULT DeviceImpl::CreateVertexShader(const void* pShaderBytecode, SIZE_T BytecodeLength, ClassLinkage* pClassLinkage,
                                       VertexShader** ppVertexShader) {
  return CreateShaderObject(*this, pShaderBytecode, BytecodeLength, pClassLinkage, ShaderStage::Vertex,
                            "CreateVertexShader", ppVertexShader);
}

HRESULT DeviceImpl::CreateHullShader(const void* pShaderBytecode, SIZE_T BytecodeLength, ClassLinkage* pClassLinkage,
                                     HullShader** ppHullShader) {
  return CreateShaderObject(*this, pShaderBytecode, BytecodeLength, pClassLinkage, ShaderStage::Hull,
                            "CreateHullShader", ppHullShader);
}

HRESULT DeviceImpl::CreateDomainShader(const void* pShaderBytecode, SIZE_T BytecodeLength, ClassLinkage* pClassLinkage,
                                       DomainShader** ppDomainShader) {
  return CreateShaderObject(*this, pShaderBytecode, BytecodeLength, pClassLinkage, ShaderStage::Domain,
                            "CreateDomainShader", ppDomainShader);
}

HRESULT DeviceImpl::CreateGeometryShader(const void* pShaderBytecode, SIZE_T BytecodeLength,
                                         ClassLinkage* pClassLinkage, GeometryShader** ppGeometryShader) {
  return CreateShaderObject(*this, pShaderBytecode, BytecodeLength, pClassLinkage, ShaderStage::Geometry,
                            "CreateGeometryShader", ppGeometryShader);
}

HRESULT DeviceImpl::CreatePixelShader(const void* pShaderBytecode, SIZE_T BytecodeLength, ClassLinkage* pClassLinkage,
                                      PixelShader** ppPixelShader) {
  return CreateShaderObject(*this, pShaderBytecode, BytecodeLength, pClassLinkage, ShaderStage::Pixel,
                            "CreatePixelShader", ppPixelShader);
}

HRESULT DeviceImpl::CreateComputeShader(const void* pShaderBytecode, SIZE_T BytecodeLength,
                                        ClassLinkage* pClassLinkage, ComputeShader** ppComputeShader) {
  return CreateShaderObject(*this, pShaderBytecode, BytecodeLength, pClassLinkage, ShaderStage::Compute,
                            "CreateComputeShader", ppComputeShader);
}

HRESULT DeviceImpl::CreateGeometryShaderWithStreamOutput(const void* pShaderBytecode, SIZE_T BytecodeLength,
                                                         const SO_DECLARATION_ENTRY* pSODeclaration, UINT NumEntries,
                                                         const UINT* pBufferStrides, UINT NumStrides,
                                                         UINT RasterizedStream, ClassLinkage* pClassLinkage,
                                                         GeometryShader** ppGeometryShader) {
  constexpr const char* kCall = "CreateGeometryShaderWithStreamOutput";
  if (pClassLinkage) return gpu_->Refuse(std::string(kCall) + ": class linkage is not supported");
  if (!gpu_->Caps().transformFeedback)
    return gpu_->Refuse(std::string(kCall) + ": " + gpu_->AdapterName() + " lacks VK_EXT_transform_feedback");
  // D3D11 accepts a vertex shader here for stream output without a geometry shader.
  const bool fromVertexShader = BytecodeLength >= 20 && BytecodeLength % 4 == 0 && pShaderBytecode &&
                                spirv::Reflect(std::span(static_cast<const uint32_t*>(pShaderBytecode),
                                                         BytecodeLength / 4))
                                        ->stage == spirv::Stage::Vertex;
  std::shared_ptr<ShaderCode> code;
  HRESULT hr = LoadShaderCode(*this, pShaderBytecode, BytecodeLength,
                              fromVertexShader ? ShaderStage::Vertex : ShaderStage::Geometry, kCall, &code);
  if (FAILED(hr)) return hr;
  if (std::string reason = spirv::ValidateSoDeclaration(pSODeclaration, NumEntries, pBufferStrides, NumStrides,
                                                        RasterizedStream, code->reflection);
      !reason.empty())
    return gpu_->Refuse(std::string(kCall) + ": " + reason);
  // Streams beyond what the device captures, or a rasterized stream it cannot select, are refused.
  const UINT streams = std::max(1u, gpu_->Caps().maxTransformFeedbackStreams);
  for (UINT i = 0; i < NumEntries; ++i)
    if (pSODeclaration[i].Stream >= streams)
      return gpu_->Refuse(std::string(kCall) + ": entry " + std::to_string(i) + " uses stream " +
                          std::to_string(pSODeclaration[i].Stream) + " but " + gpu_->AdapterName() + " captures " +
                          std::to_string(streams) + " stream(s)");
  if (RasterizedStream != 0 && RasterizedStream != SO_NO_RASTERIZED_STREAM && !gpu_->Caps().rasterizationStreamSelect)
    return gpu_->Refuse(std::string(kCall) + ": " + gpu_->AdapterName() + " cannot rasterize stream " +
                        std::to_string(RasterizedStream));

  auto so = std::make_shared<StreamOutput>();
  so->rasterizedStream = RasterizedStream;
  so->strides = spirv::SoBufferStrides(std::span(pSODeclaration, NumEntries), std::span(pBufferStrides, NumStrides));
  so->names.reserve(NumEntries);
  for (UINT i = 0; i < NumEntries; ++i) {
    SO_DECLARATION_ENTRY entry = pSODeclaration[i];
    if (entry.SemanticName) {
      so->names.emplace_back(entry.SemanticName);
      entry.SemanticName = so->names.back().c_str();
    }
    so->entries.push_back(entry);
  }
  spirv::WordsResult patched = spirv::ApplyStreamOutput(code->words, code->reflection, so->entries, so->strides);
  if (!patched) return gpu_->Refuse(std::string(kCall) + ": " + patched.error);
  code->words = std::move(*patched);
  code->streamOutput = std::move(so);
  AssignContentId(*this, *code);
  *ppGeometryShader = new ShaderObject<GeometryShader>(this, std::move(code));
  return S_OK;
}

// ---------------------------------------------------------------------------
// Input layouts

InputLayoutImpl::InputLayoutImpl(DeviceImpl* device, const INPUT_ELEMENT_DESC* elements, UINT count)
    : DeviceChildImpl(device) {
  std::vector<UINT> offsets = states::ResolveOffsets(elements, count);
  names_.reserve(count);
  for (UINT i = 0; i < count; ++i) {
    INPUT_ELEMENT_DESC element = elements[i];
    std::string name = element.SemanticName;
    std::transform(name.begin(), name.end(), name.begin(), [](unsigned char c) { return std::toupper(c); });
    names_.push_back(std::move(name));
    element.SemanticName = names_.back().c_str();
    element.AlignedByteOffset = offsets[i];
    elements_.push_back(element);
  }
  std::string content;
  for (const INPUT_ELEMENT_DESC& e : elements_) {
    content.append(e.SemanticName, std::strlen(e.SemanticName) + 1);
    for (UINT field : {e.SemanticIndex, UINT(e.Format), e.InputSlot, e.AlignedByteOffset, UINT(e.InputSlotClass),
                       e.InstanceDataStepRate})
      AppendBytes(content, field);
  }
  contentId_ = device->caches().inputLayouts.IdOf(*device, std::move(content));
}

HRESULT DeviceImpl::CreateInputLayout(const INPUT_ELEMENT_DESC* pInputElementDescs, UINT NumElements,
                                      const void* pShaderBytecodeWithInputSignature, SIZE_T BytecodeLength,
                                      InputLayout** ppInputLayout) {
  constexpr const char* kCall = "CreateInputLayout";
  if (std::string reason = states::Validate(pInputElementDescs, NumElements); !reason.empty())
    return gpu_->Refuse(std::string(kCall) + ": " + reason);
  std::shared_ptr<ShaderCode> vs;
  if (HRESULT hr = LoadShaderCode(*this, pShaderBytecodeWithInputSignature, BytecodeLength, ShaderStage::Vertex, kCall,
                                  &vs);
      FAILED(hr))
    return hr;
  // D3D11 refuses a layout that lacks an input the vertex shader reads.
  ComPtr<InputLayoutImpl> layout;
  layout.Attach(new InputLayoutImpl(this, pInputElementDescs, NumElements));
  for (const auto& input : vs->reflection.inputs) {
    if (!input.location || input.builtIn) continue;
    bool found = std::any_of(layout->elements().begin(), layout->elements().end(), [&](const INPUT_ELEMENT_DESC& e) {
      return input.semanticName == e.SemanticName && input.semanticIndex == e.SemanticIndex;
    });
    if (!found)
      return gpu_->Refuse(std::string(kCall) + ": the vertex shader reads " + input.Semantic() +
                          ", which no element provides");
  }
  *ppInputLayout = layout.Detach();
  return S_OK;
}

}  // namespace rhi::vk
