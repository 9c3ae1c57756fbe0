// The device's caches by content: state objects deduplicated by desc, and the
// content ids that pipeline keys are made of (pipelines.h).
#pragma once

#include <mutex>
#include <string>
#include <unordered_map>

#include "device.h"
#include "states/blend.h"
#include "states/depth_stencil.h"
#include "states/rasterizer.h"
#include "states/sampler.h"

namespace rhi::vk {

template <class Interface, class Desc>
class StateObject;

// The device's cache of one state type: D3D11 returns the existing object for a
// desc equal to an earlier one once normalised. Keyed by the whole normalised
// desc; the objects are held weakly. An entry outlives its object so that a
// desc created again gets its old content id, and with it the pipelines built
// for it (pipelines.h).
template <class Interface, class Desc>
class StateCache {
 public:
  using Object = StateObject<Interface, Desc>;

  // A new reference to the object of `normalized`, made by
  // `create(contentId, &object)` if none is alive. A lookup never revives an
  // object whose deletion has begun (DeviceChildImpl::TryAddRef): that one is
  // replaced, and forgets itself without touching its replacement.
  template <class Create>
  HRESULT FindOrCreate(DeviceImpl& device, const Desc& normalized, Create&& create, Object** out) {
    std::lock_guard lock(mutex_);
    Entry& entry = entries_[normalized];
    if (entry.object && entry.object->TryAddRef()) {
      *out = entry.object;
      return S_OK;
    }
    if (entry.contentId == 0) entry.contentId = device.NextContentId();
    Object* created = nullptr;
    if (HRESULT hr = create(entry.contentId, &created); FAILED(hr)) return hr;
    entry.object = created;
    *out = created;
    return S_OK;
  }

  // Called by a dying object: its entry stops pointing at it, unless a newer object took it.
  void Forget(const Desc& normalized, const Object* object) {
    std::lock_guard lock(mutex_);
    auto it = entries_.find(normalized);
    if (it != entries_.end() && it->second.object == object) it->second.object = nullptr;
  }

 private:
  struct Entry {
    Object* object = nullptr;
    uint64_t contentId = 0;
  };
  struct Hash {
    size_t operator()(const Desc& desc) const { return states::RawHash(desc); }
  };
  struct Equal {
    bool operator()(const Desc& a, const Desc& b) const { return states::RawEqual(a, b); }
  };
  // Recursive: an object that fails to initialise in `create` forgets itself
  // while FindOrCreate holds the lock.
  std::recursive_mutex mutex_;
  std::unordered_map<Desc, Entry, Hash, Equal> entries_;
};

// Ids for the contents of shaders and input layouts: equal contents get the
// same id for the device's lifetime, so pipelines (keyed by these ids) are
// found again when an object is created again after its release.
class ContentIds {
 public:
  uint64_t IdOf(DeviceImpl& device, std::string content) {
    std::lock_guard lock(mutex_);
    auto [it, added] = ids_.try_emplace(std::move(content), 0);
    if (added) it->second = device.NextContentId();
    return it->second;
  }

 private:
  std::mutex mutex_;
  std::unordered_map<std::string, uint64_t> ids_;
};

// The device's caches by content. One per state type, so a hash shared by
// descs of two types never mixes them.
struct ObjectCaches {
  StateCache<BlendState, BLEND_DESC> blend;
  StateCache<DepthStencilState, DEPTH_STENCIL_DESC> depthStencil;
  StateCache<RasterizerState, RASTERIZER_DESC> rasterizer;
  StateCache<SamplerState, SAMPLER_DESC> sampler;

  StateCache<BlendState, BLEND_DESC>& Of(const BLEND_DESC*) { return blend; }
  StateCache<DepthStencilState, DEPTH_STENCIL_DESC>& Of(const DEPTH_STENCIL_DESC*) { return depthStencil; }
  StateCache<RasterizerState, RASTERIZER_DESC>& Of(const RASTERIZER_DESC*) { return rasterizer; }
  StateCache<SamplerState, SAMPLER_DESC>& Of(const SAMPLER_DESC*) { return sampler; }

  ContentIds shaders;  // by stage, SPIR-V and stream-output declaration
  ContentIds inputLayouts;
};

}  // namespace rhi::vk
