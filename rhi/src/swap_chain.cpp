// rhi/swap_chain.h over VK_KHR_swapchain.
//
// Present: the context's pending work (which wrote the back buffer) is submitted
// through Gpu with a barrier that makes the back buffer's writes visible to
// transfer reads; then the swap chain records its own small command buffer that
// waits on the acquire semaphore, blits the back buffer (GENERAL, as every backend
// image) into the swapchain image, and signals a semaphore that the present waits
// on. Queue submission order puts that command buffer after the context's work.
// Frames in flight: 2, each with its own command buffer, fence and acquire
// semaphore; "render finished" semaphores are per swapchain image.
#include "rhi/swap_chain.h"

#include <vulkan/vulkan.h>

#include <algorithm>
#include <array>
#include <vector>

#include "context.h"
#include "resources.h"
#include "states/formats.h"
#include "vk_check.h"

namespace rhi {

namespace vk {
namespace {

constexpr uint32_t kFramesInFlight = 2;

class SwapChainImpl final : public SwapChain {
 public:
  SwapChainImpl(DeviceImpl* device, const SWAP_CHAIN_DESC& desc) : device_(device), desc_(desc) {}
  ~SwapChainImpl() override;

  HRESULT Initialize(const SurfaceFactory& createSurface);
  HRESULT GetBuffer(UINT Buffer, Texture2D** ppSurface) override;
  HRESULT Present(UINT SyncInterval, UINT Flags) override;
  HRESULT ResizeBuffers(UINT BufferCount, UINT Width, UINT Height, DXGI_FORMAT NewFormat,
                        UINT SwapChainFlags) override;
  void GetDesc(SWAP_CHAIN_DESC* pDesc) override { *pDesc = desc_; }

 private:
  Gpu& gpu() { return device_->gpu(); }
  HRESULT CreateBackBuffer();
  // Recreates the Vulkan swapchain for the surface's current extent; S_FALSE when
  // the extent is zero (minimised): then there is no swapchain until it is not.
  HRESULT CreateSwapchain();
  void DestroySwapchainImages();
  void WaitForFrames();

  DeviceImpl* device_;
  SWAP_CHAIN_DESC desc_;
  UINT syncInterval_ = 1;
  ComPtr<Texture2D> backBuffer_;

  VkSurfaceKHR surface_ = VK_NULL_HANDLE;
  VkSwapchainKHR swapchain_ = VK_NULL_HANDLE;
  VkFormat format_ = VK_FORMAT_UNDEFINED;
  VkExtent2D extent_{0, 0};
  std::vector<VkImage> images_;
  std::vector<VkSemaphore> renderDone_;  // one per swapchain image
  bool outOfDate_ = false;

  VkCommandPool pool_ = VK_NULL_HANDLE;
  std::array<VkCommandBuffer, kFramesInFlight> commands_{};
  std::array<VkFence, kFramesInFlight> fences_{};
  std::array<VkSemaphore, kFramesInFlight> acquired_{};
  uint32_t frame_ = 0;
};

VkPresentModeKHR PickPresentMode(VkPhysicalDevice physical, VkSurfaceKHR surface, UINT syncInterval) {
  if (syncInterval > 0) return VK_PRESENT_MODE_FIFO_KHR;  // always supported
  uint32_t count = 0;
  vkGetPhysicalDeviceSurfacePresentModesKHR(physical, surface, &count, nullptr);
  std::vector<VkPresentModeKHR> modes(count);
  vkGetPhysicalDeviceSurfacePresentModesKHR(physical, surface, &count, modes.data());
  for (VkPresentModeKHR wanted : {VK_PRESENT_MODE_MAILBOX_KHR, VK_PRESENT_MODE_IMMEDIATE_KHR})
    if (std::find(modes.begin(), modes.end(), wanted) != modes.end()) return wanted;
  return VK_PRESENT_MODE_FIFO_KHR;
}

HRESULT SwapChainImpl::Initialize(const SurfaceFactory& createSurface) {
  Gpu& g = gpu();
  uint32_t count = 0;
  vkEnumerateDeviceExtensionProperties(g.Physical(), nullptr, &count, nullptr);
  std::vector<VkExtensionProperties> extensions(count);
  vkEnumerateDeviceExtensionProperties(g.Physical(), nullptr, &count, extensions.data());
  bool hasSwapchain = false;
  for (const auto& e : extensions)
    if (std::string_view(e.extensionName) == VK_KHR_SWAPCHAIN_EXTENSION_NAME) hasSwapchain = true;
  if (!hasSwapchain) return g.Refuse("CreateSwapChain: " + g.AdapterName() + " lacks VK_KHR_swapchain");

  uint64_t surface = 0;
  if (!createSurface || !createSurface(g.Instance(), &surface) || !surface)
    return g.Refuse(
        "CreateSwapChain: the surface could not be created (were DEVICE_OPTIONS::InstanceExtensions given?)");
  surface_ = reinterpret_cast<VkSurfaceKHR>(surface);
  VkBool32 supported = VK_FALSE;
  vkGetPhysicalDeviceSurfaceSupportKHR(g.Physical(), g.QueueFamily(), surface_, &supported);
  if (!supported) return g.Refuse("CreateSwapChain: the device's queue cannot present to this surface");

  VkCommandPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
  poolInfo.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
  poolInfo.queueFamilyIndex = g.QueueFamily();
  if (vkCreateCommandPool(g.Device(), &poolInfo, nullptr, &pool_) != VK_SUCCESS) return E_OUTOFMEMORY;
  VkCommandBufferAllocateInfo allocInfo{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
  allocInfo.commandPool = pool_;
  allocInfo.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  allocInfo.commandBufferCount = kFramesInFlight;
  if (vkAllocateCommandBuffers(g.Device(), &allocInfo, commands_.data()) != VK_SUCCESS) return E_OUTOFMEMORY;
  for (uint32_t i = 0; i < kFramesInFlight; ++i) {
    VkFenceCreateInfo fenceInfo{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    fenceInfo.flags = VK_FENCE_CREATE_SIGNALED_BIT;
    VkSemaphoreCreateInfo semaphoreInfo{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
    if (vkCreateFence(g.Device(), &fenceInfo, nullptr, &fences_[i]) != VK_SUCCESS ||
        vkCreateSemaphore(g.Device(), &semaphoreInfo, nullptr, &acquired_[i]) != VK_SUCCESS)
      return E_OUTOFMEMORY;
  }
  if (HRESULT hr = CreateBackBuffer(); FAILED(hr)) return hr;
  if (HRESULT hr = CreateSwapchain(); FAILED(hr)) return hr;
  return S_OK;
}

HRESULT SwapChainImpl::CreateBackBuffer() {
  switch (desc_.Format) {
    case DXGI_FORMAT_R8G8B8A8_UNORM:
    case DXGI_FORMAT_R8G8B8A8_UNORM_SRGB:
    case DXGI_FORMAT_B8G8R8A8_UNORM:
    case DXGI_FORMAT_B8G8R8A8_UNORM_SRGB: break;
    default: return gpu().Refuse("SwapChain: Format must be R8G8B8A8_UNORM(_SRGB) or B8G8R8A8_UNORM(_SRGB)");
  }
  if (desc_.Width == 0 || desc_.Height == 0) return gpu().Refuse("SwapChain: Width and Height must be non-zero");
  TEXTURE2D_DESC desc{};
  desc.Width = desc_.Width;
  desc.Height = desc_.Height;
  desc.MipLevels = 1;
  desc.ArraySize = 1;
  desc.Format = desc_.Format;
  desc.SampleDesc = {1, 0};
  desc.Usage = USAGE_DEFAULT;
  desc.BindFlags = BIND_RENDER_TARGET | BIND_SHADER_RESOURCE;
  backBuffer_.Reset();
  return device_->CreateTexture2D(&desc, nullptr, backBuffer_.GetAddressOf());
}

HRESULT SwapChainImpl::CreateSwapchain() {
  Gpu& g = gpu();
  VkSurfaceCapabilitiesKHR caps{};
  vkGetPhysicalDeviceSurfaceCapabilitiesKHR(g.Physical(), surface_, &caps);
  VkExtent2D extent = caps.currentExtent;
  if (extent.width == UINT32_MAX) {  // the surface takes the swapchain's size
    extent.width = std::clamp(desc_.Width, caps.minImageExtent.width, caps.maxImageExtent.width);
    extent.height = std::clamp(desc_.Height, caps.minImageExtent.height, caps.maxImageExtent.height);
  }
  WaitForFrames();
  if (extent.width == 0 || extent.height == 0) {
    DestroySwapchainImages();
    if (swapchain_) vkDestroySwapchainKHR(g.Device(), swapchain_, nullptr);
    swapchain_ = VK_NULL_HANDLE;
    extent_ = extent;
    return S_FALSE;
  }

  // Prefer an sRGB format when the back buffer is sRGB so the blit keeps values as they are.
  uint32_t count = 0;
  vkGetPhysicalDeviceSurfaceFormatsKHR(g.Physical(), surface_, &count, nullptr);
  std::vector<VkSurfaceFormatKHR> formats(count);
  vkGetPhysicalDeviceSurfaceFormatsKHR(g.Physical(), surface_, &count, formats.data());
  if (formats.empty()) return g.Refuse("SwapChain: the surface reports no formats");
  const bool srgb = desc_.Format == DXGI_FORMAT_R8G8B8A8_UNORM_SRGB || desc_.Format == DXGI_FORMAT_B8G8R8A8_UNORM_SRGB;
  VkSurfaceFormatKHR chosen = formats[0];
  for (const VkFormat wanted : srgb ? std::array{VK_FORMAT_B8G8R8A8_SRGB, VK_FORMAT_R8G8B8A8_SRGB}
                                    : std::array{VK_FORMAT_B8G8R8A8_UNORM, VK_FORMAT_R8G8B8A8_UNORM}) {
    auto it = std::find_if(formats.begin(), formats.end(), [&](const VkSurfaceFormatKHR& f) {
      return f.format == wanted && f.colorSpace == VK_COLOR_SPACE_SRGB_NONLINEAR_KHR;
    });
    if (it != formats.end()) {
      chosen = *it;
      break;
    }
  }
  VkFormatProperties blitProps{};
  vkGetPhysicalDeviceFormatProperties(g.Physical(), chosen.format, &blitProps);
  if (!(blitProps.optimalTilingFeatures & VK_FORMAT_FEATURE_BLIT_DST_BIT))
    return g.Refuse("SwapChain: the surface format cannot be a blit destination");

  VkSwapchainCreateInfoKHR info{VK_STRUCTURE_TYPE_SWAPCHAIN_CREATE_INFO_KHR};
  info.surface = surface_;
  info.minImageCount = std::max(desc_.BufferCount, caps.minImageCount);
  if (caps.maxImageCount) info.minImageCount = std::min(info.minImageCount, caps.maxImageCount);
  info.imageFormat = chosen.format;
  info.imageColorSpace = chosen.colorSpace;
  info.imageExtent = extent;
  info.imageArrayLayers = 1;
  info.imageUsage = VK_IMAGE_USAGE_TRANSFER_DST_BIT;
  info.imageSharingMode = VK_SHARING_MODE_EXCLUSIVE;
  info.preTransform = (caps.supportedTransforms & VK_SURFACE_TRANSFORM_IDENTITY_BIT_KHR)
                          ? VK_SURFACE_TRANSFORM_IDENTITY_BIT_KHR
                          : caps.currentTransform;
  info.compositeAlpha = VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR;
  for (VkCompositeAlphaFlagBitsKHR mode : {VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR, VK_COMPOSITE_ALPHA_INHERIT_BIT_KHR,
                                           VK_COMPOSITE_ALPHA_PRE_MULTIPLIED_BIT_KHR,
                                           VK_COMPOSITE_ALPHA_POST_MULTIPLIED_BIT_KHR}) {
    if (caps.supportedCompositeAlpha & mode) {
      info.compositeAlpha = mode;
      break;
    }
  }
  info.presentMode = PickPresentMode(g.Physical(), surface_, syncInterval_);
  info.clipped = VK_TRUE;
  info.oldSwapchain = swapchain_;
  VkSwapchainKHR created = VK_NULL_HANDLE;
  VkResult result = vkCreateSwapchainKHR(g.Device(), &info, nullptr, &created);
  DestroySwapchainImages();
  if (swapchain_) vkDestroySwapchainKHR(g.Device(), swapchain_, nullptr);
  swapchain_ = created;
  if (result != VK_SUCCESS) return g.Refuse("SwapChain: vkCreateSwapchainKHR failed (" + std::to_string(result) + ")");
  format_ = chosen.format;
  extent_ = extent;
  vkGetSwapchainImagesKHR(g.Device(), swapchain_, &count, nullptr);
  images_.resize(count);
  vkGetSwapchainImagesKHR(g.Device(), swapchain_, &count, images_.data());
  renderDone_.resize(count);
  for (VkSemaphore& s : renderDone_) {
    VkSemaphoreCreateInfo semaphoreInfo{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
    vkCreateSemaphore(g.Device(), &semaphoreInfo, nullptr, &s);
  }
  outOfDate_ = false;
  return S_OK;
}

void SwapChainImpl::WaitForFrames() {
  // Everything this swap chain submitted (and presented) must be done before its
  // images, semaphores or the back buffer change.
  if (gpu().Queue()) vkQueueWaitIdle(gpu().Queue());
}

void SwapChainImpl::DestroySwapchainImages() {
  for (VkSemaphore s : renderDone_) vkDestroySemaphore(gpu().Device(), s, nullptr);
  renderDone_.clear();
  images_.clear();
}

SwapChainImpl::~SwapChainImpl() {
  Gpu& g = gpu();
  device_->context().Flush();
  WaitForFrames();
  DestroySwapchainImages();
  if (swapchain_) vkDestroySwapchainKHR(g.Device(), swapchain_, nullptr);
  for (uint32_t i = 0; i < kFramesInFlight; ++i) {
    if (fences_[i]) vkDestroyFence(g.Device(), fences_[i], nullptr);
    if (acquired_[i]) vkDestroySemaphore(g.Device(), acquired_[i], nullptr);
  }
  if (pool_) vkDestroyCommandPool(g.Device(), pool_, nullptr);
  if (surface_) vkDestroySurfaceKHR(g.Instance(), surface_, nullptr);
}

HRESULT SwapChainImpl::GetBuffer(UINT Buffer, Texture2D** ppSurface) {
  if (Buffer != 0) return gpu().Refuse("SwapChain::GetBuffer: only buffer 0 is accessible");
  if (!ppSurface) return gpu().Refuse("SwapChain::GetBuffer: ppSurface is NULL");
  backBuffer_->AddRef();
  *ppSurface = backBuffer_.Get();
  return S_OK;
}

HRESULT SwapChainImpl::ResizeBuffers(UINT BufferCount, UINT Width, UINT Height, DXGI_FORMAT NewFormat, UINT) {
  // As DXGI: 0 keeps the current count; a zero size takes the window's (here: the surface's) size.
  device_->context().Flush();
  WaitForFrames();
  if (BufferCount) desc_.BufferCount = BufferCount;
  if (NewFormat != DXGI_FORMAT_UNKNOWN) desc_.Format = NewFormat;
  if (Width == 0 || Height == 0) {
    VkSurfaceCapabilitiesKHR caps{};
    vkGetPhysicalDeviceSurfaceCapabilitiesKHR(gpu().Physical(), surface_, &caps);
    if (Width == 0) Width = caps.currentExtent.width != UINT32_MAX ? caps.currentExtent.width : desc_.Width;
    if (Height == 0) Height = caps.currentExtent.height != UINT32_MAX ? caps.currentExtent.height : desc_.Height;
  }
  if (Width == 0 || Height == 0) return gpu().Refuse("SwapChain::ResizeBuffers: the size is zero");
  desc_.Width = Width;
  desc_.Height = Height;
  if (backBuffer_) {
    // DXGI refuses ResizeBuffers while the application holds back-buffer references.
    backBuffer_->AddRef();
    const UINT references = backBuffer_->Release();
    if (references > 1) return gpu().Refuse("SwapChain::ResizeBuffers: release every back-buffer reference first");
  }
  if (HRESULT hr = CreateBackBuffer(); FAILED(hr)) return hr;
  HRESULT hr = CreateSwapchain();
  return FAILED(hr) ? hr : S_OK;
}

HRESULT SwapChainImpl::Present(UINT SyncInterval, UINT Flags) {
  if (Flags != 0) return gpu().Refuse("SwapChain::Present: Flags must be 0");
  Gpu& g = gpu();
  ContextImpl& context = device_->context();
  if (SyncInterval > 1) SyncInterval = 1;
  if ((SyncInterval == 0) != (syncInterval_ == 0)) {
    syncInterval_ = SyncInterval;
    outOfDate_ = true;  // the present mode changes with the swapchain
  }
  if (outOfDate_ || !swapchain_) {
    if (HRESULT hr = CreateSwapchain(); FAILED(hr)) return hr;
    if (!swapchain_) {  // minimised: drop the frame
      context.Flush();
      return S_OK;
    }
  }

  // The context's work that wrote the back buffer goes first, with its writes
  // made visible to the transfer read that follows.
  TextureStorage* back = AsTexture(backBuffer_.Get());
  context.EndRendering();
  context.Use(*back, uses::kTransferRead);
  context.FlushBarriers();
  context.Flush();  // submits, and forgets the state bound in the old command buffer

  const uint32_t frame = frame_;
  vkWaitForFences(g.Device(), 1, &fences_[frame], VK_TRUE, UINT64_MAX);
  uint32_t imageIndex = 0;
  VkResult result = vkAcquireNextImageKHR(g.Device(), swapchain_, UINT64_MAX, acquired_[frame], VK_NULL_HANDLE,
                                          &imageIndex);
  if (result == VK_ERROR_OUT_OF_DATE_KHR) {
    outOfDate_ = true;  // recreated on the next Present; this frame is dropped
    return S_OK;
  }
  if (result != VK_SUCCESS && result != VK_SUBOPTIMAL_KHR) return ToHresult(result);
  if (result == VK_SUBOPTIMAL_KHR) outOfDate_ = true;
  vkResetFences(g.Device(), 1, &fences_[frame]);

  VkCommandBuffer cmd = commands_[frame];
  vkResetCommandBuffer(cmd, 0);
  VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  vkBeginCommandBuffer(cmd, &begin);
  VkMemoryBarrier2 memory{VK_STRUCTURE_TYPE_MEMORY_BARRIER_2};
  memory.srcStageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
  memory.srcAccessMask = VK_ACCESS_2_MEMORY_WRITE_BIT;
  memory.dstStageMask = VK_PIPELINE_STAGE_2_BLIT_BIT;
  memory.dstAccessMask = VK_ACCESS_2_TRANSFER_READ_BIT;
  VkImageMemoryBarrier2 toDst{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
  toDst.srcStageMask = VK_PIPELINE_STAGE_2_BLIT_BIT;  // chained to the acquire semaphore's wait stage
  toDst.srcAccessMask = 0;
  toDst.dstStageMask = VK_PIPELINE_STAGE_2_BLIT_BIT;
  toDst.dstAccessMask = VK_ACCESS_2_TRANSFER_WRITE_BIT;
  toDst.oldLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  toDst.newLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
  toDst.srcQueueFamilyIndex = toDst.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  toDst.image = images_[imageIndex];
  toDst.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
  VkDependencyInfo dependency{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
  dependency.memoryBarrierCount = 1;
  dependency.pMemoryBarriers = &memory;
  dependency.imageMemoryBarrierCount = 1;
  dependency.pImageMemoryBarriers = &toDst;
  vkCmdPipelineBarrier2(cmd, &dependency);

  VkImageBlit blit{};
  blit.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  blit.srcOffsets[1] = {static_cast<int32_t>(desc_.Width), static_cast<int32_t>(desc_.Height), 1};
  blit.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  blit.dstOffsets[1] = {static_cast<int32_t>(extent_.width), static_cast<int32_t>(extent_.height), 1};
  const bool sameSize = desc_.Width == extent_.width && desc_.Height == extent_.height;
  vkCmdBlitImage(cmd, back->image(), VK_IMAGE_LAYOUT_GENERAL, images_[imageIndex],
                 VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &blit, sameSize ? VK_FILTER_NEAREST : VK_FILTER_LINEAR);

  VkImageMemoryBarrier2 toPresent = toDst;
  toPresent.srcStageMask = VK_PIPELINE_STAGE_2_BLIT_BIT;
  toPresent.srcAccessMask = VK_ACCESS_2_TRANSFER_WRITE_BIT;
  toPresent.dstStageMask = VK_PIPELINE_STAGE_2_NONE;  // the semaphore signal orders the present
  toPresent.dstAccessMask = 0;
  toPresent.oldLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
  toPresent.newLayout = VK_IMAGE_LAYOUT_PRESENT_SRC_KHR;
  dependency = {VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
  dependency.imageMemoryBarrierCount = 1;
  dependency.pImageMemoryBarriers = &toPresent;
  vkCmdPipelineBarrier2(cmd, &dependency);
  vkEndCommandBuffer(cmd);

  VkSemaphoreSubmitInfo wait{VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO};
  wait.semaphore = acquired_[frame];
  wait.stageMask = VK_PIPELINE_STAGE_2_BLIT_BIT;
  VkSemaphoreSubmitInfo signal{VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO};
  signal.semaphore = renderDone_[imageIndex];
  signal.stageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
  VkCommandBufferSubmitInfo cmdInfo{VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO};
  cmdInfo.commandBuffer = cmd;
  VkSubmitInfo2 submit{VK_STRUCTURE_TYPE_SUBMIT_INFO_2};
  submit.waitSemaphoreInfoCount = 1;
  submit.pWaitSemaphoreInfos = &wait;
  submit.commandBufferInfoCount = 1;
  submit.pCommandBufferInfos = &cmdInfo;
  submit.signalSemaphoreInfoCount = 1;
  submit.pSignalSemaphoreInfos = &signal;
  result = vkQueueSubmit2(g.Queue(), 1, &submit, fences_[frame]);
  if (result != VK_SUCCESS) return ToHresult(result);
  frame_ = (frame_ + 1) % kFramesInFlight;

  VkPresentInfoKHR present{VK_STRUCTURE_TYPE_PRESENT_INFO_KHR};
  present.waitSemaphoreCount = 1;
  present.pWaitSemaphores = &renderDone_[imageIndex];
  present.swapchainCount = 1;
  present.pSwapchains = &swapchain_;
  present.pImageIndices = &imageIndex;
  result = vkQueuePresentKHR(g.Queue(), &present);
  if (result == VK_ERROR_OUT_OF_DATE_KHR || result == VK_SUBOPTIMAL_KHR) {
    outOfDate_ = true;
    return S_OK;
  }
  return ToHresult(result);
}

}  // namespace
}  // namespace vk

HRESULT CreateSwapChain(Device* pDevice, const SWAP_CHAIN_DESC* pDesc, const SurfaceFactory& createSurface,
                        SwapChain** ppSwapChain) {
  if (!pDevice || !pDesc || !ppSwapChain) return E_INVALIDARG;
  auto* device = static_cast<vk::DeviceImpl*>(pDevice);
  ComPtr<vk::SwapChainImpl> swapChain;
  swapChain.Attach(new vk::SwapChainImpl(device, *pDesc));
  if (HRESULT hr = swapChain->Initialize(createSurface); FAILED(hr)) return hr;
  *ppSwapChain = swapChain.Detach();
  return S_OK;
}

}  // namespace rhi
