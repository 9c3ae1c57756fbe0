// Exact OIT with a prefix-sum fragment buffer (document 004, SPEC.md). Before
// these passes the frame driver has drawn the opaque objects into a visibility
// buffer and the depth (steps 0-1, scene.fx technique Visibility). Passes, in order:
//   Count           (object) steps 2: per pixel, InterlockedAdd into Counts of the
//                   fragments that pass the opaque depth test ([earlydepthstencil]).
//   ScanBlocks, AddBlockOffsets (compute, method.fx) step 3: the exclusive prefix sum
//                   of Counts into Offsets, 512 elements a group (Blelloch), the
//                   groups' sums scanned recursively, for any length.
//   Total           (compute) Offsets[last] + Counts[last]: the fragments of the frame.
//   Fill            (object) step 4: each fragment's (triangle id, depth) at
//                   Offsets[pixel] + InterlockedAdd(Cursors[pixel], 1); the cursors
//                   end equal to the counts.
//   ShadeOpaque     (scene.fx Visibility/ShadeOpaque, full screen) step 6's opaque part: each
//                   pixel's opaque triangle shaded from the visibility buffer into the
//                   frame (the background where there is none), before the resolve
//                   blends the translucent composite over it: frame = C + T * opaque,
//                   as step 6's "shade the opaque pixel under it".
//   Resolve         (object, full screen) step 5: fragment_resolve.fxh.
// Per-pixel buffers are raw R32 words at (y * FrameWidth + x) * 4; the fill stores
// only the slots below the fragment buffer's size (renderer/src/oit/prefix_sum.cpp
// sizes it, and counts what did not fit).
#include "common.fxh"
#include "fragment.hlsli"

cbuffer FragmentBufferParams {
  uint FrameWidth;  // pixels in a row of the per-pixel buffers
};

// Step 3 (compute, the method's own effect): one level of the scan.
cbuffer ScanParams {
  uint ScanLength;   // elements of ScanInput / ScanOutput
  uint ScanGroupsX;  // groups in x of the dispatch (65535 at most a dimension): group = y * ScanGroupsX + x
};
RWByteAddressBuffer ScanInput : register(u0);
RWByteAddressBuffer ScanOutput : register(u1);
RWByteAddressBuffer ScanBlockSums : register(u2);  // ScanBlocks: each group's sum; AddBlockOffsets: their scan
RWByteAddressBuffer ScanTotal : register(u3);

static const uint kScanThreads = 256;
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

// The frame's fragments: the last offset plus the last count.
[numthreads(1, 1, 1)]
void CSTotal() {
  uint last = (ScanLength - 1) * 4;
  ScanTotal.Store(0, ScanOutput.Load(last) + ScanInput.Load(last));
}

#ifdef OBJECT_VS
RWByteAddressBuffer CountsOut : register(u0);           // Count
RWByteAddressBuffer Cursors : register(u1);             // Fill
RWStructuredBuffer<Fragment> FragmentsOut : register(u2);  // Fill
ByteAddressBuffer Counts;                                // Resolve
ByteAddressBuffer Offsets;                               // Fill, Resolve
StructuredBuffer<Fragment> Fragments;                    // Resolve

uint PixelAddress(float4 position) { return (uint(position.y) * FrameWidth + uint(position.x)) * 4; }

[earlydepthstencil]
void PSCount(OBJECT_PIXEL p) { CountsOut.InterlockedAdd(PixelAddress(p.position), 1u); }

[earlydepthstencil]
void PSFill(OBJECT_PIXEL p, uint primitiveId : SV_PrimitiveID) {
  uint address = PixelAddress(p.position);
  uint rank;
  Cursors.InterlockedAdd(address, 1u, rank);
  uint slot = Offsets.Load(address) + rank;
  uint capacity, stride;
  FragmentsOut.GetDimensions(capacity, stride);
  if (slot >= capacity) return;  // the buffer was sized from an earlier frame: counted on the CPU
  Fragment f;
  f.id = TriangleId(p, primitiveId);
  f.depth = p.position.z;
  FragmentsOut[slot] = f;
}

// The resolve walks the pixel's contiguous range of the fragment buffer.
struct FragmentCursor {
  uint at, end;
};
FragmentCursor FirstFragment(uint2 pixel) {
  uint address = (pixel.y * FrameWidth + pixel.x) * 4;
  uint capacity, stride;
  Fragments.GetDimensions(capacity, stride);
  FragmentCursor c;
  c.at = Offsets.Load(address);
  c.end = min(c.at + Counts.Load(address), capacity);
  return c;
}
bool AtEnd(FragmentCursor c) { return c.at >= c.end; }
Fragment FragmentAt(FragmentCursor c) { return Fragments[c.at]; }
FragmentCursor NextFragment(FragmentCursor c) {
  c.at += 1;
  return c;
}
#endif

#include "fragment_resolve.fxh"

#define SCAN_PASS(name, cs) \
  pass name { SetComputeShader(CompileShader(cs_5_0, cs())); }

// With an object, its passes (FX11: a technique holds every pass); without one
// (oit/method.fx), the scan's compute passes.
technique11 PrefixSum {
#ifdef OBJECT_VS
  FRAGMENT_PASS(Count, PSCount)
  FRAGMENT_PASS(Fill, PSFill)
  FRAGMENT_RESOLVE_PASS
#else
  SCAN_PASS(ScanBlocks, CSScanBlocks)
  SCAN_PASS(AddBlockOffsets, CSAddBlockOffsets)
  SCAN_PASS(Total, CSTotal)
#endif
}
