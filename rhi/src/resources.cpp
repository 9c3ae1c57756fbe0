#include "resources.h"

#include <algorithm>
#include <bit>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "context.h"
#include "states/formats.h"
#include "vk_check.h"

namespace rhi::vk {

namespace {

// Creation records its uploads and layout changes into the immediate context:
// one creating thread at a time (the device is free-threaded).
template <class Record>
void UploadInitialData(DeviceImpl& device, Record&& record) {
  std::lock_guard lock(device.creationRecordingMutex());
  record(device.context());
}

std::string Hex(UINT value) {
  char text[16];
  std::snprintf(text, sizeof text, "0x%X", value);
  return text;
}

// D3D11's CreateBuffer rules (ID3D11Device::CreateBuffer, D3D11_BUFFER_DESC remarks).
std::string ValidateBufferDesc(const BUFFER_DESC& d, const SUBRESOURCE_DATA* initialData) {
  const std::string where = "CreateBuffer: ";
  if (d.ByteWidth == 0) return where + "ByteWidth is 0";
  if (d.Usage > USAGE_STAGING) return where + "Usage " + std::to_string(d.Usage) + " is not a D3D11_USAGE";
  constexpr UINT kKnownBinds = 0xFF;
  if (d.BindFlags & ~kKnownBinds) return where + "BindFlags " + Hex(d.BindFlags) + " has unknown bits";
  if (d.BindFlags & (BIND_RENDER_TARGET | BIND_DEPTH_STENCIL))
    return where + "buffers cannot be bound as render target or depth-stencil";
  if ((d.BindFlags & BIND_CONSTANT_BUFFER) && d.BindFlags != BIND_CONSTANT_BUFFER)
    return where + "BIND_CONSTANT_BUFFER cannot be combined with other bind flags";
  if ((d.BindFlags & BIND_CONSTANT_BUFFER) && (d.ByteWidth % 16 != 0 || d.ByteWidth > 65536))
    return where + "a constant buffer's ByteWidth (" + std::to_string(d.ByteWidth) +
           ") must be a multiple of 16 and at most 65536";
  if (d.CPUAccessFlags & ~(CPU_ACCESS_READ | CPU_ACCESS_WRITE))
    return where + "CPUAccessFlags " + Hex(d.CPUAccessFlags) + " has unknown bits";
  switch (d.Usage) {
    case USAGE_IMMUTABLE:
      if (!initialData || !initialData->pSysMem) return where + "USAGE_IMMUTABLE requires initial data";
      if (d.CPUAccessFlags) return where + "USAGE_IMMUTABLE does not allow CPU access";
      break;
    case USAGE_DYNAMIC:
      if (d.CPUAccessFlags != CPU_ACCESS_WRITE) return where + "USAGE_DYNAMIC requires CPUAccessFlags == CPU_ACCESS_WRITE";
      if (d.BindFlags & (BIND_STREAM_OUTPUT | BIND_UNORDERED_ACCESS))
        return where + "USAGE_DYNAMIC cannot be bound for stream output or unordered access";
      break;
    case USAGE_STAGING:
      if (d.BindFlags) return where + "USAGE_STAGING cannot have bind flags";
      if (!d.CPUAccessFlags) return where + "USAGE_STAGING requires CPU access flags";
      break;
    case USAGE_DEFAULT:
      if (d.CPUAccessFlags) return where + "USAGE_DEFAULT does not allow CPU access";
      break;
  }
  if (d.MiscFlags & RESOURCE_MISC_BUFFER_STRUCTURED) {
    if (d.StructureByteStride == 0 || d.StructureByteStride % 4 || d.StructureByteStride > 2048)
      return where + "StructureByteStride " + std::to_string(d.StructureByteStride) +
             " must be a non-zero multiple of 4 up to 2048 for a structured buffer";
    if (d.ByteWidth % d.StructureByteStride)
      return where + "ByteWidth must be a multiple of StructureByteStride for a structured buffer";
    if (d.MiscFlags & RESOURCE_MISC_BUFFER_ALLOW_RAW_VIEWS)
      return where + "a buffer cannot be both structured and raw";
  }
  return {};
}

VkBufferUsageFlags BufferUsage(const BUFFER_DESC& d, bool transformFeedback) {
  VkBufferUsageFlags usage = VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT;
  if (d.BindFlags & BIND_VERTEX_BUFFER) usage |= VK_BUFFER_USAGE_VERTEX_BUFFER_BIT;
  if (d.BindFlags & BIND_INDEX_BUFFER) usage |= VK_BUFFER_USAGE_INDEX_BUFFER_BIT;
  if (d.BindFlags & BIND_CONSTANT_BUFFER) usage |= VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT;
  if (d.BindFlags & BIND_SHADER_RESOURCE)
    usage |= VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT | VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
  if (d.BindFlags & BIND_UNORDERED_ACCESS)
    usage |= VK_BUFFER_USAGE_STORAGE_TEXEL_BUFFER_BIT | VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
  if (d.BindFlags & BIND_STREAM_OUTPUT) {
    usage |= VK_BUFFER_USAGE_VERTEX_BUFFER_BIT;
    if (transformFeedback) usage |= VK_BUFFER_USAGE_TRANSFORM_FEEDBACK_BUFFER_BIT_EXT;
  }
  if (d.MiscFlags & RESOURCE_MISC_DRAWINDIRECT_ARGS) usage |= VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT;
  return usage;
}

VkResult CreateBoundBuffer(Gpu& gpu, VkDeviceSize size, VkBufferUsageFlags usage, VkMemoryPropertyFlags memoryFlags,
                           VkBuffer* buffer, VkDeviceMemory* memory) {
  VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
  info.size = size;
  info.usage = usage;
  VkResult result = vkCreateBuffer(gpu.Device(), &info, nullptr, buffer);
  if (result != VK_SUCCESS) return result;
  VkMemoryRequirements requirements;
  vkGetBufferMemoryRequirements(gpu.Device(), *buffer, &requirements);
  result = gpu.AllocateFor(requirements, memoryFlags, memory);
  if (result == VK_SUCCESS) result = vkBindBufferMemory(gpu.Device(), *buffer, *memory, 0);
  return result;
}

VkMemoryPropertyFlags StagingMemoryFlags(const Gpu& gpu, UINT cpuAccess) {
  // Readback wants cached memory; fall back to coherent-only where the device has none.
  VkMemoryPropertyFlags flags = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
  if ((cpuAccess & CPU_ACCESS_READ) &&
      gpu.FindMemoryType(~0u, flags | VK_MEMORY_PROPERTY_HOST_CACHED_BIT) != UINT32_MAX)
    flags |= VK_MEMORY_PROPERTY_HOST_CACHED_BIT;
  return flags;
}

}  // namespace

// ---------------------------------------------------------------------------
// Buffers

HRESULT BufferImpl::Create(DeviceImpl* device, const BUFFER_DESC& desc, const SUBRESOURCE_DATA* initialData,
                           BufferImpl** out) {
  if (std::string reason = ValidateBufferDesc(desc, initialData); !reason.empty())
    return device->gpu().Refuse(reason);
  ComPtr<BufferImpl> buffer;
  buffer.Attach(new BufferImpl(device, desc));
  if (HRESULT hr = buffer->Initialize(initialData); FAILED(hr)) return hr;
  *out = buffer.Detach();
  return S_OK;
}

HRESULT BufferImpl::Initialize(const SUBRESOURCE_DATA* initialData) {
  Gpu& gpu = this->gpu();
  if (isDynamic()) {
    Rename();
    if (initialData && initialData->pSysMem) std::memcpy(slice_.data, initialData->pSysMem, desc_.ByteWidth);
    return S_OK;
  }
  VkMemoryPropertyFlags memoryFlags = isStaging() ? StagingMemoryFlags(gpu, desc_.CPUAccessFlags)
                                                  : VkMemoryPropertyFlags{VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT};
  VkResult result = CreateBoundBuffer(gpu, desc_.ByteWidth, BufferUsage(desc_, gpu.Caps().transformFeedback),
                                      memoryFlags, &buffer_, &memory_);
  if (result != VK_SUCCESS) return ToHresult(result);
  if (isStaging()) vkMapMemory(gpu.Device(), memory_, 0, VK_WHOLE_SIZE, 0, &mapped_);
  if (initialData && initialData->pSysMem) {
    if (isStaging())
      std::memcpy(mapped_, initialData->pSysMem, desc_.ByteWidth);
    else
      UploadInitialData(device(), [&](ContextImpl& context) {
        context.UploadBuffer(*this, 0, initialData->pSysMem, desc_.ByteWidth);
      });
  }
  return S_OK;
}

BufferImpl::~BufferImpl() {
  Gpu& gpu = this->gpu();
  if (isDynamic()) device().hostSlices().Release(slice_);
  VkDevice vkDevice = gpu.Device();
  VkBuffer buffer = buffer_;
  VkDeviceMemory memory = memory_;
  StreamOutCounter* counter = soCounter_.release();
  gpu.DeferDestroy([=] {
    vkDestroyBuffer(vkDevice, buffer, nullptr);
    vkFreeMemory(vkDevice, memory, nullptr);
    if (counter) {
      vkDestroyBuffer(vkDevice, counter->buffer, nullptr);
      vkFreeMemory(vkDevice, counter->memory, nullptr);
      delete counter;
    }
  });
}

void BufferImpl::Rename() {
  HostSliceAllocator& slices = device().hostSlices();
  slices.Release(slice_);
  // Constant buffers need the uniform offset alignment; 256 covers every device.
  slice_ = slices.Allocate(desc_.ByteWidth, 256);
}

StreamOutCounter& BufferImpl::soCounter() {
  if (!soCounter_) {
    soCounter_ = std::make_unique<StreamOutCounter>();
    VkBufferUsageFlags usage = VK_BUFFER_USAGE_TRANSFER_DST_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT |
                               VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT |
                               VK_BUFFER_USAGE_TRANSFORM_FEEDBACK_COUNTER_BUFFER_BIT_EXT;
    CreateBoundBuffer(gpu(), StreamOutCounter::kSize, usage, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT,
                      &soCounter_->buffer, &soCounter_->memory);
  }
  return *soCounter_;
}

BufferImpl* AsBuffer(Resource* resource) { return dynamic_cast<BufferImpl*>(resource); }
TextureStorage* AsTexture(Resource* resource) { return dynamic_cast<TextureStorage*>(resource); }

// ---------------------------------------------------------------------------
// Textures

namespace {

UINT FullMipCount(const TextureShape& s) { return std::bit_width(std::max({s.width, s.height, s.depth})); }

// D3D11's size limits: D3D11_REQ_TEXTURE1D_U_DIMENSION and _TEXTURE2D_U_OR_V_DIMENSION
// (16384), _TEXTURE3D_U_V_OR_W_DIMENSION (2048), _TEXTURE2D_ARRAY_AXIS_DIMENSION (2048).
std::string CheckSize(const TextureShape& s) {
  if (s.dimension == RESOURCE_DIMENSION_TEXTURE3D) {
    if (s.width == 0 || s.height == 0 || s.depth == 0 || s.width > 2048 || s.height > 2048 || s.depth > 2048)
      return "size " + std::to_string(s.width) + "x" + std::to_string(s.height) + "x" + std::to_string(s.depth) +
             " is outside 1..2048 (D3D11_REQ_TEXTURE3D_U_V_OR_W_DIMENSION)";
    return {};
  }
  if (s.width == 0 || s.height == 0 || s.width > 16384 || s.height > 16384)
    return "size " + std::to_string(s.width) + "x" + std::to_string(s.height) + " is outside 1..16384";
  if (s.arraySize == 0 || s.arraySize > 2048) return "ArraySize " + std::to_string(s.arraySize) + " is outside 1..2048";
  return {};
}

std::string ValidateTextureShape(const TextureShape& s, const SUBRESOURCE_DATA* initialData, const char* call) {
  const std::string where = std::string(call) + ": ";
  const auto* format = states::GetFormatInfo(s.format);
  if (!format) return where + "Format " + std::to_string(s.format) + " is not supported";
  if (std::string reason = CheckSize(s); !reason.empty()) return where + reason;
  if (s.mipLevels > FullMipCount(s))
    return where + "MipLevels " + std::to_string(s.mipLevels) + " exceeds the full chain of " +
           std::to_string(FullMipCount(s));
  // D3D11: volume textures cannot be depth-stencil targets, nor be stored in a depth format.
  if (s.dimension == RESOURCE_DIMENSION_TEXTURE3D && (s.bindFlags & BIND_DEPTH_STENCIL))
    return where + "a 3D texture cannot have BIND_DEPTH_STENCIL";
  if (s.dimension == RESOURCE_DIMENSION_TEXTURE3D && format->isDepth)
    return where + std::string(format->name) + " is a depth format, which 3D textures cannot have";
  if (!std::has_single_bit(s.samples) || s.samples > 32)
    return where + "SampleDesc.Count " + std::to_string(s.samples) + " is not a power of two up to 32";
  if (s.samples > 1 && s.mipLevels != 1) return where + "multisampled textures must have MipLevels 1";
  if (s.samples > 1 && s.usage != USAGE_DEFAULT) return where + "multisampled textures must be USAGE_DEFAULT";
  if (s.samples > 1 && (s.bindFlags & BIND_UNORDERED_ACCESS))
    return where + "multisampled textures cannot have BIND_UNORDERED_ACCESS";
  if (s.samples > 1 && initialData && initialData->pSysMem)
    return where + "multisampled textures cannot be initialized with data";
  // One quality level per supported count (CheckMultisampleQualityLevels): 0,
  // or the standard pattern, which Vulkan's standard sample locations are.
  if (s.sampleQuality != 0 && !(s.samples > 1 && s.sampleQuality == STANDARD_MULTISAMPLE_PATTERN))
    return where + "SampleDesc.Quality " + Hex(s.sampleQuality) + " is not available for SampleDesc.Count " +
           std::to_string(s.samples) +
           " (quality levels: 1, so Quality must be 0 or D3D11_STANDARD_MULTISAMPLE_PATTERN for counts above 1)";
  if (s.bindFlags & (BIND_VERTEX_BUFFER | BIND_INDEX_BUFFER | BIND_CONSTANT_BUFFER | BIND_STREAM_OUTPUT))
    return where + "textures cannot be bound as vertex, index, constant or stream-output buffers";
  if ((s.bindFlags & BIND_DEPTH_STENCIL) && !format->isDepth && format->kind != states::ComponentKind::Typeless)
    return where + "BIND_DEPTH_STENCIL needs a depth or typeless format";
  // D3D11: block-compressed textures are shader resources only (and staging copies).
  if (format->blockSize > 1 && (s.bindFlags & ~BIND_SHADER_RESOURCE))
    return where + std::string(format->name) + " textures can only have BIND_SHADER_RESOURCE (BindFlags " +
           Hex(s.bindFlags) + ")";
  if (format->blockSize > 1 && s.samples > 1)
    return where + std::string(format->name) + " textures cannot be multisampled";
  if ((s.bindFlags & BIND_RENDER_TARGET) && format->isDepth)
    return where + "BIND_RENDER_TARGET cannot use a depth format";
  // D3D11: a depth format cannot be read by shaders; a depth buffer that is
  // also a shader resource is created typeless and viewed through typed views.
  if ((s.bindFlags & BIND_SHADER_RESOURCE) && format->kind == states::ComponentKind::Depth)
    return where + "BIND_SHADER_RESOURCE cannot use " + format->name +
           "; create the texture with its typeless format (R32_TYPELESS, R24G8_TYPELESS, R16_TYPELESS) and view "
           "it through a depth-stencil view and a shader-resource view";
  if (s.usage == USAGE_IMMUTABLE && (!initialData || !initialData->pSysMem))
    return where + "USAGE_IMMUTABLE requires initial data";
  if (s.usage == USAGE_STAGING && s.bindFlags) return where + "USAGE_STAGING cannot have bind flags";
  if (s.usage == USAGE_DYNAMIC)
    return where + "USAGE_DYNAMIC textures are not supported by this backend (use DEFAULT + UpdateSubresource)";
  return CheckMiscFlags(s, where);
}

VkImageUsageFlags ImageUsage(const TextureShape& s, bool depth) {
  VkImageUsageFlags usage = VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
  if (s.bindFlags & BIND_SHADER_RESOURCE) usage |= VK_IMAGE_USAGE_SAMPLED_BIT;
  if (s.bindFlags & BIND_RENDER_TARGET) usage |= VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT;
  if (s.bindFlags & BIND_DEPTH_STENCIL) usage |= VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT;
  if (s.bindFlags & BIND_UNORDERED_ACCESS) usage |= VK_IMAGE_USAGE_STORAGE_BIT;
  (void)depth;
  return usage;
}

}  // namespace

TextureStorage::~TextureStorage() {
  if (!device_) return;
  VkDevice vkDevice = device_->gpu().Device();
  VkImage image = image_;
  VkBuffer buffer = stagingBuffer_;
  VkDeviceMemory memory = memory_;
  device_->gpu().DeferDestroy([=] {
    vkDestroyImage(vkDevice, image, nullptr);
    vkDestroyBuffer(vkDevice, buffer, nullptr);
    vkFreeMemory(vkDevice, memory, nullptr);
  });
}

HRESULT TextureStorage::Initialize(DeviceImpl& device, const TextureShape& shape,
                                   const SUBRESOURCE_DATA* initialData) {
  shape_ = shape;
  if (shape_.mipLevels == 0) shape_.mipLevels = FullMipCount(shape_);
  const char* call = CreateCallName(shape.dimension);
  if (std::string reason = ValidateTextureShape(shape_, initialData, call); !reason.empty())
    return device.gpu().Refuse(reason);
  const auto* format = states::GetFormatInfo(shape_.format);
  const bool depth = format->isDepth || (shape_.bindFlags & BIND_DEPTH_STENCIL);
  vkFormat_ = format->vkFormat;
  if (depth) {
    if (std::string reason = PickDepthImageFormat(device.gpu()); !reason.empty())
      return device.gpu().Refuse(std::string(call) + ": " + reason);
  }
  if (std::string reason = CheckMipGenerationFormat(device.gpu(), shape_, vkFormat_, call); !reason.empty())
    return device.gpu().Refuse(reason);
  aspects_ = depth ? VK_IMAGE_ASPECT_DEPTH_BIT : VK_IMAGE_ASPECT_COLOR_BIT;
  if (depth && (vkFormat_ == VK_FORMAT_D24_UNORM_S8_UINT || vkFormat_ == VK_FORMAT_D32_SFLOAT_S8_UINT ||
                vkFormat_ == VK_FORMAT_D16_UNORM_S8_UINT))
    aspects_ |= VK_IMAGE_ASPECT_STENCIL_BIT;
  if (format->blockSize > 1 && !isStaging() &&
      !device.gpu().IsFormatSupported(vkFormat_, VK_FORMAT_FEATURE_2_SAMPLED_IMAGE_BIT))
    return device.gpu().Refuse(std::string(call) + ": " + device.gpu().AdapterName() + " cannot sample " +
                               format->name + " (the device lacks textureCompressionBC)");
  device_ = &device;
  HRESULT hr = isStaging() ? CreateStagingBuffer(device) : CreateImage(device);
  if (FAILED(hr) || !initialData || !initialData->pSysMem) return hr;
  UploadInitialData(device, [&](ContextImpl& context) {
    for (UINT sub = 0; sub < subresourceCount(); ++sub) {
      const SUBRESOURCE_DATA& data = initialData[sub];
      context.UploadTexture(*this, sub, nullptr, data.pSysMem, data.SysMemPitch, data.SysMemSlicePitch);
    }
  });
  return S_OK;
}

std::vector<VkFormat> TextureStorage::FamilyViewFormats() const {
  const auto* format = states::GetFormatInfo(shape_.format);
  if (format->kind != states::ComponentKind::Typeless || (aspects_ & VK_IMAGE_ASPECT_DEPTH_BIT)) return {};
  std::vector<VkFormat> formats{vkFormat_};
  for (const states::FormatInfo& member : states::AllFormats())
    if (member.family == shape_.format && !member.isDepth && member.kind != states::ComponentKind::Typeless &&
        std::find(formats.begin(), formats.end(), member.vkFormat) == formats.end())
      formats.push_back(member.vkFormat);
  return formats;
}

HRESULT TextureStorage::CreateImage(DeviceImpl& device) {
  Gpu& gpu = device.gpu();
  VkImageCreateInfo info{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
  info.imageType = shape_.dimension == RESOURCE_DIMENSION_TEXTURE1D   ? VK_IMAGE_TYPE_1D
                   : shape_.dimension == RESOURCE_DIMENSION_TEXTURE3D ? VK_IMAGE_TYPE_3D
                                                                      : VK_IMAGE_TYPE_2D;
  info.format = vkFormat_;
  info.extent = {shape_.width, shape_.height, shape_.depth};
  info.mipLevels = shape_.mipLevels;
  info.arrayLayers = shape_.arraySize;
  info.samples = static_cast<VkSampleCountFlagBits>(shape_.samples);
  info.tiling = VK_IMAGE_TILING_OPTIMAL;
  info.usage = ImageUsage(shape_, aspects_ & VK_IMAGE_ASPECT_DEPTH_BIT);
  info.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  if (shape_.miscFlags & RESOURCE_MISC_TEXTURECUBE) info.flags |= VK_IMAGE_CREATE_CUBE_COMPATIBLE_BIT;
  // A 3D render-target view is a 2D-array view whose layers are W slices.
  if (is3D() && (shape_.bindFlags & BIND_RENDER_TARGET)) info.flags |= VK_IMAGE_CREATE_2D_ARRAY_COMPATIBLE_BIT;
  // Only views of typeless colour resources reinterpret the format (D3D11's
  // IsViewCompatible rule); listing the family lets drivers keep render-target
  // compression, which an unrestricted MUTABLE_FORMAT image may lose.
  const std::vector<VkFormat> viewFormats = FamilyViewFormats();
  VkImageFormatListCreateInfo formatList{VK_STRUCTURE_TYPE_IMAGE_FORMAT_LIST_CREATE_INFO};
  if (!viewFormats.empty()) {
    info.flags |= VK_IMAGE_CREATE_MUTABLE_FORMAT_BIT;
    formatList.viewFormatCount = static_cast<uint32_t>(viewFormats.size());
    formatList.pViewFormats = viewFormats.data();
    info.pNext = &formatList;
  }
  if (std::string reason = CheckSampleCount(gpu, info); !reason.empty()) return gpu.Refuse(reason);
  VkResult result = vkCreateImage(gpu.Device(), &info, nullptr, &image_);
  if (result != VK_SUCCESS)
    return gpu.Refuse(std::string("vkCreateImage failed for this texture: ") + ResultName(result));
  VkMemoryRequirements requirements;
  vkGetImageMemoryRequirements(gpu.Device(), image_, &requirements);
  result = gpu.AllocateFor(requirements, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, &memory_);
  if (result == VK_SUCCESS) result = vkBindImageMemory(gpu.Device(), image_, memory_, 0);
  if (result != VK_SUCCESS) return ToHresult(result);
  UploadInitialData(device, [&](ContextImpl& context) { context.InitializeImageLayout(*this); });
  return S_OK;
}

std::string TextureStorage::PickDepthImageFormat(const Gpu& gpu) {
  // Depth formats fall back (D24S8 -> D32S8) where the device lacks them; a
  // depth buffer that shaders read must also be sampleable.
  VkFormatFeatureFlags2 needed = VK_FORMAT_FEATURE_2_DEPTH_STENCIL_ATTACHMENT_BIT;
  if (shape_.bindFlags & BIND_SHADER_RESOURCE) needed |= VK_FORMAT_FEATURE_2_SAMPLED_IMAGE_BIT;
  vkFormat_ = states::PickDepthFormat(shape_.format, [&](VkFormat f) { return gpu.IsFormatSupported(f, needed); });
  if (vkFormat_ != VK_FORMAT_UNDEFINED) return {};
  std::string tried;
  for (VkFormat candidate : states::DepthFormatCandidates(shape_.format))
    tried += (tried.empty() ? "VkFormat " : ", ") + std::to_string(candidate);
  return gpu.AdapterName() + " has no depth format for " + states::FormatName(shape_.format) +
         ((shape_.bindFlags & BIND_SHADER_RESOURCE) ? " that is both a depth-stencil attachment and sampled"
                                                    : " as a depth-stencil attachment") +
         " (tried " + (tried.empty() ? std::string("none") : tried) + ")";
}

namespace {

std::string SampleCountList(VkSampleCountFlags counts) {
  std::string list;
  for (VkSampleCountFlags bit = 1; bit <= counts; bit <<= 1)
    if (counts & bit) list += (list.empty() ? "" : ", ") + std::to_string(bit);
  return list.empty() ? "none" : list;
}

}  // namespace

std::string TextureStorage::CheckSampleCount(const Gpu& gpu, const VkImageCreateInfo& info) const {
  // D3D11 refuses a count CheckMultisampleQualityLevels reports 0 levels for;
  // Vulkan decides per format, usage and flags, so the image's own are asked.
  const VkSampleCountFlags counts = gpu.ImageSampleCounts(info);
  if (counts & info.samples) return {};
  const char* call = CreateCallName(shape_.dimension);
  if (counts == 0)
    return std::string(call) + ": " + gpu.AdapterName() + " cannot create a " + states::FormatName(shape_.format) +
           " texture with BindFlags " + Hex(shape_.bindFlags) + " at any sample count";
  return std::string(call) + ": SampleDesc.Count " + std::to_string(shape_.samples) + " is not supported for " +
         states::FormatName(shape_.format) + " with BindFlags " + Hex(shape_.bindFlags) + " on " +
         gpu.AdapterName() + " (supported counts: " + SampleCountList(counts) +
         "; CheckMultisampleQualityLevels reports 0 quality levels)";
}

VkSampleCountFlags TargetSampleCounts(const Gpu& gpu, DXGI_FORMAT format) {
  const auto* info = states::GetFormatInfo(format);
  if (!info || info->kind == states::ComponentKind::Typeless) return 0;
  VkImageCreateInfo image{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
  image.imageType = VK_IMAGE_TYPE_2D;
  image.tiling = VK_IMAGE_TILING_OPTIMAL;
  image.format = info->vkFormat;
  image.usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT;
  if (info->kind == states::ComponentKind::Depth) {
    image.format = states::PickDepthFormat(format, [&](VkFormat f) {
      return gpu.IsFormatSupported(f, VK_FORMAT_FEATURE_2_DEPTH_STENCIL_ATTACHMENT_BIT);
    });
    image.usage = VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT;
  } else if (!(info->bindFlags & BIND_RENDER_TARGET)) {
    return 0;
  }
  return image.format == VK_FORMAT_UNDEFINED ? 0 : gpu.ImageSampleCounts(image);
}

HRESULT TextureStorage::CreateStagingBuffer(DeviceImpl& device) {
  VkDeviceSize total = 0;
  for (UINT sub = 0; sub < subresourceCount(); ++sub) {
    subresourceOffsets_.push_back(total);
    total += (SubresourceSize(sub) + 15) / 16 * 16;
  }
  VkResult result = CreateBoundBuffer(device.gpu(), total,
                                      VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                      StagingMemoryFlags(device.gpu(), shape_.cpuAccessFlags), &stagingBuffer_,
                                      &memory_);
  if (result != VK_SUCCESS) return ToHresult(result);
  vkMapMemory(device.gpu().Device(), memory_, 0, VK_WHOLE_SIZE, 0, &mapped_);
  return S_OK;
}

VkExtent3D TextureStorage::MipExtent(UINT mip) const {
  return {std::max(1u, shape_.width >> mip), std::max(1u, shape_.height >> mip), std::max(1u, shape_.depth >> mip)};
}

const char* CreateCallName(RESOURCE_DIMENSION dimension) {
  switch (dimension) {
    case RESOURCE_DIMENSION_TEXTURE1D: return "CreateTexture1D";
    case RESOURCE_DIMENSION_TEXTURE3D: return "CreateTexture3D";
    default: return "CreateTexture2D";
  }
}

VkImageSubresourceLayers TextureStorage::Layers(UINT subresource) const {
  VkImageSubresourceLayers layers{};
  // Copies address depth and stencil separately; D3D11 subresources mean both.
  layers.aspectMask = aspects_;
  layers.mipLevel = subresource % shape_.mipLevels;
  layers.baseArrayLayer = subresource / shape_.mipLevels;
  layers.layerCount = 1;
  return layers;
}

UINT TextureStorage::RowPitch(UINT subresource) const {
  return states::RowPitchBytes(*states::GetFormatInfo(shape_.format), MipExtent(subresource % shape_.mipLevels).width);
}

UINT TextureStorage::DepthPitch(UINT subresource) const {
  return RowPitch(subresource) *
         states::RowCount(*states::GetFormatInfo(shape_.format), MipExtent(subresource % shape_.mipLevels).height);
}

}  // namespace rhi::vk
