// Exact OIT with per-pixel linked lists, beside document 004's prefix-sum buffer
// (prefix_sum.fxh): one geometry pass instead of two, a fixed node pool instead of
// a buffer sized from a count. Passes:
//   Link     (object) every fragment that passes the opaque depth test
//            ([earlydepthstencil]) takes a node (InterlockedAdd on NodeCounter, one
//            word), stores (triangle id, depth) in it and pushes it on its
//            pixel's list (InterlockedExchange on Heads: R32 words, pixel y * FrameWidth
//            + x, cleared to 0xFFFFFFFF).
//            A fragment whose node lies past the pool is dropped; the counter still
//            counts it, so the C++ reads how many were lost (linked_list.cpp).
//   Resolve  (object, full screen) fragment_resolve.fxh, walking the lists.
#include "common.fxh"
#include "fragment.hlsli"

static const uint kEndOfList = 0xFFFFFFFF;

cbuffer FragmentBufferParams {
  uint FrameWidth;  // pixels in a row of Heads
};

struct FragmentNode {
  Fragment fragment;
  uint next;  // the node pushed before it on the same pixel, or kEndOfList
};

#ifdef OBJECT_VS
RWByteAddressBuffer HeadsOut : register(u0);               // Link: a node index per pixel
RWStructuredBuffer<FragmentNode> NodesOut : register(u1);  // Link: the pool
RWByteAddressBuffer NodeCounter : register(u2);             // Link: nodes taken, one word
ByteAddressBuffer Heads;                                   // Resolve

uint HeadAddress(uint2 pixel) { return (pixel.y * FrameWidth + pixel.x) * 4; }
StructuredBuffer<FragmentNode> Nodes;                      // Resolve

[earlydepthstencil]
void PSLink(OBJECT_PIXEL p, uint primitiveId : SV_PrimitiveID) {
  uint node;
  NodeCounter.InterlockedAdd(0, 1u, node);
  uint capacity, stride;
  NodesOut.GetDimensions(capacity, stride);
  if (node >= capacity) return;  // lost, and counted by the counter
  FragmentNode n;
  n.fragment.id = TriangleId(p, primitiveId);
  n.fragment.depth = p.position.z;
  HeadsOut.InterlockedExchange(HeadAddress(uint2(p.position.xy)), node, n.next);
  NodesOut[node] = n;
}

struct FragmentCursor {
  uint node;
};
FragmentCursor FirstFragment(uint2 pixel) {
  FragmentCursor c;
  c.node = Heads.Load(HeadAddress(pixel));
  return c;
}
bool AtEnd(FragmentCursor c) { return c.node == kEndOfList; }
Fragment FragmentAt(FragmentCursor c) { return Nodes[c.node].fragment; }
FragmentCursor NextFragment(FragmentCursor c) {
  c.node = Nodes[c.node].next;
  return c;
}
#endif

#include "fragment_resolve.fxh"

// With an object, every pass; without one (oit/method.fx) none: both draw the object.
#ifdef OBJECT_VS
technique11 LinkedList {
  FRAGMENT_PASS(Link, PSLink)
  FRAGMENT_RESOLVE_PASS
}
#endif
