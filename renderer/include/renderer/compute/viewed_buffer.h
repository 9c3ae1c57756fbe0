// A buffer with a UAV and an SRV of all of it, raw (R32 words) or structured: what
// the compute building blocks and the methods built on them keep their data in.
#pragma once

#include <cstdint>

#include "rhi/rhi.h"

namespace renderer::compute {

struct ViewedBuffer {
  rhi::ComPtr<rhi::Buffer> buffer;
  rhi::ComPtr<rhi::UnorderedAccessView> uav;
  rhi::ComPtr<rhi::ShaderResourceView> srv;
  uint64_t bytes = 0;

  // `words` 32-bit words, ByteAddressBuffer / RWByteAddressBuffer; `misc`: more
  // RESOURCE_MISC flags (DRAWINDIRECT_ARGS for dispatch arguments).
  bool CreateRaw(rhi::Device* device, uint32_t words, rhi::UINT misc = 0);
  // `count` elements of `stride` bytes; with a hidden counter
  // (IncrementCounter) when `counter`.
  bool CreateStructured(rhi::Device* device, uint32_t count, uint32_t stride, bool counter);
};

}  // namespace renderer::compute
