// The fixture of the compute building blocks' tests: GpuTest (validation layer
// with synchronization validation on; any message fails) and raw buffers.
#pragma once

#include <cstdint>
#include <vector>

#include "gpu_test.h"

namespace rhi_test {

class ComputeTest : public GpuTest {
 protected:
  // A buffer holding `words` with a raw UAV of all of it (RWByteAddressBuffer);
  // `miscFlags` beside ALLOW_RAW_VIEWS.
  struct RawBuffer {
    ComPtr<rhi::Buffer> buffer;
    ComPtr<rhi::UnorderedAccessView> uav;
  };
  RawBuffer MakeRaw(const std::vector<uint32_t>& words, UINT miscFlags = 0);
  std::vector<uint32_t> Read(const RawBuffer& b) { return ReadBufferAs<uint32_t>(b.buffer.Get()); }
};

}  // namespace rhi_test
