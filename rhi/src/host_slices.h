// Host-visible memory handed out in slices: the storage of DYNAMIC buffers
// (a Map with WRITE_DISCARD renames the buffer to a fresh slice, so the GPU
// keeps reading the old contents) and of upload staging.
#pragma once

#include <vulkan/vulkan.h>

#include <cstdint>
#include <memory>
#include <mutex>
#include <vector>

namespace rhi::vk {

class Gpu;

struct HostSlice {
  VkBuffer buffer = VK_NULL_HANDLE;
  VkDeviceSize offset = 0;
  uint8_t* data = nullptr;
  uint32_t chunk = UINT32_MAX;
  explicit operator bool() const { return data != nullptr; }
};

class HostSliceAllocator {
 public:
  explicit HostSliceAllocator(Gpu& gpu);
  ~HostSliceAllocator();

  HostSlice Allocate(VkDeviceSize size, VkDeviceSize alignment);
  // Returns the slice once the GPU is done with everything recorded so far.
  void Release(const HostSlice& slice);

 private:
  struct Chunk {
    VkBuffer buffer = VK_NULL_HANDLE;
    VkDeviceMemory memory = VK_NULL_HANDLE;
    uint8_t* data = nullptr;
    VkDeviceSize size = 0;
    VkDeviceSize used = 0;
    uint32_t liveSlices = 0;
  };
  uint32_t CreateChunk(VkDeviceSize minSize);
  void Recycle(uint32_t chunk);

  Gpu& gpu_;
  std::mutex mutex_;  // dynamic buffers are created and released on any thread
  std::vector<Chunk> chunks_;
  std::vector<uint32_t> freeChunks_;
  uint32_t current_ = UINT32_MAX;
};

}  // namespace rhi::vk
