// The renderer's GPU compute building blocks (renderer/compute/): an exclusive
// prefix sum of 32-bit words, shared by document 004's fragment buffer
// (renderer/src/oit/prefix_sum.cpp) and the radix sort (radix_sort.h).
// Shaders: shaders_hlsl/compute/prefix_scan.fx.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "fx/effect.h"
#include "renderer/oit/method.h"  // oit::PassMarks
#include "rhi/rhi.h"

namespace renderer::compute {

// The exclusive prefix sum of `length` 32-bit words on the GPU: groups of 512
// scanned in shared memory (Blelloch), their sums scanned recursively and added
// back, so any length from 1 up works; then the total (last offset + last
// element).
class PrefixScan {
 public:
  static std::unique_ptr<PrefixScan> Create(rhi::Device* device, uint32_t length, std::string* error);
  ~PrefixScan();
  // Scans `input` (a raw UAV of `length` words) into `output` (likewise) and
  // writes the sum of all elements into the first word of `total` (a raw UAV;
  // null: no Total pass). With `marks`, each pass begins with
  // marks->BeginPass((*pass)++).
  void Run(rhi::DeviceContext* context, rhi::UnorderedAccessView* input, rhi::UnorderedAccessView* output,
           rhi::UnorderedAccessView* total, oit::PassMarks* marks = nullptr, size_t* pass = nullptr);
  // The passes Run applies, in order ("ScanBlocks", ..., "Total"); without the
  // total, the same less "Total".
  const std::vector<std::string>& PassNames(bool total = true) const {
    return total ? passNames_ : passNamesWithoutTotal_;
  }
  // Its block sums at every level.
  uint64_t MemoryBytes() const;

 private:
  struct Level;
  PrefixScan();
  bool Initialize(rhi::Device* device, uint32_t length, std::string* error);
  void ScanLevel(rhi::DeviceContext* context, size_t level, rhi::UnorderedAccessView* input,
                 rhi::UnorderedAccessView* output, oit::PassMarks* marks, size_t* pass);
  void Dispatch(rhi::DeviceContext* context, fx::EffectPass* pass, uint32_t length, rhi::UnorderedAccessView* input,
                rhi::UnorderedAccessView* output, rhi::UnorderedAccessView* blockSums, rhi::UnorderedAccessView* total);

  uint32_t length_ = 0;
  std::vector<Level> levels_;
  rhi::ComPtr<fx::Effect> effect_;
  fx::EffectPass *scanBlocks_ = nullptr, *addBlockOffsets_ = nullptr, *total_ = nullptr;
  std::vector<std::string> passNames_, passNamesWithoutTotal_;
};

}  // namespace renderer::compute
