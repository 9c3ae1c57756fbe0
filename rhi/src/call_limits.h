// D3D11's bounds on the counts that context calls take. D3D11 drops a call
// that exceeds one and its debug layer says why; these do the same through the
// device's message callback (STATE_SETTING or EXECUTION errors) and return
// false when the caller must drop the call.
#pragma once

#include <string>

#include "gpu.h"

namespace rhi::vk {

// StartSlot + count within `slots` slots (IASetVertexBuffers, *SetConstantBuffers, ...).
bool SlotRangeAllowed(const Gpu& gpu, const std::string& call, UINT start, UINT count, UINT slots);
// A count of at most `max` (RSSetViewports, RSSetScissorRects, SOSetTargets).
bool CountAllowed(const Gpu& gpu, const std::string& call, const char* what, UINT count, UINT max);
// Each thread-group count at most CS_DISPATCH_MAX_THREAD_GROUPS_PER_DIMENSION.
bool DispatchAllowed(const Gpu& gpu, UINT x, UINT y, UINT z);

}  // namespace rhi::vk
