// LSD radix sort of (key, value) uint pairs (renderer/compute/radix_sort.h,
// renderer/src/compute/radix_sort.cpp), RADIX_BITS bits of the key a pass. Each
// pass over the count the GPU holds (IndirectCount, compute/indirect.hlsli), in
// blocks of SORT_THREADS * SORT_ITEMS pairs, one group a block:
//   Histogram  each block's digit counts, digit-major: SortCounts[digit * SortMaxBlocks + block].
//   (the shared prefix scan, compute/prefix_scan.fx, turns them into each
//    (digit, block)'s first position in the pass's output: all smaller digits,
//    then this digit in the blocks before)
//   Scatter    each block ranks its pairs by digit, stably, in shared memory and
//              writes them from SortKeysIn/SortValuesIn to their positions in
//              SortKeysOut/SortValuesOut. Ranks: each thread counts the digits of
//              its SORT_ITEMS consecutive pairs, the counts (digit-major, then
//              thread) are scanned, so a pair's rank is its digit's count in the
//              threads before plus its own earlier ones: index order within a digit.
//   CopyBack   SortKeysIn/SortValuesIn to SortKeysOut/SortValuesOut, after an odd
//              number of passes (the result must end in the caller's buffers).
// RADIX_BITS, SORT_THREADS and SORT_ITEMS are defined by radix_sort.cpp, which
// sizes the buffers with them.
#if !defined(RADIX_BITS) || !defined(SORT_THREADS) || !defined(SORT_ITEMS)
#error "RADIX_BITS, SORT_THREADS and SORT_ITEMS must be defined by the loader (radix_sort.cpp)"
#endif
#include "compute/indirect.hlsli"

cbuffer SortParams {
  uint SortShift;      // the pass's digit: (key >> SortShift) & SortDigitMask
  uint SortDigitMask;
  uint SortMaxBlocks;  // blocks of the largest count: the stride of a digit's row in SortCounts
};
RWByteAddressBuffer SortKeysIn : register(u0);
RWByteAddressBuffer SortValuesIn : register(u1);
RWByteAddressBuffer SortKeysOut : register(u2);
RWByteAddressBuffer SortValuesOut : register(u3);
RWByteAddressBuffer SortCounts : register(u4);  // Histogram: the counts; Scatter: their scan

static const uint kThreads = SORT_THREADS;
static const uint kItems = SORT_ITEMS;  // pairs a thread
static const uint kBlock = kThreads * kItems;
static const uint kRadix = 1u << RADIX_BITS;
static const uint kNoDigit = kRadix;  // a slot past the count

uint Digit(uint key) { return (key >> SortShift) & SortDigitMask; }

// The block of this group and how many of its pairs are below the count (0 for
// the padding groups of a split dispatch).
uint BlockPairs(uint block) {
  uint count = IndirectCount(), first = block * kBlock;
  return first < count ? min(count - first, kBlock) : 0;
}

// ---------------------------------------------------------------------------
groupshared uint BlockDigitCounts[kRadix];

[numthreads(kThreads, 1, 1)]
void CSHistogram(uint3 group : SV_GroupID, uint thread : SV_GroupIndex) {
  uint block = IndirectGroupIndex(group), pairs = BlockPairs(block);
  if (pairs == 0) return;  // whole groups only
  if (thread < kRadix) BlockDigitCounts[thread] = 0;
  GroupMemoryBarrierWithGroupSync();
  uint first = block * kBlock;
  [unroll] for (uint k = 0; k < kItems; ++k) {
    uint i = k * kThreads + thread;
    if (i < pairs) InterlockedAdd(BlockDigitCounts[Digit(SortKeysIn.Load((first + i) * 4))], 1u);
  }
  GroupMemoryBarrierWithGroupSync();
  if (thread < kRadix) SortCounts.Store((thread * SortMaxBlocks + block) * 4, BlockDigitCounts[thread]);
}

// ---------------------------------------------------------------------------
groupshared uint BlockKeys[kBlock];
groupshared uint BlockValues[kBlock];
groupshared uint ThreadDigitCounts[kRadix * kThreads];  // [digit][thread]; then their exclusive scan
groupshared uint ChunkSums[kThreads];
groupshared uint DigitBase[kRadix];  // output position of the block's pairs of a digit, less their first rank

// The exclusive scan of ThreadDigitCounts in place: each thread sums a chunk of
// kRadix consecutive counts, the chunk sums are scanned (Hillis-Steele), and the
// chunks are rewritten as running sums from their chunk's offset.
void ScanThreadDigitCounts(uint thread) {
  uint chunk = thread * kRadix, sum = 0;
  [unroll] for (uint i = 0; i < kRadix; ++i) sum += ThreadDigitCounts[chunk + i];
  ChunkSums[thread] = sum;
  GroupMemoryBarrierWithGroupSync();
  for (uint offset = 1; offset < kThreads; offset <<= 1) {
    uint inclusive = ChunkSums[thread] + (thread >= offset ? ChunkSums[thread - offset] : 0);
    GroupMemoryBarrierWithGroupSync();
    ChunkSums[thread] = inclusive;
    GroupMemoryBarrierWithGroupSync();
  }
  uint running = ChunkSums[thread] - sum;
  [unroll] for (uint j = 0; j < kRadix; ++j) {
    uint c = ThreadDigitCounts[chunk + j];
    ThreadDigitCounts[chunk + j] = running;
    running += c;
  }
}

[numthreads(kThreads, 1, 1)]
void CSScatter(uint3 group : SV_GroupID, uint thread : SV_GroupIndex) {
  uint block = IndirectGroupIndex(group), pairs = BlockPairs(block);
  if (pairs == 0) return;
  uint first = block * kBlock;
  [unroll] for (uint k = 0; k < kItems; ++k) {
    uint i = k * kThreads + thread;  // coalesced
    if (i < pairs) {
      BlockKeys[i] = SortKeysIn.Load((first + i) * 4);
      BlockValues[i] = SortValuesIn.Load((first + i) * 4);
    }
  }
  [unroll] for (uint d = 0; d < kRadix; ++d) ThreadDigitCounts[d * kThreads + thread] = 0;
  GroupMemoryBarrierWithGroupSync();

  // This thread's consecutive pairs and their digits.
  uint keys[kItems], values[kItems], digits[kItems];
  [unroll] for (uint m = 0; m < kItems; ++m) {
    uint i = thread * kItems + m;
    keys[m] = BlockKeys[i];
    values[m] = BlockValues[i];
    digits[m] = i < pairs ? Digit(keys[m]) : kNoDigit;
    if (digits[m] != kNoDigit) ThreadDigitCounts[digits[m] * kThreads + thread] += 1;
  }
  GroupMemoryBarrierWithGroupSync();
  ScanThreadDigitCounts(thread);
  GroupMemoryBarrierWithGroupSync();

  if (thread < kRadix)
    DigitBase[thread] = SortCounts.Load((thread * SortMaxBlocks + block) * 4) - ThreadDigitCounts[thread * kThreads];
  // Each pair at its rank in the block (BlockKeys were all read above).
  [unroll] for (uint n = 0; n < kItems; ++n) {
    if (digits[n] == kNoDigit) continue;
    uint rank = ThreadDigitCounts[digits[n] * kThreads + thread];
    [unroll] for (uint e = 0; e < n; ++e) rank += digits[e] == digits[n] ? 1 : 0;
    BlockKeys[rank] = keys[n];
    BlockValues[rank] = values[n];
  }
  GroupMemoryBarrierWithGroupSync();

  // Ranked, a digit's pairs are consecutive: out in order, coalesced.
  [unroll] for (uint o = 0; o < kItems; ++o) {
    uint r = o * kThreads + thread;
    if (r < pairs) {
      uint key = BlockKeys[r], at = (DigitBase[Digit(key)] + r) * 4;
      SortKeysOut.Store(at, key);
      SortValuesOut.Store(at, BlockValues[r]);
    }
  }
}

// ---------------------------------------------------------------------------
[numthreads(kThreads, 1, 1)]
void CSCopyBack(uint3 group : SV_GroupID, uint thread : SV_GroupIndex) {
  uint block = IndirectGroupIndex(group), pairs = BlockPairs(block), first = block * kBlock;
  [unroll] for (uint k = 0; k < kItems; ++k) {
    uint i = k * kThreads + thread;
    if (i < pairs) {
      SortKeysOut.Store((first + i) * 4, SortKeysIn.Load((first + i) * 4));
      SortValuesOut.Store((first + i) * 4, SortValuesIn.Load((first + i) * 4));
    }
  }
}

#define SORT_PASS(name, cs) \
  pass name { SetComputeShader(CompileShader(cs_5_0, cs())); }

technique11 RadixSort {
  SORT_PASS(Histogram, CSHistogram)
  SORT_PASS(Scatter, CSScatter)
  SORT_PASS(CopyBack, CSCopyBack)
}
