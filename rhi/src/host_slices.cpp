#include "host_slices.h"

#include <algorithm>

#include "gpu.h"

namespace rhi::vk {

namespace {
constexpr VkDeviceSize kChunkSize = 4u << 20;

VkDeviceSize AlignUp(VkDeviceSize value, VkDeviceSize alignment) {
  return (value + alignment - 1) / alignment * alignment;
}
}  // namespace

HostSliceAllocator::HostSliceAllocator(Gpu& gpu) : gpu_(gpu) {}

HostSliceAllocator::~HostSliceAllocator() {
  for (auto& chunk : chunks_) {
    vkDestroyBuffer(gpu_.Device(), chunk.buffer, nullptr);
    vkFreeMemory(gpu_.Device(), chunk.memory, nullptr);
  }
}

uint32_t HostSliceAllocator::CreateChunk(VkDeviceSize minSize) {
  Chunk chunk;
  chunk.size = std::max(kChunkSize, AlignUp(minSize, kChunkSize));
  VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
  info.size = chunk.size;
  // Every use a dynamic buffer or an upload can have.
  info.usage = VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_VERTEX_BUFFER_BIT |
               VK_BUFFER_USAGE_INDEX_BUFFER_BIT | VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT |
               VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT |
               VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT;
  vkCreateBuffer(gpu_.Device(), &info, nullptr, &chunk.buffer);
  VkMemoryRequirements requirements;
  vkGetBufferMemoryRequirements(gpu_.Device(), chunk.buffer, &requirements);
  gpu_.AllocateFor(requirements, VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT,
                   &chunk.memory);
  vkBindBufferMemory(gpu_.Device(), chunk.buffer, chunk.memory, 0);
  void* mapped = nullptr;
  vkMapMemory(gpu_.Device(), chunk.memory, 0, VK_WHOLE_SIZE, 0, &mapped);
  chunk.data = static_cast<uint8_t*>(mapped);
  chunks_.push_back(chunk);
  return static_cast<uint32_t>(chunks_.size() - 1);
}

HostSlice HostSliceAllocator::Allocate(VkDeviceSize size, VkDeviceSize alignment) {
  size = std::max<VkDeviceSize>(size, 4);
  std::lock_guard lock(mutex_);
  if (current_ != UINT32_MAX) {
    Chunk& chunk = chunks_[current_];
    if (AlignUp(chunk.used, alignment) + size > chunk.size) {
      uint32_t full = current_;
      current_ = UINT32_MAX;
      if (chunks_[full].liveSlices == 0) Recycle(full);
    }
  }
  if (current_ == UINT32_MAX) {
    auto fits = std::find_if(freeChunks_.begin(), freeChunks_.end(),
                             [&](uint32_t c) { return chunks_[c].size >= size; });
    if (fits != freeChunks_.end()) {
      current_ = *fits;
      freeChunks_.erase(fits);
    } else {
      current_ = CreateChunk(size);
    }
  }
  Chunk& chunk = chunks_[current_];
  VkDeviceSize offset = AlignUp(chunk.used, alignment);
  chunk.used = offset + size;
  ++chunk.liveSlices;
  return HostSlice{chunk.buffer, offset, chunk.data + offset, current_};
}

void HostSliceAllocator::Release(const HostSlice& slice) {
  if (!slice) return;
  uint32_t index = slice.chunk;
  gpu_.DeferDestroy([this, index] {
    std::lock_guard lock(mutex_);
    Chunk& chunk = chunks_[index];
    if (--chunk.liveSlices == 0 && index != current_) Recycle(index);
  });
}

void HostSliceAllocator::Recycle(uint32_t index) {
  chunks_[index].used = 0;
  freeChunks_.push_back(index);
}

}  // namespace rhi::vk
