#include "call_limits.h"

namespace rhi::vk {

bool SlotRangeAllowed(const Gpu& gpu, const std::string& call, UINT start, UINT count, UINT slots) {
  if (start <= slots && count <= slots - start) return true;
  gpu.Report(MESSAGE_CATEGORY_STATE_SETTING, MESSAGE_SEVERITY_ERROR,
             call + ": StartSlot (" + std::to_string(start) + ") + the count (" + std::to_string(count) +
                 ") exceeds the " + std::to_string(slots) + " slots; the call is ignored");
  return false;
}

bool CountAllowed(const Gpu& gpu, const std::string& call, const char* what, UINT count, UINT max) {
  if (count <= max) return true;
  gpu.Report(MESSAGE_CATEGORY_STATE_SETTING, MESSAGE_SEVERITY_ERROR,
             call + ": " + what + " (" + std::to_string(count) + ") exceeds " + std::to_string(max) +
                 "; the call is ignored");
  return false;
}

bool DispatchAllowed(const Gpu& gpu, UINT x, UINT y, UINT z) {
  constexpr UINT kMax = CS_DISPATCH_MAX_THREAD_GROUPS_PER_DIMENSION;
  if (x <= kMax && y <= kMax && z <= kMax) return true;
  gpu.Report(MESSAGE_CATEGORY_EXECUTION, MESSAGE_SEVERITY_ERROR,
             "Dispatch: a thread-group count (" + std::to_string(x) + ", " + std::to_string(y) + ", " +
                 std::to_string(z) + ") exceeds D3D11_CS_DISPATCH_MAX_THREAD_GROUPS_PER_DIMENSION (" +
                 std::to_string(kMax) + "); the dispatch is skipped");
  return false;
}

}  // namespace rhi::vk
