#include "oit/fragment_buffers.h"

#include <cstring>

namespace renderer::oit {

using namespace rhi;

bool ViewedBuffer::CreateRaw(Device* device, uint32_t words) {
  bytes = uint64_t(words) * 4;
  const BUFFER_DESC desc{
      words * 4, USAGE_DEFAULT, BIND_UNORDERED_ACCESS | BIND_SHADER_RESOURCE, 0, RESOURCE_MISC_BUFFER_ALLOW_RAW_VIEWS,
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

bool AcceptsOnlyOneObject(const MethodInfo& info, const MethodSetup& setup, std::string* error) {
  if (setup.objectCount <= 1) return true;
  *error = std::string(info.name) +
           " resolves with one object's full-screen pass (deferred shading from its "
           "triangle ids), so it draws scenes of one translucent object; this scene "
           "has " +
           std::to_string(setup.objectCount);
  return false;
}

bool LateReadback::Create(Device* device, Arrived arrived) {
  arrived_ = std::move(arrived);
  const BUFFER_DESC desc{4, USAGE_STAGING, 0, CPU_ACCESS_READ, 0, 0};
  for (auto& buffer : staging_)
    if (FAILED(device->CreateBuffer(&desc, nullptr, buffer.GetAddressOf()))) return false;
  return SUCCEEDED(device->CreateBuffer(&desc, nullptr, now_.GetAddressOf()));
}

void LateReadback::Issue(DeviceContext* context, Buffer* source, uint64_t tag) {
  if (pending_ == kRing) {  // the GPU is a whole ring behind: wait for the oldest (at next_)
    uint32_t value = 0;
    if (Read(context, staging_[next_].Get(), true, &value)) arrived_(value, tags_[next_]);
    --pending_;
  }
  const BOX first{0, 0, 0, 4, 1, 1};
  context->CopySubresourceRegion(staging_[next_].Get(), 0, 0, 0, 0, source, 0, &first);
  tags_[next_] = tag;
  next_ = (next_ + 1) % kRing;
  ++pending_;
}

void LateReadback::Poll(DeviceContext* context) {
  while (pending_ > 0) {
    const size_t oldest = (next_ + kRing - pending_) % kRing;
    uint32_t value = 0;
    if (!Read(context, staging_[oldest].Get(), false, &value)) return;
    --pending_;
    arrived_(value, tags_[oldest]);
  }
}

uint32_t LateReadback::ReadNow(DeviceContext* context, Buffer* source) {
  const BOX first{0, 0, 0, 4, 1, 1};
  context->CopySubresourceRegion(now_.Get(), 0, 0, 0, 0, source, 0, &first);
  uint32_t value = 0;
  Read(context, now_.Get(), true, &value);
  return value;
}

bool LateReadback::Read(DeviceContext* context, Buffer* staging, bool wait, uint32_t* value) {
  MAPPED_SUBRESOURCE mapped{};
  if (FAILED(context->Map(staging, 0, MAP_READ, wait ? 0u : UINT(MAP_FLAG_DO_NOT_WAIT), &mapped))) return false;
  std::memcpy(value, mapped.pData, 4);
  context->Unmap(staging, 0);
  return true;
}

}  // namespace renderer::oit
