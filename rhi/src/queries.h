// D3D11 queries over Vulkan query pools.
//
// D3D11 lets any number of queries of one kind be active at once, across
// anything the application does. Vulkan allows one active query per type (and
// stream) in a command buffer, which must begin and end in that command buffer.
// So the context keeps, per kind, one open Vulkan query (a "segment") while any
// D3D11 query of that kind is active; whenever the set of active queries
// changes, or a command buffer is submitted, the open segment is closed and
// handed to every query that was active during it, and a new one opens. A
// query's result is the sum over its segments. Segments begin and end outside
// rendering instances, so one segment may span several of them.
#pragma once

#include <map>
#include <memory>
#include <vector>

#include "device.h"

namespace rhi::vk {

class QueryTracker;

// The pipeline statistics the device can count, in D3D11's order.
VkQueryPipelineStatisticFlags SupportedStatistics(const GpuCapabilities& caps);

// Which Vulkan query a D3D11 query is made of: a type and, for stream-output
// queries, the stream.
struct QueryKind {
  VkQueryType type = VK_QUERY_TYPE_OCCLUSION;
  uint32_t stream = 0;
  auto operator<=>(const QueryKind&) const = default;
};

struct QuerySegment {
  QueryTracker* tracker = nullptr;
  QueryKind kind;
  VkQueryPool pool = VK_NULL_HANDLE;
  ~QuerySegment();
};

// Every query implements Predicate (ID3D11Predicate adds nothing to ID3D11Query);
// CreatePredicate accepts only the predicate kinds.
class QueryImpl final : public DeviceChildImpl<Predicate> {
 public:
  static HRESULT Create(DeviceImpl* device, const QUERY_DESC& desc, QueryImpl** out);
  ~QueryImpl() override;

  void GetDesc(QUERY_DESC* desc) override { *desc = desc_; }
  UINT GetDataSize() override;
  HRESULT GetData(void* data, UINT size, UINT flags, ContextImpl& context);

  const QUERY_DESC& desc() const { return desc_; }
  // The Vulkan queries this D3D11 query is made of (none for EVENT and TIMESTAMP_DISJOINT).
  const std::vector<QueryKind>& kinds() const { return kinds_; }
  bool active = false;
  // Segments per kind, filled by the tracker.
  std::vector<std::vector<std::shared_ptr<QuerySegment>>> segments;
  VkQueryPool timestampPool = VK_NULL_HANDLE;
  uint64_t endSerial = 0;
  bool issued = false;

 private:
  QueryImpl(DeviceImpl* device, const QUERY_DESC& desc) : DeviceChildImpl(device), desc_(desc) {}
  HRESULT Initialize();
  bool SumResults(size_t kind, uint32_t valuesPerQuery, std::vector<uint64_t>* sums);

  QUERY_DESC desc_;
  std::vector<QueryKind> kinds_;
  VkQueryPipelineStatisticFlags statistics_ = 0;
};

class QueryTracker {
 public:
  explicit QueryTracker(Gpu& gpu) : gpu_(gpu) {}
  ~QueryTracker();

  void Begin(QueryImpl& query, VkCommandBuffer commands);
  void End(QueryImpl& query, VkCommandBuffer commands);
  // Around a submission: close every open segment, then reopen in the new command buffer.
  void Suspend(VkCommandBuffer commands);
  void Resume(VkCommandBuffer commands);
  // A destroyed query leaves every active set.
  void Forget(QueryImpl& query, VkCommandBuffer commands);
  void Recycle(const QueryKind& kind, VkQueryPool pool) { freePools_[kind].push_back(pool); }
  VkQueryPipelineStatisticFlags statistics = 0;

 private:
  struct KindState {
    std::vector<QueryImpl*> active;
    std::shared_ptr<QuerySegment> open;
  };
  void Close(const QueryKind& kind, KindState& state, VkCommandBuffer commands);
  void Open(const QueryKind& kind, KindState& state, VkCommandBuffer commands);
  void Leave(QueryImpl& query, VkCommandBuffer commands);

  Gpu& gpu_;
  std::map<QueryKind, KindState> kinds_;
  std::map<QueryKind, std::vector<VkQueryPool>> freePools_;
};

}  // namespace rhi::vk
