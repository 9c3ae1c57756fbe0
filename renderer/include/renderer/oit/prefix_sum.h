// Document 004's prefix-sum fragment buffer (renderer/src/oit/prefix_sum.cpp,
// shaders_hlsl/oit/prefix_sum.fxh): its GPU scan, which works on its own, and
// what a frame left in the method's per-pixel buffers, for checks.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "fx/effect.h"
#include "renderer/oit/method.h"

namespace renderer::oit {

// The exclusive prefix sum of `length` 32-bit words on the GPU (step 3): groups
// of 512 scanned in shared memory (Blelloch), their sums scanned recursively
// and added back, so any length from 1 up works; then the total (last offset +
// last element).
class PrefixScan {
 public:
  static std::unique_ptr<PrefixScan> Create(rhi::Device* device, uint32_t length, std::string* error);
  ~PrefixScan();
  // Scans `input` (a raw UAV of `length` words) into `output` (likewise) and
  // writes the sum of all elements into the first word of `total` (a raw UAV).
  // With `marks`, each pass begins with marks->BeginPass((*pass)++).
  void Run(rhi::DeviceContext* context, rhi::UnorderedAccessView* input, rhi::UnorderedAccessView* output,
           rhi::UnorderedAccessView* total, PassMarks* marks = nullptr, size_t* pass = nullptr);
  // The passes Run applies, in order ("ScanBlocks", ..., "Total").
  const std::vector<std::string>& PassNames() const { return passNames_; }
  // Its block sums at every level.
  uint64_t MemoryBytes() const;

 private:
  struct Level;
  PrefixScan() = default;
  bool Initialize(rhi::Device* device, uint32_t length, std::string* error);
  void ScanLevel(rhi::DeviceContext* context, size_t level, rhi::UnorderedAccessView* input,
                 rhi::UnorderedAccessView* output, PassMarks* marks, size_t* pass);
  void Dispatch(rhi::DeviceContext* context, fx::EffectPass* pass, uint32_t length, rhi::UnorderedAccessView* input,
                rhi::UnorderedAccessView* output, rhi::UnorderedAccessView* blockSums, rhi::UnorderedAccessView* total);

  uint32_t length_ = 0;
  std::vector<Level> levels_;
  rhi::ComPtr<fx::Effect> effect_;
  fx::EffectPass *scanBlocks_ = nullptr, *addBlockOffsets_ = nullptr, *total_ = nullptr;
  std::vector<std::string> passNames_;
};

// The per-pixel buffers of a prefix-sum method's last frame (row by row), read
// back (the CPU waits); nullopt when `method` is not a prefix-sum method.
struct PrefixSumFrame {
  std::vector<uint32_t> counts, offsets, cursors;
  uint32_t total = 0;
  uint64_t capacity = 0;  // of the fragment buffer the frame filled
};
std::optional<PrefixSumFrame> ReadPrefixSumFrame(const Method& method, rhi::DeviceContext* context);

}  // namespace renderer::oit
