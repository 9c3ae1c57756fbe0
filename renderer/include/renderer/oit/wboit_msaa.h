// Document 001's WBOIT with MSAA (renderer/src/oit/wboit_msaa.cpp,
// shaders_hlsl/oit/wboit_msaa.fxh): what a frame left in its multisampled
// targets, for checks of the composite against a CPU model.
#pragma once

#include <optional>

#include "renderer/oit/method.h"

namespace renderer::oit {

// The multisampled targets of a wboit-msaa method's last frame, as shader
// resources (Texture2DMS): the opaque colour (R16G16B16A16_FLOAT), accum
// (R16G16B16A16_FLOAT: Σ w·c, Σ w) and product (R16_FLOAT: Π(1 − w); null for the
// additive variants, which keep none). nullopt when `method` is not one of them.
struct WboitMsaaTargets {
  rhi::ShaderResourceView* opaque = nullptr;
  rhi::ShaderResourceView* accum = nullptr;
  rhi::ShaderResourceView* product = nullptr;
  uint32_t samples = 0;
};
std::optional<WboitMsaaTargets> GetWboitMsaaTargets(const Method& method);

}  // namespace renderer::oit
