// A small DXGI-like swap chain over a Vulkan surface (IDXGISwapChain, reduced).
//
// The swap chain owns one back-buffer Texture2D (GetBuffer(0)) that the application
// renders into (or resolves into) with the ordinary D3D11-shaped API. Present
// copies it (vkCmdBlitImage, scaling and converting the format if needed) into the
// acquired Vulkan swapchain image and presents that. ResizeBuffers recreates the
// back buffer and the Vulkan swapchain; as in DXGI, release every reference to the
// old back buffer (views included) first. While the surface has a zero extent
// (a minimised window) Present does nothing and returns S_OK.
//
// The Vulkan instance must have been created with the surface extensions of the
// window system (DEVICE_OPTIONS::InstanceExtensions, e.g. from
// glfwGetRequiredInstanceExtensions); the device enables VK_KHR_swapchain when the
// adapter has it.
#pragma once

#include <cstdint>
#include <functional>

#include "rhi/rhi.h"

namespace rhi {

struct SWAP_CHAIN_DESC {
  UINT Width;          // back-buffer size in pixels
  UINT Height;
  DXGI_FORMAT Format;  // R8G8B8A8_UNORM(_SRGB) or B8G8R8A8_UNORM(_SRGB)
  UINT BufferCount;    // Vulkan images wanted (at least the surface's minimum)
};

class SwapChain : public Unknown {
 public:
  // Buffer must be 0 (one application-visible back buffer). Adds a reference.
  virtual HRESULT GetBuffer(UINT Buffer, Texture2D** ppSurface) = 0;
  // SyncInterval 0: no vsync (MAILBOX/IMMEDIATE when available), else FIFO. Flags must be 0.
  virtual HRESULT Present(UINT SyncInterval, UINT Flags) = 0;
  // 0 / DXGI_FORMAT_UNKNOWN keep the current value, as in DXGI.
  virtual HRESULT ResizeBuffers(UINT BufferCount, UINT Width, UINT Height, DXGI_FORMAT NewFormat,
                                UINT SwapChainFlags) = 0;
  virtual void GetDesc(SWAP_CHAIN_DESC* pDesc) = 0;
};

// Creates the window's surface: receives the VkInstance (as void*), stores the
// VkSurfaceKHR (as uint64_t) and returns true on success. With GLFW:
//   [w](void* i, uint64_t* s) { return glfwCreateWindowSurface((VkInstance)i, w, nullptr,
//                                                              (VkSurfaceKHR*)s) == VK_SUCCESS; }
// The swap chain destroys the surface when it goes.
using SurfaceFactory = std::function<bool(void* vkInstance, uint64_t* vkSurface)>;

// Release the swap chain before its device.
HRESULT CreateSwapChain(Device* pDevice, const SWAP_CHAIN_DESC* pDesc, const SurfaceFactory& createSurface,
                        SwapChain** ppSwapChain);

}  // namespace rhi
