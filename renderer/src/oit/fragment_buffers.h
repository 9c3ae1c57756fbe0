// What the fragment-buffer methods (prefix_sum.cpp, linked_list.cpp: document
// 004 and per-pixel linked lists) share: their buffers, the refusal of scenes
// their one-object resolve cannot draw, and reading a GPU count back without
// waiting.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <string>

#include "renderer/compute/viewed_buffer.h"
#include "renderer/oit/method.h"

namespace renderer::oit {

using compute::ViewedBuffer;

// The resolve draws one object's full-screen pass: true, or false with the
// reason.
bool AcceptsOnlyOneObject(const MethodInfo& info, const MethodSetup& setup, std::string* error);

// A 32-bit value the GPU writes each frame (a total, a counter), copied into a
// ring of staging buffers and read back when the GPU has got there: polled with
// MAP_FLAG_DO_NOT_WAIT, so a frame or two late, never a stall unless the GPU is
// a whole ring of frames behind.
class LateReadback {
 public:
  using Arrived = std::function<void(uint32_t value, uint64_t tag)>;
  // `arrived` receives each value, oldest first, with the tag it was issued
  // with.
  bool Create(rhi::Device* device, Arrived arrived);
  // Copies the value at the start of `source` for reading later.
  void Issue(rhi::DeviceContext* context, rhi::Buffer* source, uint64_t tag);
  // Hands every copy that has arrived to `arrived`.
  void Poll(rhi::DeviceContext* context);
  // Reads the value at the start of `source` now: the CPU waits for the GPU.
  uint32_t ReadNow(rhi::DeviceContext* context, rhi::Buffer* source);

 private:
  static constexpr size_t kRing = 3;
  bool Read(rhi::DeviceContext* context, rhi::Buffer* staging, bool wait, uint32_t* value);
  std::array<rhi::ComPtr<rhi::Buffer>, kRing> staging_;
  rhi::ComPtr<rhi::Buffer> now_;
  std::array<uint64_t, kRing> tags_{};
  size_t next_ = 0, pending_ = 0;
  Arrived arrived_;
};

}  // namespace renderer::oit
