// compute-wboit: document 000's WBOIT (Tables 1 and 2) evaluated per pixel in
// compute tiles (compute_tiles.fxh) instead of blended by the output merger: the
// particles unsorted, in buffer order (the order the ROPs blend them in), each sum
// rounded as its RGBA16F / R8 target stores it. Not the paper's pass structure.
#define TILE_BLEND TILE_BLEND_WBOIT
#include "compute_tiles.fxh"
