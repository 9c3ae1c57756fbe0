// Turning Vulkan failures into HRESULTs and messages.
#pragma once

#include <vulkan/vulkan.h>

#include "rhi/d3d11_types.h"

namespace rhi::vk {

inline HRESULT ToHresult(VkResult result) {
  switch (result) {
    case VK_SUCCESS: return S_OK;
    case VK_ERROR_OUT_OF_HOST_MEMORY:
    case VK_ERROR_OUT_OF_DEVICE_MEMORY: return E_OUTOFMEMORY;
    case VK_ERROR_DEVICE_LOST: return DXGI_ERROR_DEVICE_REMOVED;
    case VK_ERROR_FORMAT_NOT_SUPPORTED:
    case VK_ERROR_FEATURE_NOT_PRESENT:
    case VK_ERROR_EXTENSION_NOT_PRESENT: return DXGI_ERROR_UNSUPPORTED;
    default: return E_FAIL;
  }
}

const char* ResultName(VkResult result);

}  // namespace rhi::vk
