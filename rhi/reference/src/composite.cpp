#include "rhi_reference/composite.h"

#include "rhi_reference/blend.h"

namespace rhi::reference {

RENDER_TARGET_BLEND_DESC OverBlendDesc() {
  RENDER_TARGET_BLEND_DESC over;
  over.BlendEnable = TRUE;
  over.SrcBlend = BLEND_SRC_ALPHA;
  over.DestBlend = BLEND_INV_SRC_ALPHA;
  over.BlendOp = BLEND_OP_ADD;
  over.SrcBlendAlpha = BLEND_ONE;
  over.DestBlendAlpha = BLEND_INV_SRC_ALPHA;
  over.BlendOpAlpha = BLEND_OP_ADD;
  over.RenderTargetWriteMask = COLOR_WRITE_ENABLE_ALL;
  return over;
}

StoredColor CompositeBackToFront(DXGI_FORMAT format, std::span<const Float4> layersBackToFront,
                                 const StoredColor& background, const RENDER_TARGET_BLEND_DESC& blend) {
  const Float4 unusedFactor{1.0f, 1.0f, 1.0f, 1.0f};  // D3D11's default blend factor
  StoredColor pixel = background;
  for (const Float4& layer : layersBackToFront) {
    pixel = BlendResult(format, blend, unusedFactor, layer, layer, pixel).stored;
  }
  return pixel;
}

}  // namespace rhi::reference
