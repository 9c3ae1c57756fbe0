// compute-sorted: the particles sorted on the GPU and blended back to front with
// OVER in compute tiles (compute_tiles.fxh), each blend rounded as the output
// merger rounds into the R8G8B8A8_UNORM frame: `sorted`'s image with no ROP.
#define TILE_BLEND TILE_BLEND_OVER
#include "compute_tiles.fxh"
