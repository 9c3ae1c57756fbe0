// What the fragment-buffer methods (prefix_sum.fxh, linked_list.fxh) store per
// translucent fragment: 8 bytes, and no colour (document 004: shading is deferred
// to the resolve, from the triangle id).
#ifndef OIT_FRAGMENT_HLSLI
#define OIT_FRAGMENT_HLSLI

struct Fragment {
  uint id;      // the object's TriangleId (oit/common.fxh)
  float depth;  // SV_Position.z
};

#endif
