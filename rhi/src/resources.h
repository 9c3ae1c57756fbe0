// Buffers and textures.
#pragma once

#include <atomic>
#include <string>
#include <vector>

#include "device.h"
#include "resource_tracking.h"

namespace rhi::vk {

// The counter behind D3D11's "append where the last stream-out stopped" and
// DrawAuto: bytes 0..3 hold the Vulkan transform feedback counter (the byte
// offset the last stream-out reached), bytes 16..31 the VkDrawIndirectCommand
// that DrawAuto's compute step writes from it.
struct StreamOutCounter : TrackedResource {
  static constexpr VkDeviceSize kCounterOffset = 0;
  static constexpr VkDeviceSize kDrawArgsOffset = 16;
  static constexpr VkDeviceSize kSize = 32;
  VkBuffer buffer = VK_NULL_HANDLE;
  VkDeviceMemory memory = VK_NULL_HANDLE;
  // Whether the counter holds a value; until the first stream-out it counts from 0.
  bool valid = false;
};

class BufferImpl final : public DeviceChildImpl<Buffer>, public TrackedResource {
 public:
  static HRESULT Create(DeviceImpl* device, const BUFFER_DESC& desc, const SUBRESOURCE_DATA* initialData,
                        BufferImpl** out);
  ~BufferImpl() override;

  void GetType(RESOURCE_DIMENSION* dimension) override { *dimension = RESOURCE_DIMENSION_BUFFER; }
  void GetDesc(BUFFER_DESC* desc) override { *desc = desc_; }
  const BUFFER_DESC& desc() const { return desc_; }

  // Where the contents live now (DYNAMIC buffers move on every WRITE_DISCARD).
  VkBuffer handle() const { return isDynamic() ? slice_.buffer : buffer_; }
  VkDeviceSize baseOffset() const { return isDynamic() ? slice_.offset : 0; }
  bool isDynamic() const { return desc_.Usage == USAGE_DYNAMIC; }
  bool isStaging() const { return desc_.Usage == USAGE_STAGING; }
  // CPU-visible contents of DYNAMIC and STAGING buffers.
  uint8_t* hostData() const { return isDynamic() ? slice_.data : static_cast<uint8_t*>(mapped_); }
  // WRITE_DISCARD: new storage; the GPU keeps the old until it is done with it.
  void Rename();

  StreamOutCounter& soCounter();

 private:
  BufferImpl(DeviceImpl* device, const BUFFER_DESC& desc) : DeviceChildImpl(device), desc_(desc) {}
  HRESULT Initialize(const SUBRESOURCE_DATA* initialData);

  BUFFER_DESC desc_;
  VkBuffer buffer_ = VK_NULL_HANDLE;
  VkDeviceMemory memory_ = VK_NULL_HANDLE;
  void* mapped_ = nullptr;
  HostSlice slice_;
  std::unique_ptr<StreamOutCounter> soCounter_;
};

// What Texture1D, Texture2D and Texture3D have in common.
struct TextureShape {
  RESOURCE_DIMENSION dimension = RESOURCE_DIMENSION_TEXTURE2D;
  UINT width = 1, height = 1, mipLevels = 1, arraySize = 1, samples = 1;
  DXGI_FORMAT format = DXGI_FORMAT_UNKNOWN;
  USAGE usage = USAGE_DEFAULT;
  UINT bindFlags = 0, cpuAccessFlags = 0, miscFlags = 0;
  UINT sampleQuality = 0;  // DXGI_SAMPLE_DESC::Quality
  UINT depth = 1;          // TEXTURE3D_DESC::Depth (3D textures have arraySize 1)
};

// "CreateTexture1D", "CreateTexture2D" or "CreateTexture3D", for messages.
const char* CreateCallName(RESOURCE_DIMENSION dimension);

// The sample counts a render target (a depth-stencil for depth formats) of
// `format` may have on `gpu`, as a VkSampleCountFlags mask; 0 for formats that
// cannot be either. CheckMultisampleQualityLevels answers from it.
VkSampleCountFlags TargetSampleCounts(const Gpu& gpu, DXGI_FORMAT format);

class TextureStorage : public TrackedResource {
 public:
  ~TextureStorage();
  HRESULT Initialize(DeviceImpl& device, const TextureShape& shape, const SUBRESOURCE_DATA* initialData);

  const TextureShape& shape() const { return shape_; }
  VkImage image() const { return image_; }
  VkFormat vkFormat() const { return vkFormat_; }
  VkImageAspectFlags aspects() const { return aspects_; }
  UINT subresourceCount() const { return shape_.mipLevels * shape_.arraySize; }
  bool is3D() const { return shape_.dimension == RESOURCE_DIMENSION_TEXTURE3D; }
  // Width, height and (3D textures) depth of a mip level.
  VkExtent3D MipExtent(UINT mip) const;
  VkImageSubresourceLayers Layers(UINT subresource) const;

  // SetResourceMinLOD's clamp: set by the immediate context, read by deferred ones too.
  FLOAT minLod() const { return minLod_.load(std::memory_order_relaxed); }
  void SetMinLod(FLOAT minLod) { minLod_.store(minLod, std::memory_order_relaxed); }

  // STAGING textures live in a buffer, subresources packed one after another.
  bool isStaging() const { return shape_.usage == USAGE_STAGING; }
  VkBuffer stagingBuffer() const { return stagingBuffer_; }
  VkDeviceSize SubresourceOffset(UINT subresource) const { return subresourceOffsets_[subresource]; }
  UINT RowPitch(UINT subresource) const;
  // Bytes of one depth slice (of the whole subresource for 1D and 2D textures).
  UINT DepthPitch(UINT subresource) const;
  VkDeviceSize SubresourceSize(UINT subresource) const {
    return VkDeviceSize(DepthPitch(subresource)) * MipExtent(subresource % shape_.mipLevels).depth;
  }
  uint8_t* stagingData() const { return static_cast<uint8_t*>(mapped_); }

 private:
  HRESULT CreateImage(DeviceImpl& device);
  // Picks vkFormat_ for a texture used as depth-stencil; empty, or the reason there is none.
  std::string PickDepthImageFormat(const Gpu& gpu);
  // Empty when the device can create `info` with the shape's sample count, else the reason.
  std::string CheckSampleCount(const Gpu& gpu, const VkImageCreateInfo& info) const;
  // The VkFormats views of a typeless colour texture may use; empty when views keep the image's format.
  std::vector<VkFormat> FamilyViewFormats() const;
  HRESULT CreateStagingBuffer(DeviceImpl& device);

  DeviceImpl* device_ = nullptr;
  TextureShape shape_;
  VkFormat vkFormat_ = VK_FORMAT_UNDEFINED;
  VkImageAspectFlags aspects_ = 0;
  VkImage image_ = VK_NULL_HANDLE;
  VkBuffer stagingBuffer_ = VK_NULL_HANDLE;
  VkDeviceMemory memory_ = VK_NULL_HANDLE;
  void* mapped_ = nullptr;
  std::vector<VkDeviceSize> subresourceOffsets_;
  std::atomic<FLOAT> minLod_{0.0f};
};

template <class Interface, class Desc>
class TextureImpl final : public DeviceChildImpl<Interface>, public TextureStorage {
 public:
  TextureImpl(DeviceImpl* device, const Desc& desc) : DeviceChildImpl<Interface>(device), desc_(desc) {}
  void GetType(RESOURCE_DIMENSION* dimension) override { *dimension = shape().dimension; }
  // As D3D11: MipLevels 0 at creation ("the full chain") reads back as the count made.
  void GetDesc(Desc* desc) override {
    *desc = desc_;
    desc->MipLevels = shape().mipLevels;
  }

 private:
  Desc desc_;
};

using Texture1DImpl = TextureImpl<Texture1D, TEXTURE1D_DESC>;
using Texture2DImpl = TextureImpl<Texture2D, TEXTURE2D_DESC>;
using Texture3DImpl = TextureImpl<Texture3D, TEXTURE3D_DESC>;

// D3D11's rules for RESOURCE_MISC_TEXTURECUBE and RESOURCE_MISC_GENERATE_MIPS
// (texture_misc.cpp): empty, or the reason prefixed with `where`.
std::string CheckMiscFlags(const TextureShape& shape, const std::string& where);
// GenerateMips filters with linear blits: empty when `format` allows them.
std::string CheckMipGenerationFormat(const Gpu& gpu, const TextureShape& shape, VkFormat format, const char* call);

// The storage behind any texture resource, or null for buffers.
TextureStorage* AsTexture(Resource* resource);
BufferImpl* AsBuffer(Resource* resource);

}  // namespace rhi::vk
