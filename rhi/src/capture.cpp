#include "rhi/capture.h"

#include <algorithm>
#include <cstring>

#include "device.h"
#include "states/formats.h"

namespace rhi {

HRESULT CaptureTexture2D(Device* device, DeviceContext* context, Texture2D* source, UINT subresource,
                         std::vector<uint8_t>* texels) {
  const vk::Gpu& gpu = static_cast<vk::DeviceImpl*>(device)->gpu();
  TEXTURE2D_DESC desc;
  source->GetDesc(&desc);
  if (desc.SampleDesc.Count != 1)
    return gpu.Refuse("CaptureTexture2D: the texture is multisampled (SampleDesc.Count " +
                      std::to_string(desc.SampleDesc.Count) + "); resolve it with ResolveSubresource first");
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
  ComPtr<Texture2D> staging;
  if (HRESULT hr = device->CreateTexture2D(&desc, nullptr, staging.GetAddressOf()); FAILED(hr)) return hr;
  context->CopySubresourceRegion(staging.Get(), 0, 0, 0, 0, source, subresource, nullptr);
  MAPPED_SUBRESOURCE mapped{};
  if (HRESULT hr = context->Map(staging.Get(), 0, MAP_READ, 0, &mapped); FAILED(hr)) return hr;
  const size_t rowBytes = size_t(desc.Width) * states::GetFormatInfo(desc.Format)->bytesPerElement;
  texels->resize(rowBytes * desc.Height);
  for (UINT y = 0; y < desc.Height; ++y)
    std::memcpy(texels->data() + y * rowBytes, static_cast<const uint8_t*>(mapped.pData) + size_t(y) * mapped.RowPitch,
                rowBytes);
  context->Unmap(staging.Get(), 0);
  return S_OK;
}

}  // namespace rhi
