// ViewedBuffer: see renderer/compute/viewed_buffer.h.
#include "renderer/compute/viewed_buffer.h"

namespace renderer::compute {

using namespace rhi;

bool ViewedBuffer::CreateRaw(Device* device, uint32_t words, UINT misc) {
  bytes = uint64_t(words) * 4;
  const BUFFER_DESC desc{
      words * 4, USAGE_DEFAULT, BIND_UNORDERED_ACCESS | BIND_SHADER_RESOURCE, 0, RESOURCE_MISC_BUFFER_ALLOW_RAW_VIEWS | misc,
      0};
  UNORDERED_ACCESS_VIEW_DESC u{};
  u.Format = DXGI_FORMAT_R32_TYPELESS;
  u.ViewDimension = UAV_DIMENSION_BUFFER;
  u.Buffer = {0, words, BUFFER_UAV_FLAG_RAW};
  SHADER_RESOURCE_VIEW_DESC s{};
  s.Format = DXGI_FORMAT_R32_TYPELESS;
  s.ViewDimension = SRV_DIMENSION_BUFFEREX;
  s.BufferEx = {0, words, BUFFEREX_SRV_FLAG_RAW};
  return SUCCEEDED(device->CreateBuffer(&desc, nullptr, buffer.GetAddressOf())) &&
         SUCCEEDED(device->CreateUnorderedAccessView(buffer.Get(), &u, uav.GetAddressOf())) &&
         SUCCEEDED(device->CreateShaderResourceView(buffer.Get(), &s, srv.GetAddressOf()));
}

bool ViewedBuffer::CreateStructured(Device* device, uint32_t count, uint32_t stride, bool counter) {
  bytes = uint64_t(count) * stride;
  const BUFFER_DESC desc{
      count * stride, USAGE_DEFAULT, BIND_UNORDERED_ACCESS | BIND_SHADER_RESOURCE, 0, RESOURCE_MISC_BUFFER_STRUCTURED,
      stride};
  UNORDERED_ACCESS_VIEW_DESC u{};
  u.Format = DXGI_FORMAT_UNKNOWN;
  u.ViewDimension = UAV_DIMENSION_BUFFER;
  u.Buffer = {0, count, counter ? UINT(BUFFER_UAV_FLAG_COUNTER) : 0u};
  return SUCCEEDED(device->CreateBuffer(&desc, nullptr, buffer.GetAddressOf())) &&
         SUCCEEDED(device->CreateUnorderedAccessView(buffer.Get(), &u, uav.GetAddressOf())) &&
         SUCCEEDED(device->CreateShaderResourceView(buffer.Get(), nullptr, srv.GetAddressOf()));
}

}  // namespace renderer::compute
