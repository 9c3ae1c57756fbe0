// The exclusive prefix sum of ScanLength 32-bit words (renderer/compute/prefix_scan.h,
// renderer/src/compute/prefix_scan.cpp), one level at a time. Passes:
//   ScanBlocks       each group's SCAN_THREADS * 2 elements scanned in shared memory
//                    (Blelloch), the group's sum into ScanBlockSums.
//   AddBlockOffsets  each group's elements plus the scanned sum of the groups before it
//                    (ScanBlockSums, now scanned: the next level's output).
//   Total            the last offset plus the last element: the sum of all.
// SCAN_THREADS (threads a group) is defined by the C++ side, which sizes the levels with it.
#ifndef SCAN_THREADS
#error "SCAN_THREADS (threads per scan group) must be defined by the loader (prefix_scan.cpp)"
#endif

cbuffer ScanParams {
  uint ScanLength;   // elements of ScanInput / ScanOutput
  uint ScanGroupsX;  // groups in x of the dispatch (65535 at most a dimension): group = y * ScanGroupsX + x
};
RWByteAddressBuffer ScanInput : register(u0);
RWByteAddressBuffer ScanOutput : register(u1);
RWByteAddressBuffer ScanBlockSums : register(u2);  // ScanBlocks: each group's sum; AddBlockOffsets: their scan
RWByteAddressBuffer ScanTotal : register(u3);

static const uint kScanThreads = SCAN_THREADS;
static const uint kScanBlock = 2 * kScanThreads;  // elements a group scans
groupshared uint ScanShared[kScanBlock];

uint ScanBlockIndex(uint3 group) { return group.y * ScanGroupsX + group.x; }

// Blelloch's work-efficient exclusive scan of one block in shared memory: an
// up-sweep of partial sums, the block's sum out, then a down-sweep.
[numthreads(kScanThreads, 1, 1)]
void CSScanBlocks(uint3 group : SV_GroupID, uint thread : SV_GroupIndex) {
  uint block = ScanBlockIndex(group);
  uint first = block * kScanBlock;
  if (first >= ScanLength) return;  // the dispatch's padding groups, whole
  uint i0 = first + 2 * thread, i1 = i0 + 1;
  ScanShared[2 * thread] = i0 < ScanLength ? ScanInput.Load(i0 * 4) : 0;
  ScanShared[2 * thread + 1] = i1 < ScanLength ? ScanInput.Load(i1 * 4) : 0;
  uint stride = 1;
  for (uint active = kScanThreads; active > 0; active >>= 1) {
    GroupMemoryBarrierWithGroupSync();
    if (thread < active) {
      uint left = stride * (2 * thread + 1) - 1, right = stride * (2 * thread + 2) - 1;
      ScanShared[right] += ScanShared[left];
    }
    stride <<= 1;
  }
  GroupMemoryBarrierWithGroupSync();
  if (thread == 0) {
    ScanBlockSums.Store(block * 4, ScanShared[kScanBlock - 1]);
    ScanShared[kScanBlock - 1] = 0;
  }
  for (uint active2 = 1; active2 < kScanBlock; active2 <<= 1) {
    stride >>= 1;
    GroupMemoryBarrierWithGroupSync();
    if (thread < active2) {
      uint left = stride * (2 * thread + 1) - 1, right = stride * (2 * thread + 2) - 1;
      uint sum = ScanShared[left];
      ScanShared[left] = ScanShared[right];
      ScanShared[right] += sum;
    }
  }
  GroupMemoryBarrierWithGroupSync();
  if (i0 < ScanLength) ScanOutput.Store(i0 * 4, ScanShared[2 * thread]);
  if (i1 < ScanLength) ScanOutput.Store(i1 * 4, ScanShared[2 * thread + 1]);
}

// Each block's elements plus the scanned sum of the blocks before it.
[numthreads(kScanThreads, 1, 1)]
void CSAddBlockOffsets(uint3 group : SV_GroupID, uint thread : SV_GroupIndex) {
  uint block = ScanBlockIndex(group);
  uint first = block * kScanBlock;
  if (first >= ScanLength) return;
  uint offset = ScanBlockSums.Load(block * 4);
  uint i0 = first + 2 * thread, i1 = i0 + 1;
  if (i0 < ScanLength) ScanOutput.Store(i0 * 4, ScanOutput.Load(i0 * 4) + offset);
  if (i1 < ScanLength) ScanOutput.Store(i1 * 4, ScanOutput.Load(i1 * 4) + offset);
}

// The sum of all elements: the last offset plus the last element.
[numthreads(1, 1, 1)]
void CSTotal() {
  uint last = (ScanLength - 1) * 4;
  ScanTotal.Store(0, ScanOutput.Load(last) + ScanInput.Load(last));
}

#define SCAN_PASS(name, cs) \
  pass name { SetComputeShader(CompileShader(cs_5_0, cs())); }

technique11 PrefixScan {
  SCAN_PASS(ScanBlocks, CSScanBlocks)
  SCAN_PASS(AddBlockOffsets, CSAddBlockOffsets)
  SCAN_PASS(Total, CSTotal)
}
