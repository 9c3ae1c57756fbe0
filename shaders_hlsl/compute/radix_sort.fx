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
#if SORT_ITEMS % 4 != 0
#error "a thread's pairs are loaded as uint4s (LOAD_THREAD_PAIRS)"
#endif
#if SORT_THREADS * SORT_ITEMS >= 65536 || SORT_THREADS % ((1 << RADIX_BITS) / 2) != 0 || SORT_THREADS < (1 << RADIX_BITS)
#error "the scatter's ranks need blocks under 2^16 pairs and threads a multiple of half the digits, at least the digits"
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

// words[kItems] = this thread's kItems consecutive words of `buffer` in block
// `block`: 16-byte loads where all four are below `pairs` (the group reads its
// block in one contiguous sweep), else those that are, one by one (robust buffer
// access is off: nothing is read past the count). A macro: glslang takes no
// buffer as a parameter.
#define LOAD_THREAD_PAIRS(words, buffer, block, thread, pairs)               \
  [unroll] for (uint q = 0; q < kItems; q += 4) {                            \
    uint first = thread * kItems + q, at = (block * kBlock + first) * 4;     \
    if (first + 4 <= pairs) {                                                \
      uint4 v = buffer.Load4(at);                                            \
      words[q] = v.x, words[q + 1] = v.y, words[q + 2] = v.z, words[q + 3] = v.w; \
    } else {                                                                 \
      [unroll] for (uint m = 0; m < 4; ++m) {                                \
        words[q + m] = 0;                                                    \
        if (first + m < pairs) words[q + m] = buffer.Load(at + m * 4);       \
      }                                                                      \
    }                                                                        \
  }

// ---------------------------------------------------------------------------
groupshared uint BlockDigitCounts[kRadix];

[numthreads(kThreads, 1, 1)]
void CSHistogram(uint3 group : SV_GroupID, uint thread : SV_GroupIndex) {
  uint block = IndirectGroupIndex(group), pairs = BlockPairs(block);
  if (pairs == 0) return;  // whole groups only
  if (thread < kRadix) BlockDigitCounts[thread] = 0;
  GroupMemoryBarrierWithGroupSync();
  uint keys[kItems];
  LOAD_THREAD_PAIRS(keys, SortKeysIn, block, thread, pairs)
  [unroll] for (uint k = 0; k < kItems; ++k)
    if (thread * kItems + k < pairs) InterlockedAdd(BlockDigitCounts[Digit(keys[k])], 1u);
  GroupMemoryBarrierWithGroupSync();
  if (thread < kRadix) SortCounts.Store((thread * SortMaxBlocks + block) * 4, BlockDigitCounts[thread]);
}

// ---------------------------------------------------------------------------
// The scatter's ranks. Each thread counts its pairs of each digit; counter
// (digit, thread) then becomes the number of the block's pairs ranked before
// that thread's first pair of that digit: those of smaller digits, then those of
// the digit in the threads before. Two counters share a word, digit d and
// d + kRadix / 2 in the low and high 16 bits of word d (a block's counts fit 16
// bits), so one scan over the words in (word, thread) order gives the low
// digits their ranks and the high digits theirs less the block's count of low
// digits, which is added after. The words lie word-major, thread-minor, with one
// padding word every kCounterWords words, so that a thread's chunk of the scan
// (kCounterWords consecutive words) is in other banks than its neighbours'.
static const uint kCounterWords = kRadix / 2;  // a thread's
static const uint kWords = kCounterWords * kThreads;
static const uint kChunkRows = kThreads / kCounterWords;  // the chunk sums' scan: rows of kCounterWords
groupshared uint CounterWords[kWords + kWords / kCounterWords];
groupshared uint ChunkSums[kThreads];
groupshared uint RowSums[kChunkRows];
groupshared uint LowDigitPairs;       // the block's pairs of the low digits (< kRadix / 2)
groupshared uint DigitBase[kRadix];   // output position of the block's pairs of a digit, less their first rank
groupshared uint BlockKeys[kBlock];   // the block's pairs in rank order
groupshared uint BlockValues[kBlock];
// With 128 threads of 8 pairs: 1,152 + 128 + 16 + 1 + 16 + 2 x 1,024 words, 13.4 KB of D3D11's 32 KB.

uint CounterWord(uint word, uint thread) {
  uint i = word * kThreads + thread;
  return i + i / kCounterWords;
}

// Every counter word replaced by the sum of those before it: each thread sums a
// chunk of consecutive words, the chunk sums are scanned in rows and the rows'
// sums by one thread (3 barriers for any size), and the chunks are rewritten as
// running sums. Sets LowDigitPairs.
void ScanCounterWords(uint thread) {
  uint chunk = thread * (kCounterWords + 1), sum = 0;  // words thread * kCounterWords.., after their padding
  [unroll] for (uint i = 0; i < kCounterWords; ++i) sum += CounterWords[chunk + i];
  ChunkSums[thread] = sum;
  GroupMemoryBarrierWithGroupSync();
  if (thread < kChunkRows) {
    uint running = 0;
    [unroll] for (uint j = 0; j < kCounterWords; ++j) {
      uint c = ChunkSums[thread * kCounterWords + j];
      ChunkSums[thread * kCounterWords + j] = running;
      running += c;
    }
    RowSums[thread] = running;
  }
  GroupMemoryBarrierWithGroupSync();
  if (thread == 0) {
    uint running = 0;
    for (uint r = 0; r < kChunkRows; ++r) {
      uint c = RowSums[r];
      RowSums[r] = running;
      running += c;
    }
    LowDigitPairs = running & 0xffff;
  }
  GroupMemoryBarrierWithGroupSync();
  uint running = ChunkSums[thread] + RowSums[thread / kCounterWords];
  [unroll] for (uint k = 0; k < kCounterWords; ++k) {
    uint c = CounterWords[chunk + k];
    CounterWords[chunk + k] = running;
    running += c;
  }
}

// The block's pairs ranked before `thread`'s first pair of `digit` (after the scan).
uint Rank(uint digit, uint thread) {
  uint word = CounterWords[CounterWord(digit % kCounterWords, thread)];
  return digit < kCounterWords ? word & 0xffff : (word >> 16) + LowDigitPairs;
}

[numthreads(kThreads, 1, 1)]
void CSScatter(uint3 group : SV_GroupID, uint thread : SV_GroupIndex) {
  uint block = IndirectGroupIndex(group), pairs = BlockPairs(block);
  if (pairs == 0) return;
  // This thread's kItems consecutive pairs and their digits.
  uint keys[kItems], values[kItems];
  LOAD_THREAD_PAIRS(keys, SortKeysIn, block, thread, pairs)
  LOAD_THREAD_PAIRS(values, SortValuesIn, block, thread, pairs)
  uint digits[kItems];
  [unroll] for (uint m = 0; m < kItems; ++m) digits[m] = thread * kItems + m < pairs ? Digit(keys[m]) : kNoDigit;
  [unroll] for (uint w = 0; w < kCounterWords; ++w) {
    uint n = 0;
    [unroll] for (uint m2 = 0; m2 < kItems; ++m2)
      n += digits[m2] == w ? 1 : digits[m2] == w + kCounterWords ? 0x10000 : 0;
    CounterWords[CounterWord(w, thread)] = n;
  }
  GroupMemoryBarrierWithGroupSync();
  ScanCounterWords(thread);
  GroupMemoryBarrierWithGroupSync();

  if (thread < kRadix)
    DigitBase[thread] = SortCounts.Load((thread * SortMaxBlocks + block) * 4) - Rank(thread, 0);
  // Each pair at its rank in the block: its digit's rank in this thread plus
  // its pairs of that digit before it.
  [unroll] for (uint n = 0; n < kItems; ++n) {
    if (digits[n] == kNoDigit) continue;
    uint rank = Rank(digits[n], thread);
    [unroll] for (uint e = 0; e < n; ++e) rank += digits[e] == digits[n] ? 1 : 0;
    BlockKeys[rank] = keys[n];
    BlockValues[rank] = values[n];
  }
  GroupMemoryBarrierWithGroupSync();

  // Ranked, a digit's pairs are consecutive: out in order, coalesced.
  [unroll] for (uint o = 0; o < kItems; ++o) {
    uint r = o * kThreads + thread;
    if (r < pairs) {
      uint key = BlockKeys[r], to = (DigitBase[Digit(key)] + r) * 4;
      SortKeysOut.Store(to, key);
      SortValuesOut.Store(to, BlockValues[r]);
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
