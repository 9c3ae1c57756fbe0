// Exact OIT with a prefix-sum fragment buffer (document 004, SPEC.md). Before
// these passes the frame driver has drawn the opaque objects into a visibility
// buffer and the depth (steps 0-1, scene.fx technique Visibility). Passes, in order:
//   Count           (object) steps 2: per pixel, InterlockedAdd into Counts of the
//                   fragments that pass the opaque depth test ([earlydepthstencil]).
//   ScanBlocks, AddBlockOffsets, Total (compute: renderer::compute::PrefixScan,
//                   compute/prefix_scan.fx) step 3: the exclusive prefix sum of Counts
//                   into Offsets; its total, Offsets[last] + Counts[last], is the
//                   fragments of the frame.
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

// With an object, its passes (FX11: a technique holds every pass); the scan's
// compute passes are compute/prefix_scan.fx's, and without an object
// (oit/method.fx) the method has none of its own.
#ifdef OBJECT_VS
technique11 PrefixSum {
  FRAGMENT_PASS(Count, PSCount)
  FRAGMENT_PASS(Fill, PSFill)
  FRAGMENT_RESOLVE_PASS
}
#endif
