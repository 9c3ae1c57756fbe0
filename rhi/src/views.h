// Shader-resource, render-target, depth-stencil and unordered-access views.
#pragma once

#include <utility>
#include <vector>

#include "device.h"
#include "resources.h"

namespace rhi::vk {

// What every view holds: the viewed resource, and the Vulkan objects that
// descriptors and attachments need.
class ViewTarget {
 public:
  Resource* resource() const { return resource_; }
  // Exactly one of these is non-null.
  BufferImpl* buffer() const { return buffer_; }
  TextureStorage* texture() const { return texture_; }
  TrackedResource& tracked() const {
    return buffer_ ? static_cast<TrackedResource&>(*buffer_) : static_cast<TrackedResource&>(*texture_);
  }

  DXGI_FORMAT format() const { return format_; }
  VkImageView imageView() const { return imageView_; }
  VkImageSubresourceRange range() const { return range_; }
  VkBufferView bufferView() const { return bufferView_; }
  // The image view a shader-resource descriptor of this view uses: imageView(), or
  // while the texture has a minimum LOD above the view's most detailed level
  // (SetResourceMinLOD) a variant clamped to it (the latest few kept); VK_NULL_HANDLE
  // (reads return 0) when the clamp lies past the view's last level. Immediate context only.
  VkImageView SampledImageView();
  // Structured and raw buffer views bind as storage buffers over this range.
  VkDescriptorBufferInfo bufferRange() const;

 protected:
  ~ViewTarget();
  // `format` UNKNOWN means the resource's format.
  HRESULT InitTexture(DeviceImpl& device, Resource* resource, DXGI_FORMAT format, VkImageViewType type,
                      VkImageSubresourceRange range, VkImageUsageFlags usage, const char* call);
  HRESULT InitBuffer(DeviceImpl& device, Resource* resource, DXGI_FORMAT format, UINT firstElement,
                     UINT numElements, bool storage, const char* call);

 private:
  // Sets the viewed resource and keeps it alive for the view's lifetime.
  void Hold(Resource* resource);

  DeviceImpl* device_ = nullptr;
  Resource* resource_ = nullptr;
  // A binding, not a reference: a view kept only by the context's bindings must
  // not keep the device alive through its resource (device -> context -> view ->
  // resource -> device would never be released).
  Bound<Bindable> resourceHold_;
  BufferImpl* buffer_ = nullptr;
  TextureStorage* texture_ = nullptr;
  DXGI_FORMAT format_ = DXGI_FORMAT_UNKNOWN;
  VkImageView imageView_ = VK_NULL_HANDLE;
  VkImageSubresourceRange range_{};
  VkBufferView bufferView_ = VK_NULL_HANDLE;
  VkDeviceSize firstByte_ = 0;
  VkDeviceSize byteCount_ = 0;
  // How imageView_ was made, for its minimum-LOD variants.
  VkImageViewCreateInfo viewInfo_{};
  VkImageViewUsageCreateInfo usageInfo_{};
  std::vector<std::pair<FLOAT, VkImageView>> minLodViews_;
};

template <class Interface, class Desc>
class ViewImpl final : public DeviceChildImpl<Interface>, public ViewTarget {
 public:
  static HRESULT Create(DeviceImpl* device, Resource* resource, const Desc* desc, Interface** out);
  void GetResource(Resource** ppResource) override {
    resource()->AddRef();
    *ppResource = resource();
  }
  void GetDesc(Desc* desc) override { *desc = desc_; }
  const Desc& desc() const { return desc_; }
  // Attachments index into textures only.
  TextureStorage& texture() const { return *ViewTarget::texture(); }

 private:
  ViewImpl(DeviceImpl* device, const Desc& desc) : DeviceChildImpl<Interface>(device), desc_(desc) {}
  HRESULT Initialize(Resource* resource);
  Desc desc_;
};

using ShaderResourceViewImpl = ViewImpl<ShaderResourceView, SHADER_RESOURCE_VIEW_DESC>;
using RenderTargetViewImpl = ViewImpl<RenderTargetView, RENDER_TARGET_VIEW_DESC>;
using DepthStencilViewImpl = ViewImpl<DepthStencilView, DEPTH_STENCIL_VIEW_DESC>;

// UAVs are bound to buffers as well as textures, so `texture()` may be null.
class UnorderedAccessViewImpl final : public DeviceChildImpl<UnorderedAccessView>, public ViewTarget {
 public:
  static HRESULT Create(DeviceImpl* device, Resource* resource, const UNORDERED_ACCESS_VIEW_DESC* desc,
                        UnorderedAccessView** out);
  void GetResource(Resource** ppResource) override {
    resource()->AddRef();
    *ppResource = resource();
  }
  void GetDesc(UNORDERED_ACCESS_VIEW_DESC* desc) override { *desc = desc_; }
  // The hidden counter of a BUFFER_UAV_FLAG_APPEND / _COUNTER view (D3D11 keeps
  // it in the view, not in the buffer): a 4-byte buffer; null for other views.
  BufferImpl* counter() const { return counter_.Get(); }

 private:
  UnorderedAccessViewImpl(DeviceImpl* device, const UNORDERED_ACCESS_VIEW_DESC& desc)
      : DeviceChildImpl(device), desc_(desc) {}
  HRESULT Initialize(Resource* resource);
  HRESULT CreateCounter(Resource* resource);
  UNORDERED_ACCESS_VIEW_DESC desc_;
  // A binding, not a reference, as the viewed resource's hold: no device cycle.
  Bound<BufferImpl> counter_;
};

}  // namespace rhi::vk
