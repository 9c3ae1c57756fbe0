// A GPU radix sort of (key, value) uint pairs (renderer/compute/): the sort of
// issue 19's compute-tile smoke (particles back to front), sized by a count the
// GPU holds. Shaders: shaders_hlsl/compute/radix_sort.fx; the scan of its
// histograms is the shared PrefixScan (prefix_scan.h).
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "fx/effect.h"
#include "renderer/compute/dispatch_args.h"
#include "renderer/compute/prefix_scan.h"
#include "renderer/oit/method.h"  // oit::PassMarks
#include "rhi/rhi.h"

namespace renderer::compute {

// LSD radix sort, kRadixBits bits a pass: per block of pairs its digit counts,
// their scan (digit-major over the largest block count, so the scan's length is
// fixed on the CPU: the blocks past the GPU's count contribute zeros), a stable
// scatter ranked in shared memory; two scratch buffers in turn.
class RadixSort {
 public:
  static constexpr uint32_t kRadixBits = 4;  // key bits a pass
  static constexpr uint32_t kThreads = 128;  // a group's threads
  static constexpr uint32_t kItemsPerThread = 8;
  static constexpr uint32_t kBlock = kThreads * kItemsPerThread;  // pairs a group (block) handles

  // For up to maxCount pairs.
  static std::unique_ptr<RadixSort> Create(rhi::Device* device, uint32_t maxCount, std::string* error);
  ~RadixSort();

  // Sorts keys[i], values[i] for i < count, in place, ascending by the low
  // `keyBits` bits of the key (1..32; fewer bits, fewer passes; 0 leaves the
  // pairs as they are, more than 32 is 32), stable: equal keys keep their order.
  // `keys` and `values` are raw UAVs (RWByteAddressBuffer) of at least maxCount
  // words. count is word `countWord` of the raw UAV `count`, read only by the
  // GPU: the passes' sizes come from it through DispatchIndirect, never from a
  // read-back; a count over maxCount sorts maxCount. The words past the count
  // are left as they are. With `marks`, each pass (PassNames(keyBits)) begins
  // with marks->BeginPass((*pass)++). Leaves the compute stage's UAV slots 0-4
  // unbound (an effect's Apply binds what its pass needs). With a
  // null keys, values or count view it does nothing (and marks no pass).
  void Sort(rhi::DeviceContext* context, rhi::UnorderedAccessView* keys, rhi::UnorderedAccessView* values,
            rhi::UnorderedAccessView* count, uint32_t countWord, uint32_t keyBits = 32, oit::PassMarks* marks = nullptr,
            size_t* pass = nullptr);

  // The passes Sort runs for `keyBits`, in order (for timing): "SortArgs", then
  // per digit "Histogram", the scan's passes, "Scatter", then "CopyBack" after an
  // odd number of digits.
  const std::vector<std::string>& PassNames(uint32_t keyBits = 32) const;
  // Its scratch buffers: keys and values, the block counts and their scan, the scan's own.
  uint64_t MemoryBytes() const;
  uint32_t maxCount() const { return maxCount_; }

 private:
  struct Buffers;
  RadixSort();
  bool Initialize(rhi::Device* device, uint32_t maxCount, std::string* error);
  void Dispatch(rhi::DeviceContext* context, fx::EffectPass* pass, rhi::UnorderedAccessView* keysIn,
                rhi::UnorderedAccessView* valuesIn, rhi::UnorderedAccessView* keysOut,
                rhi::UnorderedAccessView* valuesOut, rhi::UnorderedAccessView* counts);

  uint32_t maxCount_ = 0, maxBlocks_ = 0;
  std::unique_ptr<Buffers> buffers_;
  std::unique_ptr<DispatchArgs> args_;
  std::unique_ptr<PrefixScan> scan_;
  rhi::ComPtr<fx::Effect> effect_;
  fx::EffectPass *histogram_ = nullptr, *scatter_ = nullptr, *copyBack_ = nullptr;
  std::array<std::vector<std::string>, 33> passNames_;  // by key bits
};

}  // namespace renderer::compute
