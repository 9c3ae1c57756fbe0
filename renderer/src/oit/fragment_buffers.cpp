#include "oit/fragment_buffers.h"

#include <cstring>

namespace renderer::oit {

using namespace rhi;

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
