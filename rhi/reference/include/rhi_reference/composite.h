// Back-to-front compositing of sorted layers through the reference blender, so
// the expected image carries the same per-layer quantisation the GPU's does.
#pragma once

#include <span>

#include "rhi/d3d11_types.h"
#include "rhi_reference/formats.h"

namespace rhi::reference {

// OVER for straight (non-premultiplied) colour: RGB (SRC_ALPHA, INV_SRC_ALPHA,
// ADD), alpha (ONE, INV_SRC_ALPHA, ADD), blending on, all channels written.
RENDER_TARGET_BLEND_DESC OverBlendDesc();

// Blends layers[0] (farthest) first, layers.back() (nearest) last, onto
// `background`, each layer as a pixel-shader output through BlendResult.
StoredColor CompositeBackToFront(DXGI_FORMAT format, std::span<const Float4> layersBackToFront,
                                 const StoredColor& background,
                                 const RENDER_TARGET_BLEND_DESC& blend = OverBlendDesc());

}  // namespace rhi::reference
