#include "queries.h"

#include <algorithm>
#include <cstring>

#include "context.h"

namespace rhi::vk {

namespace {

bool IsStreamOutQuery(QUERY q) { return q >= QUERY_SO_STATISTICS && q <= QUERY_SO_OVERFLOW_PREDICATE_STREAM3; }
bool IsOverflowPredicate(QUERY q) {
  return q == QUERY_SO_OVERFLOW_PREDICATE ||
         (q >= QUERY_SO_OVERFLOW_PREDICATE_STREAM0 && q <= QUERY_SO_OVERFLOW_PREDICATE_STREAM3);
}

// The statistics D3D11 reports, in QUERY_DATA_PIPELINE_STATISTICS order, which
// is also the order of the Vulkan flag bits (results come back in bit order).
constexpr VkQueryPipelineStatisticFlags kAllStatistics =
    VK_QUERY_PIPELINE_STATISTIC_INPUT_ASSEMBLY_VERTICES_BIT | VK_QUERY_PIPELINE_STATISTIC_INPUT_ASSEMBLY_PRIMITIVES_BIT |
    VK_QUERY_PIPELINE_STATISTIC_VERTEX_SHADER_INVOCATIONS_BIT |
    VK_QUERY_PIPELINE_STATISTIC_GEOMETRY_SHADER_INVOCATIONS_BIT |
    VK_QUERY_PIPELINE_STATISTIC_GEOMETRY_SHADER_PRIMITIVES_BIT | VK_QUERY_PIPELINE_STATISTIC_CLIPPING_INVOCATIONS_BIT |
    VK_QUERY_PIPELINE_STATISTIC_CLIPPING_PRIMITIVES_BIT | VK_QUERY_PIPELINE_STATISTIC_FRAGMENT_SHADER_INVOCATIONS_BIT |
    VK_QUERY_PIPELINE_STATISTIC_TESSELLATION_CONTROL_SHADER_PATCHES_BIT |
    VK_QUERY_PIPELINE_STATISTIC_TESSELLATION_EVALUATION_SHADER_INVOCATIONS_BIT |
    VK_QUERY_PIPELINE_STATISTIC_COMPUTE_SHADER_INVOCATIONS_BIT;

}  // namespace

HRESULT QueryImpl::Create(DeviceImpl* device, const QUERY_DESC& desc, QueryImpl** out) {
  Gpu& gpu = device->gpu();
  if (desc.Query > QUERY_SO_OVERFLOW_PREDICATE_STREAM3)
    return gpu.Refuse("CreateQuery: Query " + std::to_string(desc.Query) + " is not a D3D11_QUERY");
  if (desc.Query == QUERY_PIPELINE_STATISTICS && !gpu.Caps().pipelineStatistics)
    return gpu.Refuse("CreateQuery: " + gpu.AdapterName() + " has no pipeline statistics queries");
  if (IsStreamOutQuery(desc.Query) && !gpu.Caps().transformFeedbackQueries)
    return gpu.Refuse("CreateQuery: " + gpu.AdapterName() + " has no transform feedback queries");
  ComPtr<QueryImpl> query;
  query.Attach(new QueryImpl(device, desc));
  if (HRESULT hr = query->Initialize(); FAILED(hr)) return hr;
  *out = query.Detach();
  return S_OK;
}

HRESULT QueryImpl::Initialize() {
  const GpuCapabilities& caps = gpu().Caps();
  switch (desc_.Query) {
    case QUERY_OCCLUSION:
    case QUERY_OCCLUSION_PREDICATE: type_ = VK_QUERY_TYPE_OCCLUSION; break;
    case QUERY_TIMESTAMP: type_ = VK_QUERY_TYPE_TIMESTAMP; break;
    case QUERY_PIPELINE_STATISTICS: {
      type_ = VK_QUERY_TYPE_PIPELINE_STATISTICS;
      statistics_ = kAllStatistics;
      if (!caps.tessellationShader)
        statistics_ &= ~(VK_QUERY_PIPELINE_STATISTIC_TESSELLATION_CONTROL_SHADER_PATCHES_BIT |
                         VK_QUERY_PIPELINE_STATISTIC_TESSELLATION_EVALUATION_SHADER_INVOCATIONS_BIT);
      valuesPerQuery_ = static_cast<uint32_t>(std::popcount(statistics_));
      break;
    }
    default:
      if (IsStreamOutQuery(desc_.Query)) {
        type_ = VK_QUERY_TYPE_TRANSFORM_FEEDBACK_STREAM_EXT;
        valuesPerQuery_ = 2;  // primitives written, primitives needed
        if (desc_.Query >= QUERY_SO_STATISTICS_STREAM0)
          firstStream_ = (desc_.Query - QUERY_SO_STATISTICS_STREAM0) % 4;
        if (firstStream_ >= std::max(1u, caps.maxTransformFeedbackStreams))
          return gpu().Refuse("CreateQuery: stream " + std::to_string(firstStream_) + " is beyond the " +
                              std::to_string(caps.maxTransformFeedbackStreams) + " streams of " + gpu().AdapterName());
      }
      break;
  }
  return S_OK;
}

QueryImpl::~QueryImpl() {
  VkDevice vkDevice = gpu().Device();
  auto pools = pools_;
  gpu().DeferDestroy([=] {
    for (VkQueryPool pool : pools) vkDestroyQueryPool(vkDevice, pool, nullptr);
  });
}

UINT QueryImpl::GetDataSize() {
  switch (desc_.Query) {
    case QUERY_EVENT:
    case QUERY_OCCLUSION_PREDICATE:
    case QUERY_SO_OVERFLOW_PREDICATE:
    case QUERY_SO_OVERFLOW_PREDICATE_STREAM0:
    case QUERY_SO_OVERFLOW_PREDICATE_STREAM1:
    case QUERY_SO_OVERFLOW_PREDICATE_STREAM2:
    case QUERY_SO_OVERFLOW_PREDICATE_STREAM3: return sizeof(BOOL);
    case QUERY_OCCLUSION:
    case QUERY_TIMESTAMP: return sizeof(UINT64);
    case QUERY_TIMESTAMP_DISJOINT: return sizeof(QUERY_DATA_TIMESTAMP_DISJOINT);
    case QUERY_PIPELINE_STATISTICS: return sizeof(QUERY_DATA_PIPELINE_STATISTICS);
    default: return sizeof(QUERY_DATA_SO_STATISTICS);
  }
}

bool QueryImpl::UsesVulkanQueries() const {
  return desc_.Query != QUERY_EVENT && desc_.Query != QUERY_TIMESTAMP_DISJOINT;
}

uint32_t QueryImpl::QueriesPerSegment() const {
  if (desc_.Query == QUERY_SO_OVERFLOW_PREDICATE) return std::max(1u, gpu().Caps().maxTransformFeedbackStreams);
  return 1;
}

VkQueryPool QueryImpl::SegmentPool(uint32_t segment) {
  while (pools_.size() <= segment) {
    VkQueryPoolCreateInfo info{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
    info.queryType = type_;
    info.queryCount = QueriesPerSegment();
    info.pipelineStatistics = statistics_;
    VkQueryPool pool = VK_NULL_HANDLE;
    vkCreateQueryPool(gpu().Device(), &info, nullptr, &pool);
    pools_.push_back(pool);
  }
  return pools_[segment];
}

void QueryImpl::BeginVulkanQueries(VkCommandBuffer commands) {
  VkQueryPool pool = SegmentPool(segments_);
  vkCmdResetQueryPool(commands, pool, 0, QueriesPerSegment());
  if (type_ == VK_QUERY_TYPE_TRANSFORM_FEEDBACK_STREAM_EXT) {
    for (uint32_t i = 0; i < QueriesPerSegment(); ++i)
      gpu().vkCmdBeginQueryIndexedEXT(commands, pool, i, 0, firstStream_ + i);
  } else {
    VkQueryControlFlags flags = desc_.Query == QUERY_OCCLUSION ? VK_QUERY_CONTROL_PRECISE_BIT : 0;
    vkCmdBeginQuery(commands, pool, 0, flags);
  }
  ++segments_;
}

void QueryImpl::EndVulkanQueries(VkCommandBuffer commands) {
  VkQueryPool pool = pools_[segments_ - 1];
  if (type_ == VK_QUERY_TYPE_TRANSFORM_FEEDBACK_STREAM_EXT) {
    for (uint32_t i = 0; i < QueriesPerSegment(); ++i)
      gpu().vkCmdEndQueryIndexedEXT(commands, pool, i, firstStream_ + i);
  } else {
    vkCmdEndQuery(commands, pool, 0);
  }
}

void QueryImpl::Begin(VkCommandBuffer commands) {
  // D3D11: Begin on an active query restarts it; timestamps and events have no Begin.
  if (desc_.Query == QUERY_TIMESTAMP || desc_.Query == QUERY_EVENT) return;
  if (active_ && UsesVulkanQueries()) EndVulkanQueries(commands);
  segments_ = 0;
  issued_ = false;
  active_ = true;
  if (UsesVulkanQueries()) BeginVulkanQueries(commands);
}

void QueryImpl::End(VkCommandBuffer commands, uint64_t serial) {
  if (desc_.Query == QUERY_TIMESTAMP) {
    segments_ = 0;
    VkQueryPool pool = SegmentPool(0);
    vkCmdResetQueryPool(commands, pool, 0, 1);
    vkCmdWriteTimestamp2(commands, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, pool, 0);
    segments_ = 1;
  } else if (active_ && UsesVulkanQueries()) {
    EndVulkanQueries(commands);
  }
  active_ = false;
  issued_ = true;
  endSerial_ = serial;
}

void QueryImpl::EndSegment(VkCommandBuffer commands) {
  if (UsesVulkanQueries()) EndVulkanQueries(commands);
}

void QueryImpl::BeginSegment(VkCommandBuffer commands) {
  if (UsesVulkanQueries()) BeginVulkanQueries(commands);
}

bool QueryImpl::ReadResults(std::vector<uint64_t>* sums) {
  const uint32_t perQuery = valuesPerQuery_;
  const uint32_t queries = QueriesPerSegment();
  sums->assign(static_cast<size_t>(perQuery) * queries, 0);
  std::vector<uint64_t> values(sums->size());
  for (uint32_t s = 0; s < segments_; ++s) {
    VkResult result = vkGetQueryPoolResults(gpu().Device(), pools_[s], 0, queries, values.size() * sizeof(uint64_t),
                                            values.data(), perQuery * sizeof(uint64_t), VK_QUERY_RESULT_64_BIT);
    if (result != VK_SUCCESS) return false;
    for (size_t i = 0; i < values.size(); ++i) (*sums)[i] += values[i];
  }
  return true;
}

HRESULT QueryImpl::GetData(void* data, UINT size, UINT flags, ContextImpl& context) {
  if (data && size != GetDataSize()) {
    return gpu().Refuse("GetData: DataSize " + std::to_string(size) + " does not match GetDataSize() " +
                        std::to_string(GetDataSize()));
  }
  if (active_ || !issued_) return gpu().Refuse("GetData: the query has not been ended since its last Begin");
  if (!gpu().IsComplete(endSerial_)) {
    if (endSerial_ == gpu().RecordingSerial() && !(flags & ASYNC_GETDATA_DONOTFLUSH)) context.Flush();
    return S_FALSE;
  }
  if (!data) return S_OK;
  std::vector<uint64_t> sums;
  if (UsesVulkanQueries() && !ReadResults(&sums)) return S_FALSE;
  switch (desc_.Query) {
    case QUERY_EVENT: *static_cast<BOOL*>(data) = TRUE; break;
    case QUERY_OCCLUSION:
    case QUERY_TIMESTAMP: *static_cast<UINT64*>(data) = sums[0]; break;
    case QUERY_OCCLUSION_PREDICATE: *static_cast<BOOL*>(data) = sums[0] != 0; break;
    case QUERY_TIMESTAMP_DISJOINT: {
      QUERY_DATA_TIMESTAMP_DISJOINT disjoint{};
      disjoint.Frequency = static_cast<UINT64>(1e9 / gpu().Caps().timestampPeriodNs);
      disjoint.Disjoint = FALSE;
      std::memcpy(data, &disjoint, sizeof disjoint);
      break;
    }
    case QUERY_PIPELINE_STATISTICS: {
      QUERY_DATA_PIPELINE_STATISTICS stats{};
      UINT64* fields = &stats.IAVertices;
      size_t next = 0;
      for (uint32_t bit = 0; bit < 11; ++bit)
        if (statistics_ & (1u << bit)) fields[bit] = sums[next++];
      std::memcpy(data, &stats, sizeof stats);
      break;
    }
    default: {
      // Per stream: [written, needed]; "any stream" predicates OR over the streams.
      if (IsOverflowPredicate(desc_.Query)) {
        BOOL overflow = FALSE;
        for (size_t i = 0; i + 1 < sums.size(); i += 2) overflow |= sums[i + 1] > sums[i];
        *static_cast<BOOL*>(data) = overflow;
      } else {
        QUERY_DATA_SO_STATISTICS stats{sums[0], sums[1]};
        std::memcpy(data, &stats, sizeof stats);
      }
      break;
    }
  }
  return S_OK;
}

// ---------------------------------------------------------------------------
// The context's side

void ContextImpl::Begin(Asynchronous* pAsync) {
  auto* query = static_cast<QueryImpl*>(pAsync);
  EndRendering();
  query->Begin(Commands());
  if (query->active() && std::find(activeQueries_.begin(), activeQueries_.end(), query) == activeQueries_.end()) {
    query->AddRef();
    activeQueries_.push_back(query);
  }
}

void ContextImpl::End(Asynchronous* pAsync) {
  auto* query = static_cast<QueryImpl*>(pAsync);
  EndRendering();
  query->End(Commands(), device_->gpu().RecordingSerial());
  auto it = std::find(activeQueries_.begin(), activeQueries_.end(), query);
  if (it != activeQueries_.end()) {
    activeQueries_.erase(it);
    query->Release();
  }
}

HRESULT ContextImpl::GetData(Asynchronous* pAsync, void* pData, UINT DataSize, UINT GetDataFlags) {
  return static_cast<QueryImpl*>(pAsync)->GetData(pData, DataSize, GetDataFlags, *this);
}

}  // namespace rhi::vk
