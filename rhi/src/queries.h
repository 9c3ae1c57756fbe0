// D3D11 queries over Vulkan query pools.
//
// A D3D11 query may stay active across anything the application does, but a
// Vulkan query must begin and end in one command buffer. So a query records
// one or more segments (a new one after every submission while it is active)
// and GetData sums them. Begin and End are recorded outside rendering
// instances, so a segment may span several of them.
#pragma once

#include <vector>

#include "device.h"

namespace rhi::vk {

class QueryImpl final : public DeviceChildImpl<Query> {
 public:
  static HRESULT Create(DeviceImpl* device, const QUERY_DESC& desc, QueryImpl** out);
  ~QueryImpl() override;

  void GetDesc(QUERY_DESC* desc) override { *desc = desc_; }
  UINT GetDataSize() override;

  void Begin(VkCommandBuffer commands);
  void End(VkCommandBuffer commands, uint64_t serial);
  // Called around a submission while the query is active.
  void EndSegment(VkCommandBuffer commands);
  void BeginSegment(VkCommandBuffer commands);
  HRESULT GetData(void* data, UINT size, UINT flags, ContextImpl& context);
  bool active() const { return active_; }

 private:
  QueryImpl(DeviceImpl* device, const QUERY_DESC& desc) : DeviceChildImpl(device), desc_(desc) {}
  HRESULT Initialize();
  bool UsesVulkanQueries() const;
  // Number of Vulkan queries per segment: one per stream for "any stream" predicates.
  uint32_t QueriesPerSegment() const;
  void BeginVulkanQueries(VkCommandBuffer commands);
  void EndVulkanQueries(VkCommandBuffer commands);
  VkQueryPool SegmentPool(uint32_t segment);
  bool ReadResults(std::vector<uint64_t>* sums);

  QUERY_DESC desc_;
  VkQueryType type_ = VK_QUERY_TYPE_OCCLUSION;
  VkQueryPipelineStatisticFlags statistics_ = 0;
  uint32_t valuesPerQuery_ = 1;
  uint32_t firstStream_ = 0;
  std::vector<VkQueryPool> pools_;  // one per segment, reused across Begin/End pairs
  uint32_t segments_ = 0;
  bool active_ = false;
  bool issued_ = false;
  uint64_t endSerial_ = 0;
};

}  // namespace rhi::vk
