// Document 004's prefix-sum fragment buffer (renderer/src/oit/prefix_sum.cpp,
// shaders_hlsl/oit/prefix_sum.fxh): what a frame left in the method's per-pixel
// buffers, for checks. Its GPU scan is renderer/compute/prefix_scan.h.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "renderer/oit/method.h"

namespace renderer::oit {

// The per-pixel buffers of a prefix-sum method's last frame (row by row), read
// back (the CPU waits); nullopt when `method` is not a prefix-sum method.
struct PrefixSumFrame {
  std::vector<uint32_t> counts, offsets, cursors;
  uint32_t total = 0;
  uint64_t capacity = 0;  // of the fragment buffer the frame filled
};
std::optional<PrefixSumFrame> ReadPrefixSumFrame(const Method& method, rhi::DeviceContext* context);

}  // namespace renderer::oit
