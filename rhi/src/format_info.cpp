#include "rhi/format_info.h"

#include <algorithm>

#include "states/formats.h"

namespace rhi {

UINT BitsPerPixel(DXGI_FORMAT format) {
  const states::FormatInfo* info = states::GetFormatInfo(format);
  return info ? info->bytesPerElement * 8u : 0u;
}

UINT64 TextureBytes(const TEXTURE2D_DESC& desc) {
  const UINT64 bytesPerTexel = BitsPerPixel(desc.Format) / 8;
  UINT levels = desc.MipLevels;
  if (levels == 0)  // D3D11: the full chain down to 1x1
    for (UINT size = std::max(desc.Width, desc.Height); size > 0; size >>= 1) ++levels;
  UINT64 texels = 0;
  for (UINT level = 0; level < levels; ++level)
    texels += UINT64(std::max(1u, desc.Width >> level)) * std::max(1u, desc.Height >> level);
  return texels * bytesPerTexel * desc.ArraySize * std::max(1u, desc.SampleDesc.Count);
}

}  // namespace rhi
