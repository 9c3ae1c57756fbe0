// Graphics and compute pipelines, built lazily from the bound D3D11 state and
// cached by a key of that state. State objects, shaders and input layouts enter
// the key by content id (object_caches.h): an object created again after its
// release finds the pipelines built for the first, so the cache grows with the
// distinct contents, not with the objects. Everything that Vulkan can take as
// dynamic state stays out of it.
#pragma once

#include <array>
#include <memory>
#include <string>
#include <unordered_map>
#include <vector>

#include "gpu.h"
#include "rhi/shader_bindings.h"

namespace rhi::vk {

class ShaderCode;
class InputLayoutImpl;
struct StreamOutput;

struct GraphicsPipelineKey {
  std::array<uint64_t, 5> shaders{};  // VS, HS, DS, GS, PS content ids (0: none)
  uint64_t inputLayout = 0;
  uint64_t blend = 0, depthStencil = 0, rasterizer = 0;  // content ids, 0: D3D11 default
  std::array<uint32_t, SIMULTANEOUS_RENDER_TARGET_COUNT> colorFormats{};  // DXGI formats
  uint32_t depthFormat = 0;  // the VkFormat of the bound depth-stencil view's image (0: none)
  uint16_t samples = 1;
  uint16_t dsvFlags = 0;  // DSV_READ_ONLY_* of the bound depth-stencil view: those writes are dropped
  uint32_t sampleMask = 0;
  uint32_t topologyClass = 0;  // VkPrimitiveTopology class representative, or patch control points + 100
  bool operator==(const GraphicsPipelineKey&) const = default;
};

struct GraphicsPipelineKeyHash {
  size_t operator()(const GraphicsPipelineKey& key) const;
};

// The key of the D3D11 default state (as after ClearState).
GraphicsPipelineKey DefaultPipelineKey();
// The key's topologyClass: topologies Vulkan switches dynamically share a pipeline.
uint32_t TopologyClass(PRIMITIVE_TOPOLOGY topology);

// Which D3D11 register a descriptor binding stands for (inverse of BindingFor).
struct RegisterSlot {
  ShaderStage stage;
  RegisterClass registerClass;
  uint32_t slot;
  bool counter = false;  // the hidden counter of UAV u<slot>, not the UAV itself
};
inline RegisterSlot RegisterOfBinding(uint32_t binding) {
  const auto stage = static_cast<ShaderStage>(binding / kStageStride);
  const uint32_t offset = binding % kStageStride;
  if (offset >= kUnorderedAccessCounterBase)
    return {stage, RegisterClass::UnorderedAccess, offset - kUnorderedAccessCounterBase, true};
  if (offset >= kUnorderedAccessBase) return {stage, RegisterClass::UnorderedAccess, offset - kUnorderedAccessBase};
  if (offset >= kSamplerBase) return {stage, RegisterClass::Sampler, offset - kSamplerBase};
  if (offset >= kShaderResourceBase) return {stage, RegisterClass::ShaderResource, offset - kShaderResourceBase};
  return {stage, RegisterClass::ConstantBuffer, offset};
}

struct PipelineLayout {
  VkDescriptorSetLayout setLayout = VK_NULL_HANDLE;
  VkPipelineLayout layout = VK_NULL_HANDLE;
  std::vector<VkDescriptorSetLayoutBinding> bindings;
  std::vector<RegisterSlot> registers;  // of each binding, decoded once for the draw path
};

struct GraphicsPipeline {
  VkPipeline pipeline = VK_NULL_HANDLE;
  const PipelineLayout* layout = nullptr;
  uint32_t vertexSlots = 0;  // bitmask of the input slots the input layout reads
  std::shared_ptr<const StreamOutput> streamOutput;
  bool rasterizes = true;
};

struct ComputePipeline {
  VkPipeline pipeline = VK_NULL_HANDLE;
  const PipelineLayout* layout = nullptr;
};

// Everything a graphics pipeline is built from.
struct GraphicsPipelineInputs {
  std::array<const ShaderCode*, 5> shaders{};  // VS, HS, DS, GS, PS
  const InputLayoutImpl* inputLayout = nullptr;
  const BLEND_DESC* blend = nullptr;
  const DEPTH_STENCIL_DESC* depthStencil = nullptr;
  const RASTERIZER_DESC* rasterizer = nullptr;
  std::array<DXGI_FORMAT, SIMULTANEOUS_RENDER_TARGET_COUNT> colorFormats{};
  VkFormat depthFormat = VK_FORMAT_UNDEFINED;  // the depth-stencil view's image format
  UINT dsvFlags = 0;
  uint32_t samples = 1;
  uint32_t sampleMask = DEFAULT_SAMPLE_MASK;
  PRIMITIVE_TOPOLOGY topology = PRIMITIVE_TOPOLOGY_UNDEFINED;
};

class PipelineCache {
 public:
  explicit PipelineCache(Gpu& gpu);
  ~PipelineCache();

  // The pipeline built for `key`, or null if none was yet.
  const GraphicsPipeline* FindGraphics(const GraphicsPipelineKey& key);
  // Finds or builds the pipeline. Null with `error` set when the state cannot
  // form a pipeline (a D3D11 draw-time error).
  const GraphicsPipeline* Graphics(const GraphicsPipelineKey& key, const GraphicsPipelineInputs& inputs,
                                   std::string* error);
  const ComputePipeline* Compute(const ShaderCode& shader, std::string* error);
  // The backend's own compute step turning a stream-output counter into draw arguments.
  const ComputePipeline& DrawAutoArgs();

 private:
  const PipelineLayout* Layout(const std::vector<VkDescriptorSetLayoutBinding>& bindings,
                               uint32_t pushConstantBytes = 0);
  std::unique_ptr<GraphicsPipeline> BuildGraphics(const GraphicsPipelineInputs& inputs, std::string* error);
  VkShaderModule CreateModule(const std::vector<uint32_t>& words);

  Gpu& gpu_;
  std::unordered_map<GraphicsPipelineKey, std::unique_ptr<GraphicsPipeline>, GraphicsPipelineKeyHash> graphics_;
  // Recently found pipelines, direct-mapped by key hash, in front of graphics_:
  // draws look up a key on every pipeline change, and the map's prime bucket
  // count costs a 64-bit division per find. Pipelines live as long as the cache.
  struct RecentGraphics {
    GraphicsPipelineKey key;
    const GraphicsPipeline* pipeline = nullptr;
  };
  std::array<RecentGraphics, 64> recentGraphics_{};
  std::unordered_map<uint64_t, std::unique_ptr<ComputePipeline>> compute_;
  std::unordered_map<std::string, std::unique_ptr<PipelineLayout>> layouts_;
  std::unique_ptr<ComputePipeline> drawAutoArgs_;
};

}  // namespace rhi::vk
