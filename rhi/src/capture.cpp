#include "rhi/capture.h"

#include <algorithm>
#include <cstring>

#include "device.h"
#include "states/formats.h"

namespace rhi {

namespace {

// Resolves array slice `slice` of the multisampled `source` (D3D11's average of
// the samples) into a new single-sampled texture, or refuses what has no average.
HRESULT Resolve(Device* device, DeviceContext* context, Texture2D* source, UINT slice, Texture2D** out) {
  const vk::Gpu& gpu = static_cast<vk::DeviceImpl*>(device)->gpu();
  TEXTURE2D_DESC desc;
  source->GetDesc(&desc);
  const states::FormatInfo* format = states::GetFormatInfo(desc.Format);
  const std::string what = std::string("CaptureTexture2D: the texture is multisampled (SampleDesc.Count ") +
                           std::to_string(desc.SampleDesc.Count) + ") and " + format->name;
  if (format->kind == states::ComponentKind::Uint || format->kind == states::ComponentKind::Sint)
    return gpu.Refuse(what + " is an integer format, which has no resolve (average of samples); read the samples "
                             "through a Texture2DMS view");
  if (format->isDepth || format->kind == states::ComponentKind::Depth || (desc.BindFlags & BIND_DEPTH_STENCIL))
    return gpu.Refuse(what + " is a depth format, which has no resolve; read the samples through a Texture2DMS view");
  if (format->kind == states::ComponentKind::Typeless)
    return gpu.Refuse(what + " is typeless: resolve it with ResolveSubresource and a typed Format first");
  desc.ArraySize = 1;
  desc.SampleDesc = {1, 0};
  desc.BindFlags = 0;
  desc.MiscFlags = 0;
  if (HRESULT hr = device->CreateTexture2D(&desc, nullptr, out); FAILED(hr)) return hr;
  context->ResolveSubresource(*out, 0, source, slice, desc.Format);
  return S_OK;
}

}  // namespace

HRESULT CaptureTexture2D(Device* device, DeviceContext* context, Texture2D* source, UINT subresource,
                         std::vector<uint8_t>* texels) {
  const vk::Gpu& gpu = static_cast<vk::DeviceImpl*>(device)->gpu();
  TEXTURE2D_DESC desc;
  source->GetDesc(&desc);
  if (subresource >= desc.MipLevels * desc.ArraySize)
    return gpu.Refuse("CaptureTexture2D: subresource " + std::to_string(subresource) + " is out of range (" +
                      std::to_string(desc.MipLevels * desc.ArraySize) + " subresources)");
  const UINT mip = subresource % desc.MipLevels;
  desc.Width = std::max(1u, desc.Width >> mip);
  desc.Height = std::max(1u, desc.Height >> mip);
  desc.MipLevels = desc.ArraySize = 1;
  desc.Usage = USAGE_STAGING;
  desc.BindFlags = 0;
  desc.CPUAccessFlags = CPU_ACCESS_READ;
  desc.MiscFlags = 0;
  ComPtr<Texture2D> resolved;
  if (desc.SampleDesc.Count > 1) {
    if (HRESULT hr = Resolve(device, context, source, subresource, resolved.GetAddressOf()); FAILED(hr)) return hr;
    source = resolved.Get();
    subresource = 0;
    desc.SampleDesc = {1, 0};
  }
  ComPtr<Texture2D> staging;
  if (HRESULT hr = device->CreateTexture2D(&desc, nullptr, staging.GetAddressOf()); FAILED(hr)) return hr;
  context->CopySubresourceRegion(staging.Get(), 0, 0, 0, 0, source, subresource, nullptr);
  MAPPED_SUBRESOURCE mapped{};
  if (HRESULT hr = context->Map(staging.Get(), 0, MAP_READ, 0, &mapped); FAILED(hr)) return hr;
  // Block-compressed textures come back as their blocks, a row of blocks per 4 texel rows.
  const states::FormatInfo& format = *states::GetFormatInfo(desc.Format);
  const size_t rowBytes = states::RowPitchBytes(format, desc.Width);
  const UINT rows = states::RowCount(format, desc.Height);
  texels->resize(rowBytes * rows);
  for (UINT y = 0; y < rows; ++y)
    std::memcpy(texels->data() + y * rowBytes, static_cast<const uint8_t*>(mapped.pData) + size_t(y) * mapped.RowPitch,
                rowBytes);
  context->Unmap(staging.Get(), 0);
  return S_OK;
}

}  // namespace rhi
