#include "queries.h"

#include <algorithm>
#include <bit>
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

VkQueryPipelineStatisticFlags SupportedStatistics(const GpuCapabilities& caps) {
  VkQueryPipelineStatisticFlags flags = kAllStatistics;
  if (!caps.tessellationShader)
    flags &= ~(VK_QUERY_PIPELINE_STATISTIC_TESSELLATION_CONTROL_SHADER_PATCHES_BIT |
               VK_QUERY_PIPELINE_STATISTIC_TESSELLATION_EVALUATION_SHADER_INVOCATIONS_BIT);
  return flags;
}

// ---------------------------------------------------------------------------
// Queries

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
  const uint32_t streams = std::max(1u, caps.maxTransformFeedbackStreams);
  switch (desc_.Query) {
    case QUERY_EVENT:
    case QUERY_TIMESTAMP_DISJOINT: break;
    case QUERY_TIMESTAMP: {
      VkQueryPoolCreateInfo info{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
      info.queryType = VK_QUERY_TYPE_TIMESTAMP;
      info.queryCount = 1;
      vkCreateQueryPool(gpu().Device(), &info, nullptr, &timestampPool);
      break;
    }
    case QUERY_OCCLUSION:
    case QUERY_OCCLUSION_PREDICATE: kinds_ = {{VK_QUERY_TYPE_OCCLUSION, 0}}; break;
    case QUERY_PIPELINE_STATISTICS:
      kinds_ = {{VK_QUERY_TYPE_PIPELINE_STATISTICS, 0}};
      statistics_ = SupportedStatistics(caps);
      break;
    case QUERY_SO_OVERFLOW_PREDICATE:
      // "Any stream": one Vulkan query per stream the device captures.
      for (uint32_t stream = 0; stream < streams; ++stream)
        kinds_.push_back({VK_QUERY_TYPE_TRANSFORM_FEEDBACK_STREAM_EXT, stream});
      break;
    default: {
      // SO_STATISTICS reports stream 0, as D3D10's single stream did.
      const uint32_t stream =
          desc_.Query >= QUERY_SO_STATISTICS_STREAM0 ? (desc_.Query - QUERY_SO_STATISTICS_STREAM0) % 4 : 0;
      if (stream >= streams)
        return gpu().Refuse("CreateQuery: stream " + std::to_string(stream) + " is beyond the " +
                            std::to_string(streams) + " stream(s) of " + gpu().AdapterName());
      kinds_ = {{VK_QUERY_TYPE_TRANSFORM_FEEDBACK_STREAM_EXT, stream}};
      break;
    }
  }
  segments.resize(kinds_.size());
  return S_OK;
}

QueryImpl::~QueryImpl() {
  if (active) device().context().ForgetQuery(*this);
  segments.clear();
  VkDevice vkDevice = gpu().Device();
  VkQueryPool pool = timestampPool;
  gpu().DeferDestroy([=] { vkDestroyQueryPool(vkDevice, pool, nullptr); });
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

bool QueryImpl::SumResults(size_t kind, uint32_t valuesPerQuery, std::vector<uint64_t>* sums) {
  sums->assign(valuesPerQuery, 0);
  std::vector<uint64_t> values(valuesPerQuery);
  for (const auto& segment : segments[kind]) {
    VkResult result =
        vkGetQueryPoolResults(gpu().Device(), segment->pool, 0, 1, values.size() * sizeof(uint64_t), values.data(),
                              values.size() * sizeof(uint64_t), VK_QUERY_RESULT_64_BIT);
    if (result != VK_SUCCESS) return false;
    for (size_t i = 0; i < values.size(); ++i) (*sums)[i] += values[i];
  }
  return true;
}

HRESULT QueryImpl::GetData(void* data, UINT size, UINT flags, ContextImpl& context) {
  if (data && size != GetDataSize())
    return gpu().Refuse("GetData: DataSize " + std::to_string(size) + " does not match GetDataSize() " +
                        std::to_string(GetDataSize()));
  if (active || !issued) return gpu().Refuse("GetData: the query has not been ended since its last Begin");
  if (!gpu().IsComplete(endSerial)) {
    if (endSerial == gpu().RecordingSerial() && !(flags & ASYNC_GETDATA_DONOTFLUSH)) context.Flush();
    return S_FALSE;
  }
  if (!data) return S_OK;
  std::vector<uint64_t> sums;
  switch (desc_.Query) {
    case QUERY_EVENT: *static_cast<BOOL*>(data) = TRUE; break;
    case QUERY_TIMESTAMP: {
      uint64_t ticks = 0;
      vkGetQueryPoolResults(gpu().Device(), timestampPool, 0, 1, sizeof ticks, &ticks, sizeof ticks,
                            VK_QUERY_RESULT_64_BIT);
      *static_cast<UINT64*>(data) = ticks;
      break;
    }
    case QUERY_TIMESTAMP_DISJOINT: {
      QUERY_DATA_TIMESTAMP_DISJOINT disjoint{};
      disjoint.Frequency = static_cast<UINT64>(1e9 / gpu().Caps().timestampPeriodNs);
      disjoint.Disjoint = FALSE;
      std::memcpy(data, &disjoint, sizeof disjoint);
      break;
    }
    case QUERY_OCCLUSION:
    case QUERY_OCCLUSION_PREDICATE:
      if (!SumResults(0, 1, &sums)) return S_FALSE;
      if (desc_.Query == QUERY_OCCLUSION)
        *static_cast<UINT64*>(data) = sums[0];
      else
        *static_cast<BOOL*>(data) = sums[0] != 0;
      break;
    case QUERY_PIPELINE_STATISTICS: {
      if (!SumResults(0, static_cast<uint32_t>(std::popcount(statistics_)), &sums)) return S_FALSE;
      QUERY_DATA_PIPELINE_STATISTICS stats{};
      UINT64* fields = &stats.IAVertices;
      size_t next = 0;
      for (uint32_t bit = 0; bit < 11; ++bit)
        if (statistics_ & (1u << bit)) fields[bit] = sums[next++];
      std::memcpy(data, &stats, sizeof stats);
      break;
    }
    default: {
      // Per stream: [primitives written, primitives needed].
      if (IsOverflowPredicate(desc_.Query)) {
        BOOL overflow = FALSE;
        for (size_t kind = 0; kind < kinds_.size(); ++kind) {
          if (!SumResults(kind, 2, &sums)) return S_FALSE;
          overflow |= sums[1] > sums[0];
        }
        *static_cast<BOOL*>(data) = overflow;
      } else {
        if (!SumResults(0, 2, &sums)) return S_FALSE;
        QUERY_DATA_SO_STATISTICS stats{sums[0], sums[1]};
        std::memcpy(data, &stats, sizeof stats);
      }
      break;
    }
  }
  return S_OK;
}

// ---------------------------------------------------------------------------
// Segments

QuerySegment::~QuerySegment() {
  if (tracker) tracker->Recycle(kind, pool);
}

QueryTracker::~QueryTracker() {
  for (auto& [kind, pools] : freePools_)
    for (VkQueryPool pool : pools) vkDestroyQueryPool(gpu_.Device(), pool, nullptr);
}

void QueryTracker::Open(const QueryKind& kind, KindState& state, VkCommandBuffer commands) {
  auto segment = std::make_shared<QuerySegment>();
  segment->kind = kind;
  auto& free = freePools_[kind];
  if (!free.empty()) {
    segment->pool = free.back();
    free.pop_back();
  } else {
    VkQueryPoolCreateInfo info{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
    info.queryType = kind.type;
    info.queryCount = 1;
    info.pipelineStatistics = kind.type == VK_QUERY_TYPE_PIPELINE_STATISTICS ? statistics : 0;
    vkCreateQueryPool(gpu_.Device(), &info, nullptr, &segment->pool);
  }
  segment->tracker = this;
  // Pools are reused; the reset is ordered after any earlier use by the queue.
  vkCmdResetQueryPool(commands, segment->pool, 0, 1);
  if (kind.type == VK_QUERY_TYPE_TRANSFORM_FEEDBACK_STREAM_EXT)
    gpu_.vkCmdBeginQueryIndexedEXT(commands, segment->pool, 0, 0, kind.stream);
  else
    vkCmdBeginQuery(commands, segment->pool, 0,
                    kind.type == VK_QUERY_TYPE_OCCLUSION ? VK_QUERY_CONTROL_PRECISE_BIT : 0);
  state.open = std::move(segment);
}

void QueryTracker::Close(const QueryKind& kind, KindState& state, VkCommandBuffer commands) {
  if (!state.open) return;
  if (kind.type == VK_QUERY_TYPE_TRANSFORM_FEEDBACK_STREAM_EXT)
    gpu_.vkCmdEndQueryIndexedEXT(commands, state.open->pool, 0, kind.stream);
  else
    vkCmdEndQuery(commands, state.open->pool, 0);
  for (QueryImpl* query : state.active) {
    const auto& kinds = query->kinds();
    size_t index = std::find(kinds.begin(), kinds.end(), kind) - kinds.begin();
    query->segments[index].push_back(state.open);
  }
  state.open.reset();
}

void QueryTracker::Begin(QueryImpl& query, VkCommandBuffer commands) {
  // D3D11: Begin on an active query restarts it.
  if (query.active) Leave(query, commands);
  for (auto& list : query.segments) list.clear();
  query.active = true;
  query.issued = false;
  for (const QueryKind& kind : query.kinds()) {
    KindState& state = kinds_[kind];
    Close(kind, state, commands);
    state.active.push_back(&query);
    Open(kind, state, commands);
  }
}

void QueryTracker::Leave(QueryImpl& query, VkCommandBuffer commands) {
  for (const QueryKind& kind : query.kinds()) {
    KindState& state = kinds_[kind];
    Close(kind, state, commands);
    std::erase(state.active, &query);
    if (!state.active.empty()) Open(kind, state, commands);
  }
  query.active = false;
}

void QueryTracker::End(QueryImpl& query, VkCommandBuffer commands) {
  if (query.desc().Query == QUERY_TIMESTAMP) {
    vkCmdResetQueryPool(commands, query.timestampPool, 0, 1);
    vkCmdWriteTimestamp2(commands, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, query.timestampPool, 0);
  }
  if (query.active) Leave(query, commands);
  query.issued = true;
  query.endSerial = gpu_.RecordingSerial();
}

void QueryTracker::Forget(QueryImpl& query, VkCommandBuffer commands) { Leave(query, commands); }

void QueryTracker::Suspend(VkCommandBuffer commands) {
  for (auto& [kind, state] : kinds_) Close(kind, state, commands);
}

void QueryTracker::Resume(VkCommandBuffer commands) {
  for (auto& [kind, state] : kinds_)
    if (!state.active.empty()) Open(kind, state, commands);
}

// ---------------------------------------------------------------------------
// The context's side

void ContextImpl::Begin(Asynchronous* pAsync) {
  auto* query = static_cast<QueryImpl*>(pAsync);
  // Timestamps and events have no Begin.
  if (query->desc().Query == QUERY_TIMESTAMP || query->desc().Query == QUERY_EVENT) return;
  EndRendering();
  queries_->Begin(*query, Commands());
}

void ContextImpl::End(Asynchronous* pAsync) {
  EndRendering();
  queries_->End(*static_cast<QueryImpl*>(pAsync), Commands());
}

void ContextImpl::ForgetQuery(QueryImpl& query) {
  EndRendering();
  queries_->Forget(query, Commands());
}

HRESULT ContextImpl::GetData(Asynchronous* pAsync, void* pData, UINT DataSize, UINT GetDataFlags) {
  return static_cast<QueryImpl*>(pAsync)->GetData(pData, DataSize, GetDataFlags, *this);
}

}  // namespace rhi::vk
