// Particles sorted and blended in compute tiles (issue 19; AMD's D3D11 GPUParticles
// sample, 2014): no ROP blends a translucent fragment. compute_sorted.fxh (OVER back
// to front: the `sorted` reference's image) and compute_wboit.fxh (Tables 1-2 in
// registers) include this file after defining TILE_BLEND. renderer/src/oit/
// compute_tiles.cpp runs the passes, in four phases:
//   Cull    Footprints (object: DrawAuto, one point per particle, no colour target):
//           each particle's tile rectangle and back-to-front key, and whether it is
//           drawn (its geometry shader would emit a quad that covers a pixel centre);
//           the drawn ones compacted in buffer order (the shared prefix scan of
//           Visible, then Compact), their count on the GPU.
//   Sort    the keys sorted with the particle indices (renderer/compute/radix_sort.h:
//           stable, so equal depths keep buffer order, as `sorted`'s std::stable_sort).
//   Bin     CountTiles (tiles each sorted particle touches), the prefix scan of those
//           counts, FillPairs ((tile, particle) pairs in sorted order at the scanned
//           offsets), a stable sort of the pairs by tile, TileRanges (each tile's
//           first and end pair): every tile's list in back-to-front order.
//   Blend   BlendTiles (object: a group per 16x16 tile, a thread per pixel): the tile's
//           quads in order, covered and depth-tested as the rasterizer would, shaded by
//           the object's ShadeAt, blended with TILE_BLEND's arithmetic over the opaque
//           frame, each pixel written once.
// Every dispatch over the drawn particles or the pairs takes its size from the GPU
// (renderer/compute/dispatch_args.h, DispatchIndirect). The contract the object fulfils: OBJECT_QUADS (common.fxh).
#include "common.fxh"

#ifndef TILE_BLEND
#error "define TILE_BLEND (TILE_BLEND_OVER or TILE_BLEND_WBOIT) before including compute_tiles.fxh"
#endif
#define TILE_BLEND_OVER 1
#define TILE_BLEND_WBOIT 2

#include "../compute/indirect.hlsli"

static const uint kTileSize = 16;
static const uint kThreads = 256;  // threads of the one-dimensional passes

cbuffer ComputeTileParams {
  uint2 TileFrameSize;     // pixels
  uint TilesX;             // tiles in a row
  uint PrimitiveCapacity;  // words of the per-particle buffers (the particle system's capacity)
  uint PairCapacity;       // (tile, particle) pairs the pair buffers hold
  // This device's output merger (renderer/output_merger_probe.h), which the blends replay:
  uint UnormRoundsEachTerm;   // 8-bit: each product rounded to 8 bits (else the sum, once)
  uint HalfRoundsTowardZero;  // half: sums rounded toward zero (else to nearest even)
};

// The index of a thread of a one-dimensional pass sized on the GPU (DispatchArgs),
// and whether it has an item (the grid may hold a few groups past the last).
uint ItemIndex(uint3 group, uint thread) { return IndirectGroupIndex(group) * kThreads + thread; }

// ---------------------------------------------------------------------------
// Cull
RWByteAddressBuffer VisibleOut : register(u0);  // 1 where particle i is drawn (cleared to 0)
RWByteAddressBuffer KeysOut : register(u1);     // its back-to-front sort key
RWByteAddressBuffer RectsOut : register(u2);    // its tiles: (x0 | y0 << 16, x1 | y1 << 16), inclusive

ByteAddressBuffer Visible;
ByteAddressBuffer VisibleOffsets;  // the exclusive scan of Visible
ByteAddressBuffer Keys;
RWByteAddressBuffer SortKeysOut : register(u0);
RWByteAddressBuffer SortValuesOut : register(u1);

// The drawn particles, in buffer order, with their keys: the sort's input.
[numthreads(kThreads, 1, 1)]
void CSCompact(uint3 group : SV_GroupID, uint thread : SV_GroupIndex) {
  uint i = group.x * kThreads + thread;  // a dispatch over the capacity
  if (i >= PrimitiveCapacity || Visible.Load(i * 4) == 0) return;
  uint slot = VisibleOffsets.Load(i * 4);
  SortKeysOut.Store(slot * 4, Keys.Load(i * 4));
  SortValuesOut.Store(slot * 4, i);
}

// A key whose ascending order is the view depth's descending order (back to front):
// the float's bits made to order as unsigned integers, inverted.
uint BackToFrontKey(float viewDepth) {
  uint bits = asuint(viewDepth);
  return ~(bits ^ ((bits >> 31) != 0 ? 0xFFFFFFFFu : 0x80000000u));
}

// Pixel coordinates (D3D11's viewport transform of the whole frame) of a clip-space point.
float2 WindowXY(float4 clip) {
  float2 ndc = clip.xy / clip.w;
  return float2(ndc.x * 0.5 + 0.5, 0.5 - ndc.y * 0.5) * float2(TileFrameSize);
}

// ---------------------------------------------------------------------------
// Bin
ByteAddressBuffer SortedValues;  // the particles, back to front (or in buffer order: WBOIT)
ByteAddressBuffer Rects;
ByteAddressBuffer PairOffsets;   // the exclusive scan of PairCountsOut
RWByteAddressBuffer PairCountsOut : register(u0);
RWByteAddressBuffer PairTilesOut : register(u0);
RWByteAddressBuffer PairParticlesOut : register(u1);
ByteAddressBuffer PairTiles;
RWByteAddressBuffer TileStartOut : register(u0);
RWByteAddressBuffer TileEndOut : register(u1);

uint4 RectOf(uint particle) {
  uint2 r = Rects.Load2(particle * 8);
  return uint4(r.x & 0xFFFF, r.x >> 16, r.y & 0xFFFF, r.y >> 16);
}

[numthreads(kThreads, 1, 1)]
void CSCountTiles(uint3 group : SV_GroupID, uint thread : SV_GroupIndex) {
  uint i = ItemIndex(group, thread);
  if (i >= IndirectCount()) return;
  uint4 r = RectOf(SortedValues.Load(i * 4));
  PairCountsOut.Store(i * 4, (r.z - r.x + 1) * (r.w - r.y + 1));
}

// The pairs of sorted particle i at its scanned offset: the pair list is in sorted
// order, which the stable sort by tile keeps within each tile.
[numthreads(kThreads, 1, 1)]
void CSFillPairs(uint3 group : SV_GroupID, uint thread : SV_GroupIndex) {
  uint i = ItemIndex(group, thread);
  if (i >= IndirectCount()) return;
  uint particle = SortedValues.Load(i * 4);
  uint4 r = RectOf(particle);
  uint slot = PairOffsets.Load(i * 4);
  for (uint y = r.y; y <= r.w; ++y)
    for (uint x = r.x; x <= r.z; ++x, ++slot) {
      if (slot >= PairCapacity) return;  // counted on the CPU; the frame is drawn again, grown
      PairTilesOut.Store(slot * 4, y * TilesX + x);
      PairParticlesOut.Store(slot * 4, particle);
    }
}

// Each tile's range of the pairs sorted by tile (both cleared to 0: empty).
[numthreads(kThreads, 1, 1)]
void CSTileRanges(uint3 group : SV_GroupID, uint thread : SV_GroupIndex) {
  uint k = ItemIndex(group, thread);
  uint pairs = IndirectCount();  // at most PairCapacity
  if (k >= pairs) return;
  uint tile = PairTiles.Load(k * 4);
  if (k == 0 || PairTiles.Load((k - 1) * 4) != tile) TileStartOut.Store(tile * 4, k);
  if (k + 1 == pairs || PairTiles.Load((k + 1) * 4) != tile) TileEndOut.Store(tile * 4, k + 1);
}

// ---------------------------------------------------------------------------
// Blend: what TILE_BLEND does with each covered fragment of a pixel, in list order.
Texture2D<float4> OpaqueColor;  // the frame with the opaque objects
Texture2D<float> OpaqueDepth;   // their depth (D32_FLOAT read as R32_FLOAT)
ByteAddressBuffer TileStart;
ByteAddressBuffer TileEnd;
ByteAddressBuffer PairParticles;
RWTexture2D<float4> Composite : register(u0);  // R8G8B8A8_UNORM, copied into the frame

#include "output_merger.hlsli"
// The output merger's arithmetic as this device does it (renderer/output_merger_probe.h).
uint4 BlendUnorm8(float4 src, float4 srcFactor, uint4 dst, float4 inverse) {
  return BlendUnorm8(src, srcFactor, dst, inverse, UnormRoundsEachTerm != 0);
}
float4 Half(float4 x) { return Half(x, HalfRoundsTowardZero != 0); }

#if TILE_BLEND == TILE_BLEND_OVER
// `sorted`'s OVER (alpha.fxh's Over, or the object's additive OVER) into the
// R8G8B8A8_UNORM frame, blend by blend, so that the image is `sorted`'s.
struct PixelBlend {
  uint4 frame;
};
PixelBlend BeginPixel(float4 opaque) {
  PixelBlend b;
  b.frame = ToUnorm8(opaque);
  return b;
}
void BlendFragment(inout PixelBlend b, float3 c, float a, float3 t, float z) {
  float4 src = saturate(float4(c, a));
#if defined(OBJECT_ADDITIVE) && OBJECT_ADDITIVE
  b.frame = BlendUnorm8(src, float4(src.aaa, 0), b.frame, 0);  // SRC_ALPHA, ONE; alpha ZERO, ONE
#else
  b.frame = BlendUnorm8(src, float4(src.aaa, 1), b.frame, src.a);  // SRC_ALPHA, INV_SRC_ALPHA; ONE, INV_SRC_ALPHA
#endif
}
float4 EndPixel(PixelBlend b, float4 opaque) { return b.frame / 255.0; }

#elif TILE_BLEND == TILE_BLEND_WBOIT
#include "wboit_weight.hlsli"
#include "weighted_compose.fxh"
// Table 1 per fragment (accum ONE, ONE into R16G16B16A16_FLOAT; revealage ZERO,
// INV_SRC_COLOR into R8_UNORM), then PSCompose (weighted_compose.fxh) through
// Table 2 (SRC_ALPHA, INV_SRC_ALPHA) over the frame.
struct PixelBlend {
  float4 accum;
  uint revealage;  // 8-bit
};
PixelBlend BeginPixel(float4 opaque) {
  PixelBlend b;
  b.accum = 0;
  b.revealage = 255;
  return b;
}
void BlendFragment(inout PixelBlend b, float3 c, float a, float3 t, float z) {
  b.accum = Half(b.accum + float4(c * a, a) * WboitWeight(a, z));
  b.revealage = BlendUnorm8(saturate(a).xxxx, 0, b.revealage.xxxx, saturate(a)).r;
}
float4 EndPixel(PixelBlend b, float4 opaque) {
  float4 src = WeightedComposite(b.accum, b.revealage / 255.0);
  src = saturate(src);
  return BlendUnorm8(src, src.aaaa, ToUnorm8(opaque), src.a) / 255.0;
}
#endif

#ifdef OBJECT_VS
#if !defined(OBJECT_QUADS) || !OBJECT_QUADS
#error "the compute-tile methods draw objects of camera-facing quads (OBJECT_QUADS, oit/common.fxh)"
#endif

// Footprints: a point per particle (SV_VertexID of DrawAuto: its index in the buffer)
// at a pixel of its own, whose pixel shader writes the particle's footprint.
struct FootprintPoint {
  float4 position : SV_Position;
  nointerpolation uint particle : PARTICLE;
};

FootprintPoint VSFootprint(uint particle : SV_VertexID) {
  uint2 pixel = uint2(particle % TileFrameSize.x, (particle / TileFrameSize.x) % TileFrameSize.y);
  FootprintPoint p;
  p.position = float4((float2(pixel) + 0.5) / float2(TileFrameSize) * float2(2, -2) + float2(-1, 1), 0.5, 1);
  p.particle = particle;
  return p;
}

void PSFootprint(FootprintPoint p) {
  OBJECT_PIXEL v[4];
  float viewDepth;
  if (!QuadOf(p.particle, v, viewDepth)) return;
  float2 lo = 1e30, hi = -1e30;
  for (uint i = 0; i < 4; ++i) {
    if (v[i].position.w <= 0) return;  // a corner behind the eye: not drawn (README, Known gaps)
    float2 xy = WindowXY(v[i].position);
    lo = min(lo, xy), hi = max(hi, xy);
  }
  // The pixel centres (x + 0.5) inside [lo, hi].
  int2 first = max(int2(ceil(lo - 0.5)), 0), last = min(int2(floor(hi - 0.5)), int2(TileFrameSize) - 1);
  if (any(first > last)) return;
  uint4 tiles = uint4(uint2(first), uint2(last)) / kTileSize;
  VisibleOut.Store(p.particle * 4, 1);
  KeysOut.Store(p.particle * 4, BackToFrontKey(viewDepth));
  RectsOut.Store2(p.particle * 8, uint2(tiles.x | tiles.y << 16, tiles.z | tiles.w << 16));
}

// The quads of a chunk of the tile's list: their vertices, and apart their positions
// as the rasterizer sees them (window x, y, depth z / w, and 1 / w), which the
// coverage and depth tests read alone.
static const uint kChunk = 64;
groupshared OBJECT_PIXEL ChunkVertices[kChunk * 4];
groupshared float4 ChunkPositions[kChunk * 4];

float EdgeFunction(float2 a, float2 b, float2 p) { return (b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x); }

// Whether the triangle of window positions a, b, c covers the pixel centre p, and its
// screen-space barycentrics there.
bool Covers(float4 a, float4 b, float4 c, float2 p, out float3 barycentrics) {
  float area = EdgeFunction(a.xy, b.xy, c.xy);
  barycentrics = float3(EdgeFunction(b.xy, c.xy, p), EdgeFunction(c.xy, a.xy, p), EdgeFunction(a.xy, b.xy, p)) / area;
  return area != 0 && all(barycentrics >= 0);
}

[numthreads(kTileSize, kTileSize, 1)]
void CSBlendTiles(uint3 group : SV_GroupID, uint3 local : SV_GroupThreadID, uint thread : SV_GroupIndex) {
  uint2 pixel = group.xy * kTileSize + local.xy;
  bool inside = all(pixel < TileFrameSize);
  uint tile = group.y * TilesX + group.x;
  uint first = TileStart.Load(tile * 4), end = TileEnd.Load(tile * 4);
  float4 opaque = inside ? OpaqueColor.Load(int3(pixel, 0)) : 0;
  float opaqueDepth = inside ? OpaqueDepth.Load(int3(pixel, 0)) : 0;
  float2 centre = float2(pixel) + 0.5;
  PixelBlend blend = BeginPixel(opaque);
  for (uint base = first; base < end; base += kChunk) {
    GroupMemoryBarrierWithGroupSync();  // the last chunk is read
    if (thread < kChunk && base + thread < end) {
      OBJECT_PIXEL v[4];
      float viewDepth;
      QuadOf(PairParticles.Load((base + thread) * 4), v, viewDepth);
      for (uint i = 0; i < 4; ++i) {
        float4 clip = v[i].position;
        ChunkPositions[thread * 4 + i] = float4(WindowXY(clip), clip.z / clip.w, 1 / clip.w);
        ChunkVertices[thread * 4 + i] = v[i];
      }
    }
    GroupMemoryBarrierWithGroupSync();
    uint quads = min(kChunk, end - base);
    for (uint k = 0; k < quads && inside; ++k) {
      // The strip's triangles (0, 1, 2) and (1, 2, 3); a centre on their shared edge
      // counts once. Only positions until the pixel is covered and in front.
      uint v = k * 4;
      float3 l;
      if (!Covers(ChunkPositions[v], ChunkPositions[v + 1], ChunkPositions[v + 2], centre, l)) {
        if (!Covers(ChunkPositions[v + 1], ChunkPositions[v + 2], ChunkPositions[v + 3], centre, l)) continue;
        v += 1;
      }
      float4 a = ChunkPositions[v], b = ChunkPositions[v + 1], c = ChunkPositions[v + 2];
      float z = dot(l, float3(a.z, b.z, c.z));
      if (z < 0 || !(z < opaqueDepth)) continue;  // the near plane; DepthTestNoWrite (LESS)
      float3 q = l * float3(a.w, b.w, c.w);  // perspective-correct: barycentrics over w
      OBJECT_PIXEL f = InterpolateQuad(ChunkVertices[v], ChunkVertices[v + 1], ChunkVertices[v + 2], q / (q.x + q.y + q.z));
      f.position = float4(centre, z, 1);
      float3 color, transmission;
      float alpha;
      ShadeAt(f, color, alpha, transmission);
      BlendFragment(blend, color, alpha, transmission, z);
    }
  }
  if (inside) Composite[pixel] = EndPixel(blend, opaque);
}
#endif

technique11 ComputeTiles {
  pass Compact { SetComputeShader(CompileShader(cs_5_0, CSCompact())); }
  pass CountTiles { SetComputeShader(CompileShader(cs_5_0, CSCountTiles())); }
  pass FillPairs { SetComputeShader(CompileShader(cs_5_0, CSFillPairs())); }
  pass TileRanges { SetComputeShader(CompileShader(cs_5_0, CSTileRanges())); }
#ifdef OBJECT_VS
  pass Footprints {
    SetVertexShader(CompileShader(vs_5_0, VSFootprint()));
    SetGeometryShader(NULL);
    SetPixelShader(CompileShader(ps_5_0, PSFootprint()));
    SetDepthStencilState(NoDepth, 0);
    SetRasterizerState(NoCull);
  }
  pass BlendTiles { SetComputeShader(CompileShader(cs_5_0, CSBlendTiles())); }
#endif
}
