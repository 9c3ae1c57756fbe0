#include "rhi/format_info.h"

#include <algorithm>

#include "states/formats.h"

namespace rhi {

UINT BitsPerPixel(DXGI_FORMAT format) {
  const states::FormatInfo* info = states::GetFormatInfo(format);
  return info ? info->bytesPerElement * 8u / (info->blockSize * info->blockSize) : 0u;
}

const char* FormatName(DXGI_FORMAT format) { return states::FormatName(format); }

UINT FormatBindFlags(DXGI_FORMAT format) {
  const states::FormatInfo* info = states::GetFormatInfo(format);
  return info ? info->bindFlags : 0u;
}

bool IsTypeless(DXGI_FORMAT format) {
  const states::FormatInfo* info = states::GetFormatInfo(format);
  return info && info->kind == states::ComponentKind::Typeless;
}

bool IsCompressed(DXGI_FORMAT format) {
  const states::FormatInfo* info = states::GetFormatInfo(format);
  return info && info->blockSize > 1;
}

bool ComputePitch(DXGI_FORMAT format, UINT width, UINT height, UINT64* rowPitch, UINT64* slicePitch) {
  const states::FormatInfo* info = states::GetFormatInfo(format);
  if (!info) return false;
  *rowPitch = states::RowPitchBytes(*info, width);
  *slicePitch = *rowPitch * states::RowCount(*info, height);
  return true;
}

UINT64 TextureBytes(const TEXTURE2D_DESC& desc) {
  UINT levels = desc.MipLevels;
  if (levels == 0)  // D3D11: the full chain down to 1x1
    for (UINT size = std::max(desc.Width, desc.Height); size > 0; size >>= 1) ++levels;
  UINT64 bytes = 0;
  for (UINT level = 0; level < levels; ++level) {
    UINT64 rowPitch = 0, slicePitch = 0;
    ComputePitch(desc.Format, std::max(1u, desc.Width >> level), std::max(1u, desc.Height >> level), &rowPitch,
                 &slicePitch);
    bytes += slicePitch;
  }
  return bytes * desc.ArraySize * std::max(1u, desc.SampleDesc.Count);
}

}  // namespace rhi
