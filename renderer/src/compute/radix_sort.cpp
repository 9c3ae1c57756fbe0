// The GPU radix sort (renderer/compute/radix_sort.h; shaders_hlsl/compute/radix_sort.fx).
#include "renderer/compute/radix_sort.h"

#include <algorithm>

#include "compute/effect_values.h"
#include "renderer/compute/viewed_buffer.h"
#include "renderer/effect_files.h"

namespace renderer::compute {

using rhi::UnorderedAccessView;

namespace {

constexpr uint32_t kRadix = 1u << RadixSort::kRadixBits;
constexpr uint32_t kArgsSlot = 0;  // the blocks of the count
constexpr uint32_t kMaxWords = UINT32_MAX / 4;

uint32_t DigitPasses(uint32_t keyBits) {
  return (std::min(keyBits, 32u) + RadixSort::kRadixBits - 1) / RadixSort::kRadixBits;
}

}  // namespace

struct RadixSort::Buffers {
  ViewedBuffer keys, values;  // the other side of each pass
  ViewedBuffer counts;        // kRadix x maxBlocks digit counts, digit-major
  ViewedBuffer offsets;       // their exclusive scan
};

RadixSort::RadixSort() = default;
RadixSort::~RadixSort() = default;

std::unique_ptr<RadixSort> RadixSort::Create(rhi::Device* device, uint32_t maxCount, std::string* error) {
  std::unique_ptr<RadixSort> sort(new RadixSort());
  if (!sort->Initialize(device, maxCount, error)) return nullptr;
  return sort;
}

bool RadixSort::Initialize(rhi::Device* device, uint32_t maxCount, std::string* error) {
  if (maxCount > kMaxWords) {
    *error = "radix sort: " + std::to_string(maxCount) + " pairs do not fit a buffer of 32-bit words (at most " +
             std::to_string(kMaxWords) + ": BUFFER_DESC::ByteWidth is a UINT)";
    return false;
  }
  maxCount_ = maxCount;
  maxBlocks_ = std::max(maxCount / kBlock + (maxCount % kBlock != 0), 1u);
  const uint32_t scanLength = kRadix * maxBlocks_;
  buffers_ = std::make_unique<Buffers>();
  Buffers& b = *buffers_;
  if (!b.keys.CreateRaw(device, std::max(maxCount, 1u)) || !b.values.CreateRaw(device, std::max(maxCount, 1u)) ||
      !b.counts.CreateRaw(device, scanLength) || !b.offsets.CreateRaw(device, scanLength)) {
    *error = "radix sort: creating the scratch buffers for " + std::to_string(maxCount) + " pairs failed";
    return false;
  }
  if (!(args_ = DispatchArgs::Create(device, 1, error)) || !(scan_ = PrefixScan::Create(device, scanLength, error)))
    return false;
  for (uint32_t bits = 0; bits <= 32; ++bits) {
    std::vector<std::string>& names = passNames_[bits];
    names = {"SortArgs"};
    const uint32_t digits = DigitPasses(bits);
    for (uint32_t d = 0; d < digits; ++d) {
      names.push_back("Histogram");
      names.insert(names.end(), scan_->PassNames(false).begin(), scan_->PassNames(false).end());
      names.push_back("Scatter");
    }
    if (digits % 2) names.push_back("CopyBack");
  }
  effect_ = LoadEffect(device, "compute/radix_sort.fx",
                       {{"RADIX_BITS", std::to_string(kRadixBits)},
                        {"SORT_THREADS", std::to_string(kThreads)},
                        {"SORT_ITEMS", std::to_string(kItemsPerThread)}},
                       error);
  return effect_ && (histogram_ = FindPass(effect_.Get(), nullptr, "Histogram", error)) &&
         (scatter_ = FindPass(effect_.Get(), nullptr, "Scatter", error)) &&
         (copyBack_ = FindPass(effect_.Get(), nullptr, "CopyBack", error));
}

const std::vector<std::string>& RadixSort::PassNames(uint32_t keyBits) const {
  return passNames_[std::min(keyBits, 32u)];
}

void RadixSort::Sort(rhi::DeviceContext* ctx, UnorderedAccessView* keys, UnorderedAccessView* values,
                     UnorderedAccessView* count, uint32_t countWord, uint32_t keyBits, oit::PassMarks* marks,
                     size_t* pass) {
  if (!keys || !values || !count) return;  // nothing to sort, no count to size the passes by
  keyBits = std::min(keyBits, 32u);
  auto begin = [&] {
    if (marks) marks->BeginPass((*pass)++);
  };
  Buffers& b = *buffers_;
  begin();
  args_->Write(ctx, count, countWord, kBlock, kArgsSlot, maxCount_);
  const rhi::UINT zero[4] = {};
  ctx->ClearUnorderedAccessViewUint(b.counts.uav.Get(), zero);  // the blocks past the count stay zero

  const uint32_t digits = DigitPasses(keyBits);
  UnorderedAccessView *keysIn = keys, *valuesIn = values;
  UnorderedAccessView *keysOut = b.keys.uav.Get(), *valuesOut = b.values.uav.Get();
  for (uint32_t d = 0; d < digits; ++d) {
    const uint32_t shift = d * kRadixBits, bits = std::min(kRadixBits, keyBits - shift);
    SetUint(effect_.Get(), "SortShift", shift);
    SetUint(effect_.Get(), "SortDigitMask", (1u << bits) - 1);
    begin();
    Dispatch(ctx, histogram_, keysIn, valuesIn, nullptr, nullptr, b.counts.uav.Get());
    scan_->Run(ctx, b.counts.uav.Get(), b.offsets.uav.Get(), nullptr, marks, pass);  // its total is the count
    begin();
    Dispatch(ctx, scatter_, keysIn, valuesIn, keysOut, valuesOut, b.offsets.uav.Get());
    std::swap(keysIn, keysOut);
    std::swap(valuesIn, valuesOut);
  }
  if (digits % 2) {  // the result is in the scratch buffers (keysIn): back to the caller's
    begin();
    Dispatch(ctx, copyBack_, keysIn, valuesIn, keysOut, valuesOut, nullptr);
  }
}

void RadixSort::Dispatch(rhi::DeviceContext* ctx, fx::EffectPass* pass, UnorderedAccessView* keysIn,
                         UnorderedAccessView* valuesIn, UnorderedAccessView* keysOut, UnorderedAccessView* valuesOut,
                         UnorderedAccessView* counts) {
  fx::Effect* e = effect_.Get();
  SetUint(e, "SortMaxBlocks", maxBlocks_);
  SetUav(e, "SortKeysIn", keysIn);
  SetUav(e, "SortValuesIn", valuesIn);
  SetUav(e, "SortKeysOut", keysOut);
  SetUav(e, "SortValuesOut", valuesOut);
  SetUav(e, "SortCounts", counts);
  args_->Bind(e, kArgsSlot);
  pass->Apply(0, ctx);
  args_->Dispatch(ctx, kArgsSlot);
  UnorderedAccessView* noUavs[5] = {};
  ctx->CSSetUnorderedAccessViews(0, 5, noUavs, nullptr);  // the next pass may read them otherwise
}

uint64_t RadixSort::MemoryBytes() const {
  const Buffers& b = *buffers_;
  return b.keys.bytes + b.values.bytes + b.counts.bytes + b.offsets.bytes + scan_->MemoryBytes() + args_->MemoryBytes();
}

}  // namespace renderer::compute
