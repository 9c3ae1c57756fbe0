// Private data of the device, and WKPDID_D3DDebugObjectName passed on to
// Vulkan as the object's debug-utils name.
#include "private_data.h"

#include <algorithm>
#include <cstring>
#include <string>

#include "device.h"

namespace rhi {

PrivateDataStore::~PrivateDataStore() {
  for (Entry& entry : entries_)
    if (entry.object) entry.object->Release();
}

void PrivateDataStore::Remove(REFGUID guid) {
  auto it = std::find_if(entries_.begin(), entries_.end(), [&](const Entry& e) { return e.guid == guid; });
  if (it == entries_.end()) return;
  if (it->object) it->object->Release();
  entries_.erase(it);
}

HRESULT PrivateDataStore::Set(REFGUID guid, UINT size, const void* data) {
  if (!data && size) return E_INVALIDARG;
  std::lock_guard lock(mutex_);
  Remove(guid);
  if (!data) return S_OK;
  const auto* bytes = static_cast<const uint8_t*>(data);
  entries_.push_back({guid, std::vector<uint8_t>(bytes, bytes + size), nullptr});
  return S_OK;
}

HRESULT PrivateDataStore::SetInterface(REFGUID guid, const Unknown* object) {
  std::lock_guard lock(mutex_);
  Remove(guid);
  if (!object) return S_OK;
  // D3D11 takes `const IUnknown*` and still holds a reference.
  auto* held = const_cast<Unknown*>(object);
  held->AddRef();
  std::vector<uint8_t> pointer(sizeof held);
  std::memcpy(pointer.data(), &held, sizeof held);
  entries_.push_back({guid, std::move(pointer), held});
  return S_OK;
}

HRESULT PrivateDataStore::Get(REFGUID guid, UINT* size, void* data) const {
  if (!size) return E_INVALIDARG;
  std::lock_guard lock(mutex_);
  auto it = std::find_if(entries_.begin(), entries_.end(), [&](const Entry& e) { return e.guid == guid; });
  if (it == entries_.end()) {
    *size = 0;
    return DXGI_ERROR_NOT_FOUND;
  }
  const UINT stored = static_cast<UINT>(it->bytes.size());
  if (!data) {
    *size = stored;
    return S_OK;
  }
  if (*size < stored) {
    *size = stored;
    return DXGI_ERROR_MORE_DATA;
  }
  std::memcpy(data, it->bytes.data(), stored);
  *size = stored;
  if (it->object) it->object->AddRef();  // the caller now holds the returned interface
  return S_OK;
}

namespace vk {

HRESULT DeviceImpl::GetPrivateData(REFGUID guid, UINT* pDataSize, void* pData) {
  return privateData_.Get(guid, pDataSize, pData);
}

HRESULT DeviceImpl::SetPrivateData(REFGUID guid, UINT DataSize, const void* pData) {
  const HRESULT hr = privateData_.Set(guid, DataSize, pData);
  if (hr == S_OK && guid == WKPDID_D3DDebugObjectName)
    gpu_->SetObjectName(VK_OBJECT_TYPE_DEVICE, reinterpret_cast<uint64_t>(gpu_->Device()),
                        pData ? std::string(static_cast<const char*>(pData), DataSize) : std::string());
  return hr;
}

HRESULT DeviceImpl::SetPrivateDataInterface(REFGUID guid, const Unknown* pData) {
  return privateData_.SetInterface(guid, pData);
}

void Gpu::SetObjectName(VkObjectType type, uint64_t handle, const std::string& name) const {
  // Names exist only where VK_EXT_debug_utils is on (with the validation layer).
  if (!Validating()) return;
  const auto setName = reinterpret_cast<PFN_vkSetDebugUtilsObjectNameEXT>(
      vkGetInstanceProcAddr(instance_, "vkSetDebugUtilsObjectNameEXT"));
  if (!setName) return;
  VkDebugUtilsObjectNameInfoEXT info{VK_STRUCTURE_TYPE_DEBUG_UTILS_OBJECT_NAME_INFO_EXT};
  info.objectType = type;
  info.objectHandle = handle;
  info.pObjectName = name.c_str();
  setName(device_, &info);
}

}  // namespace vk
}  // namespace rhi
