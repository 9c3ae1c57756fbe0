#include "views.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "states/formats.h"
#include "vk_check.h"

namespace rhi::vk {

ViewTarget::~ViewTarget() {
  if (!device_) return;
  VkDevice vkDevice = device_->gpu().Device();
  VkImageView imageView = imageView_;
  VkBufferView bufferView = bufferView_;
  std::vector<std::pair<FLOAT, VkImageView>> variants = std::move(minLodViews_);
  device_->gpu().DeferDestroy([=] {
    vkDestroyImageView(vkDevice, imageView, nullptr);
    vkDestroyBufferView(vkDevice, bufferView, nullptr);
    for (const auto& variant : variants) vkDestroyImageView(vkDevice, variant.second, nullptr);
  });
}

VkDescriptorBufferInfo ViewTarget::bufferRange() const {
  return {buffer_->handle(), buffer_->baseOffset() + firstByte_, byteCount_};
}

void ViewTarget::Hold(Resource* resource) {
  resource_ = resource;
  resourceHold_ = Bound<Bindable>(dynamic_cast<Bindable*>(resource));
}

namespace {

// The D3D11 binding a view format must support for a view of this Vulkan usage.
struct ViewBinding {
  UINT flag;
  const char* name;
};
ViewBinding ViewBindingOf(VkImageUsageFlags usage) {
  switch (usage) {
    case VK_IMAGE_USAGE_SAMPLED_BIT: return {BIND_SHADER_RESOURCE, "BIND_SHADER_RESOURCE"};
    case VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT: return {BIND_RENDER_TARGET, "BIND_RENDER_TARGET"};
    case VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT: return {BIND_DEPTH_STENCIL, "BIND_DEPTH_STENCIL"};
    default: return {BIND_UNORDERED_ACCESS, "BIND_UNORDERED_ACCESS"};
  }
}

// D3D11: the *MS view dimensions are for multisampled textures and only they.
std::string CheckSampleDimension(Resource* resource, bool multisampledView, const char* call) {
  const TextureStorage* texture = AsTexture(resource);
  if (!texture || (texture->shape().samples > 1) == multisampledView) return {};
  return std::string(call) + ": " +
         (multisampledView ? "a *_TEXTURE2DMS* ViewDimension needs a multisampled texture (SampleDesc.Count > 1)"
                           : "a multisampled texture (SampleDesc.Count " + std::to_string(texture->shape().samples) +
                                 ") needs a *_TEXTURE2DMS or *_TEXTURE2DMSARRAY ViewDimension");
}

}  // namespace

HRESULT ViewTarget::InitTexture(DeviceImpl& device, Resource* resource, DXGI_FORMAT format, VkImageViewType type,
                                VkImageSubresourceRange range, VkImageUsageFlags usage, const char* call) {
  Gpu& gpu = device.gpu();
  TextureStorage* texture = AsTexture(resource);
  if (!texture || texture->isStaging())
    return gpu.Refuse(std::string(call) + ": the resource must be a non-staging texture");
  const TextureShape& shape = texture->shape();
  if (format == DXGI_FORMAT_UNKNOWN) format = shape.format;
  const auto* info = states::GetFormatInfo(format);
  if (!info || info->kind == states::ComponentKind::Typeless)
    return gpu.Refuse(std::string(call) + ": view format " + std::to_string(format) + " must be a typed format");
  if (const ViewBinding binding = ViewBindingOf(usage); !(info->bindFlags & binding.flag))
    return gpu.Refuse(std::string(call) + ": " + info->name + " cannot be the format of this kind of view (it does not "
                      "support " + binding.name + ")" +
                      (info->kind == states::ComponentKind::Depth
                           ? "; shaders read a depth texture through R32_FLOAT, R24_UNORM_X8_TYPELESS or R16_UNORM"
                           : ""));
  if (!states::IsViewCompatible(shape.format, format))
    return gpu.Refuse(std::string(call) + ": view format " + info->name + " cannot view a resource of format " +
                      states::FormatName(shape.format) +
                      " (a typed resource takes only its own format, a typeless one the members of its family)");
  // The layers of a 2D-array view of a 3D texture (a TEXTURE3D render-target view) are its W slices.
  const UINT layers = type == VK_IMAGE_VIEW_TYPE_2D_ARRAY && texture->is3D()
                          ? texture->MipExtent(std::min(range.baseMipLevel, shape.mipLevels - 1)).depth
                          : shape.arraySize;
  if (range.baseMipLevel >= shape.mipLevels || range.levelCount == 0 ||
      range.levelCount > shape.mipLevels - range.baseMipLevel || range.baseArrayLayer >= layers ||
      range.layerCount == 0 || range.layerCount > layers - range.baseArrayLayer)
    return gpu.Refuse(std::string(call) + ": mip or array range outside the texture (mips " +
                      std::to_string(range.baseMipLevel) + "+" + std::to_string(range.levelCount) + " of " +
                      std::to_string(shape.mipLevels) + ", slices " + std::to_string(range.baseArrayLayer) + "+" +
                      std::to_string(range.layerCount) + " of " + std::to_string(layers) + ")");
  device_ = &device;
  Hold(resource);
  texture_ = texture;
  format_ = format;
  range_ = range;

  usageInfo_ = {VK_STRUCTURE_TYPE_IMAGE_VIEW_USAGE_CREATE_INFO};
  usageInfo_.usage = usage;
  viewInfo_ = {VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
  viewInfo_.image = texture->image();
  viewInfo_.viewType = type;
  // Depth images can only be viewed in their own format; colour views may
  // reinterpret within the typeless family.
  viewInfo_.format = (texture->aspects() & VK_IMAGE_ASPECT_DEPTH_BIT)
                        ? texture->vkFormat()
                        : info->vkFormat;
  viewInfo_.components = states::ToVkComponentMapping(info->swizzle);
  viewInfo_.subresourceRange = range;
  VkImageViewCreateInfo viewInfo = viewInfo_;
  viewInfo.pNext = &usageInfo_;
  VkResult result = vkCreateImageView(gpu.Device(), &viewInfo, nullptr, &imageView_);
  return ToHresult(result);
}

VkImageView ViewTarget::SampledImageView() {
  if (!texture_ || texture_->minLod() <= FLOAT(range_.baseMipLevel)) return imageView_;
  const FLOAT minLod = texture_->minLod();
  const UINT lastLevel = range_.baseMipLevel + range_.levelCount - 1;
  if (minLod > FLOAT(lastLevel)) return VK_NULL_HANDLE;  // D3D11: an empty set of levels reads as out of bounds
  for (const auto& [lod, view] : minLodViews_)
    if (lod == minLod) return view;
  Gpu& gpu = device_->gpu();
  VkImageViewCreateInfo info = viewInfo_;
  info.pNext = &usageInfo_;
  VkImageViewMinLodCreateInfoEXT minLodInfo{VK_STRUCTURE_TYPE_IMAGE_VIEW_MIN_LOD_CREATE_INFO_EXT};
  if (gpu.Caps().imageViewMinLod) {
    // The clamp is in the image's levels, as D3D11's MinLOD is in the resource's.
    minLodInfo.minLod = minLod;
    usageInfo_.pNext = &minLodInfo;
  } else {
    // Without VK_EXT_image_view_min_lod the view starts at the first level the clamp
    // allows: whole levels only (a fractional MinLOD rounds up; the levels' sizes and
    // Load's mip indices then count from that level).
    const UINT first = UINT(std::ceil(minLod));
    info.subresourceRange.baseMipLevel = first;
    info.subresourceRange.levelCount = lastLevel + 1 - first;
  }
  VkImageView view = VK_NULL_HANDLE;
  const VkResult result = vkCreateImageView(gpu.Device(), &info, nullptr, &view);
  usageInfo_.pNext = nullptr;
  if (result != VK_SUCCESS) return imageView_;
  // A streaming system moves the clamp in small steps: keep the latest few variants
  // (destroyed once the GPU is done with commands recorded so far).
  constexpr size_t kKeptVariants = 4;
  if (minLodViews_.size() == kKeptVariants) {
    VkDevice vkDevice = gpu.Device();
    VkImageView oldest = minLodViews_.front().second;
    gpu.DeferDestroy([=] { vkDestroyImageView(vkDevice, oldest, nullptr); });
    minLodViews_.erase(minLodViews_.begin());
  }
  minLodViews_.emplace_back(minLod, view);
  return view;
}

HRESULT ViewTarget::InitBuffer(DeviceImpl& device, Resource* resource, DXGI_FORMAT format, UINT firstElement,
                               UINT numElements, bool storage, const char* call) {
  Gpu& gpu = device.gpu();
  BufferImpl* buffer = AsBuffer(resource);
  if (!buffer) return gpu.Refuse(std::string(call) + ": the resource must be a buffer");
  const BUFFER_DESC& desc = buffer->desc();
  UINT elementSize = desc.StructureByteStride;
  if (!(desc.MiscFlags & RESOURCE_MISC_BUFFER_STRUCTURED)) {
    const auto* info = states::GetFormatInfo(format);
    if (!info) return gpu.Refuse(std::string(call) + ": a typed or raw buffer view needs a format");
    elementSize = info->bytesPerElement;
  }
  const VkDeviceSize first = VkDeviceSize(firstElement) * elementSize;
  const VkDeviceSize count = VkDeviceSize(numElements) * elementSize;
  if (numElements == 0 || first + count > desc.ByteWidth)
    return gpu.Refuse(std::string(call) + ": elements " + std::to_string(firstElement) + "+" +
                      std::to_string(numElements) + " lie outside the buffer");
  device_ = &device;
  Hold(resource);
  buffer_ = buffer;
  format_ = format;
  firstByte_ = first;
  byteCount_ = count;
  // Typed views of non-dynamic buffers also get a texel-buffer view.
  const auto* info = states::GetFormatInfo(format);
  if (!(desc.MiscFlags & RESOURCE_MISC_BUFFER_STRUCTURED) && format != DXGI_FORMAT_R32_TYPELESS && info &&
      !buffer->isDynamic()) {
    VkBufferViewCreateInfo viewInfo{VK_STRUCTURE_TYPE_BUFFER_VIEW_CREATE_INFO};
    viewInfo.buffer = buffer->handle();
    viewInfo.format = info->vkFormat;
    viewInfo.offset = first;
    viewInfo.range = count;
    (void)storage;
    return ToHresult(vkCreateBufferView(gpu.Device(), &viewInfo, nullptr, &bufferView_));
  }
  return S_OK;
}

namespace {

VkImageViewType ViewType(UINT dimension, bool isArray, bool cube) {
  // A 3D texture's W slices are the layers of its render-target views' 2D arrays.
  if (dimension == RESOURCE_DIMENSION_TEXTURE3D) return isArray ? VK_IMAGE_VIEW_TYPE_2D_ARRAY : VK_IMAGE_VIEW_TYPE_3D;
  if (cube) return isArray ? VK_IMAGE_VIEW_TYPE_CUBE_ARRAY : VK_IMAGE_VIEW_TYPE_CUBE;
  if (dimension == RESOURCE_DIMENSION_TEXTURE1D) return isArray ? VK_IMAGE_VIEW_TYPE_1D_ARRAY : VK_IMAGE_VIEW_TYPE_1D;
  return isArray ? VK_IMAGE_VIEW_TYPE_2D_ARRAY : VK_IMAGE_VIEW_TYPE_2D;
}

VkImageAspectFlags ColorOrDepth(const TextureStorage& texture) {
  return (texture.aspects() & VK_IMAGE_ASPECT_DEPTH_BIT) ? VK_IMAGE_ASPECT_DEPTH_BIT : VK_IMAGE_ASPECT_COLOR_BIT;
}

// The one aspect a shader-resource view of `format` reads: a depth image's
// stencil for the stencil formats (X24_TYPELESS_G8_UINT), else its depth.
VkImageAspectFlags ReadAspect(const TextureStorage& texture, DXGI_FORMAT format) {
  const auto* info = states::GetFormatInfo(format == DXGI_FORMAT_UNKNOWN ? texture.shape().format : format);
  const bool stencil = info && info->hasStencil && !info->isDepth;
  return stencil && (texture.aspects() & VK_IMAGE_ASPECT_STENCIL_BIT) ? VK_IMAGE_ASPECT_STENCIL_BIT
                                                                       : ColorOrDepth(texture);
}

// D3D11: a TEXTURE3D view dimension is for 3D textures, and 3D textures take no other.
std::string CheckVolumeDimension(const TextureStorage* texture, bool volumeView, const char* call) {
  if (!texture || texture->is3D() == volumeView) return {};
  return std::string(call) + ": " +
         (volumeView ? "a *_TEXTURE3D ViewDimension needs a 3D texture"
                     : "a 3D texture needs a *_TEXTURE3D ViewDimension");
}

// D3D11's WSize -1: every W slice of the mip from FirstWSlice on.
UINT WSliceCount(const TextureStorage* texture, UINT mip, UINT firstWSlice, UINT wSize) {
  if (wSize != UINT(-1) || !texture) return wSize;
  const UINT depth = texture->MipExtent(std::min(mip, texture->shape().mipLevels - 1)).depth;
  return firstWSlice < depth ? depth - firstWSlice : 0;
}

}  // namespace

// ---------------------------------------------------------------------------
// Shader resource views

template <>
HRESULT ShaderResourceViewImpl::Initialize(Resource* resource) {
  DeviceImpl& dev = device();
  const auto& d = desc_;
  switch (d.ViewDimension) {
    case SRV_DIMENSION_BUFFER:
      return InitBuffer(dev, resource, d.Format, d.Buffer.FirstElement, d.Buffer.NumElements, false,
                        "CreateShaderResourceView");
    case SRV_DIMENSION_BUFFEREX:
      return InitBuffer(dev, resource, d.Format, d.BufferEx.FirstElement, d.BufferEx.NumElements, false,
                        "CreateShaderResourceView");
    default: break;
  }
  TextureStorage* texture = AsTexture(resource);
  if (!texture) return dev.gpu().Refuse("CreateShaderResourceView: ViewDimension does not match a buffer");
  if (!(texture->shape().bindFlags & BIND_SHADER_RESOURCE))
    return dev.gpu().Refuse("CreateShaderResourceView: the texture lacks BIND_SHADER_RESOURCE");
  const bool multisampledView =
      d.ViewDimension == SRV_DIMENSION_TEXTURE2DMS || d.ViewDimension == SRV_DIMENSION_TEXTURE2DMSARRAY;
  if (std::string reason = CheckSampleDimension(resource, multisampledView, "CreateShaderResourceView");
      !reason.empty())
    return dev.gpu().Refuse(reason);
  VkImageSubresourceRange range{ReadAspect(*texture, d.Format), 0, 1, 0, 1};
  bool isArray = false, cube = false;
  switch (d.ViewDimension) {
    case SRV_DIMENSION_TEXTURE1D:
    case SRV_DIMENSION_TEXTURE2D:
      range.baseMipLevel = d.Texture2D.MostDetailedMip;
      range.levelCount = d.Texture2D.MipLevels;
      break;
    case SRV_DIMENSION_TEXTURE1DARRAY:
    case SRV_DIMENSION_TEXTURE2DARRAY:
      range.baseMipLevel = d.Texture2DArray.MostDetailedMip;
      range.levelCount = d.Texture2DArray.MipLevels;
      range.baseArrayLayer = d.Texture2DArray.FirstArraySlice;
      range.layerCount = d.Texture2DArray.ArraySize;
      isArray = true;
      break;
    case SRV_DIMENSION_TEXTURE2DMS: break;
    case SRV_DIMENSION_TEXTURE2DMSARRAY:
      range.baseArrayLayer = d.Texture2DMSArray.FirstArraySlice;
      range.layerCount = d.Texture2DMSArray.ArraySize;
      isArray = true;
      break;
    case SRV_DIMENSION_TEXTURE3D:
      range.baseMipLevel = d.Texture3D.MostDetailedMip;
      range.levelCount = d.Texture3D.MipLevels;
      break;
    case SRV_DIMENSION_TEXTURECUBE:
      range.baseMipLevel = d.TextureCube.MostDetailedMip;
      range.levelCount = d.TextureCube.MipLevels;
      range.layerCount = 6;
      cube = true;
      break;
    case SRV_DIMENSION_TEXTURECUBEARRAY:
      range.baseMipLevel = d.TextureCubeArray.MostDetailedMip;
      range.levelCount = d.TextureCubeArray.MipLevels;
      range.baseArrayLayer = d.TextureCubeArray.First2DArrayFace;
      range.layerCount = d.TextureCubeArray.NumCubes * 6;
      cube = isArray = true;
      break;
    default:
      return dev.gpu().Refuse("CreateShaderResourceView: ViewDimension " + std::to_string(d.ViewDimension) +
                              " is not supported");
  }
  if (std::string reason =
          CheckVolumeDimension(texture, d.ViewDimension == SRV_DIMENSION_TEXTURE3D, "CreateShaderResourceView");
      !reason.empty())
    return dev.gpu().Refuse(reason);
  // D3D11: MipLevels -1 means "all remaining".
  if (range.levelCount == UINT(-1) && range.baseMipLevel < texture->shape().mipLevels)
    range.levelCount = texture->shape().mipLevels - range.baseMipLevel;
  if (cube && !(texture->shape().miscFlags & RESOURCE_MISC_TEXTURECUBE))
    return dev.gpu().Refuse("CreateShaderResourceView: a TEXTURECUBE or TEXTURECUBEARRAY view needs a texture "
                            "created with RESOURCE_MISC_TEXTURECUBE");
  return InitTexture(dev, resource, d.Format, ViewType(texture->shape().dimension, isArray, cube), range,
                     VK_IMAGE_USAGE_SAMPLED_BIT, "CreateShaderResourceView");
}

// ---------------------------------------------------------------------------
// Render target and depth-stencil views

template <>
HRESULT RenderTargetViewImpl::Initialize(Resource* resource) {
  const auto& d = desc_;
  VkImageSubresourceRange range{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
  bool isArray = false;
  switch (d.ViewDimension) {
    case RTV_DIMENSION_TEXTURE1D:
    case RTV_DIMENSION_TEXTURE2D: range.baseMipLevel = d.Texture2D.MipSlice; break;
    case RTV_DIMENSION_TEXTURE1DARRAY:
    case RTV_DIMENSION_TEXTURE2DARRAY:
      range.baseMipLevel = d.Texture2DArray.MipSlice;
      range.baseArrayLayer = d.Texture2DArray.FirstArraySlice;
      range.layerCount = d.Texture2DArray.ArraySize;
      isArray = true;
      break;
    case RTV_DIMENSION_TEXTURE2DMS: break;
    case RTV_DIMENSION_TEXTURE2DMSARRAY:
      range.baseArrayLayer = d.Texture2DMSArray.FirstArraySlice;
      range.layerCount = d.Texture2DMSArray.ArraySize;
      isArray = true;
      break;
    case RTV_DIMENSION_TEXTURE3D:
      // W slices as array layers (SV_RenderTargetArrayIndex picks one).
      range.baseMipLevel = d.Texture3D.MipSlice;
      range.baseArrayLayer = d.Texture3D.FirstWSlice;
      range.layerCount =
          WSliceCount(AsTexture(resource), d.Texture3D.MipSlice, d.Texture3D.FirstWSlice, d.Texture3D.WSize);
      isArray = true;
      break;
    default:
      return device().gpu().Refuse("CreateRenderTargetView: ViewDimension " + std::to_string(d.ViewDimension) +
                                   " is not supported");
  }
  TextureStorage* texture = AsTexture(resource);
  if (std::string reason =
          CheckVolumeDimension(texture, d.ViewDimension == RTV_DIMENSION_TEXTURE3D, "CreateRenderTargetView");
      !reason.empty())
    return device().gpu().Refuse(reason);
  if (texture && !(texture->shape().bindFlags & BIND_RENDER_TARGET))
    return device().gpu().Refuse("CreateRenderTargetView: the texture lacks BIND_RENDER_TARGET");
  const bool multisampledView =
      d.ViewDimension == RTV_DIMENSION_TEXTURE2DMS || d.ViewDimension == RTV_DIMENSION_TEXTURE2DMSARRAY;
  if (std::string reason = CheckSampleDimension(resource, multisampledView, "CreateRenderTargetView");
      !reason.empty())
    return device().gpu().Refuse(reason);
  RESOURCE_DIMENSION dimension = texture ? texture->shape().dimension : RESOURCE_DIMENSION_TEXTURE2D;
  return InitTexture(device(), resource, d.Format, ViewType(dimension, isArray, false), range,
                     VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT, "CreateRenderTargetView");
}

template <>
HRESULT DepthStencilViewImpl::Initialize(Resource* resource) {
  const auto& d = desc_;
  TextureStorage* texture = AsTexture(resource);
  if (!texture || !(texture->shape().bindFlags & BIND_DEPTH_STENCIL))
    return device().gpu().Refuse("CreateDepthStencilView: the resource must be a texture with BIND_DEPTH_STENCIL");
  VkImageSubresourceRange range{texture->aspects(), 0, 1, 0, 1};
  bool isArray = false;
  switch (d.ViewDimension) {
    case DSV_DIMENSION_TEXTURE1D:
    case DSV_DIMENSION_TEXTURE2D: range.baseMipLevel = d.Texture2D.MipSlice; break;
    case DSV_DIMENSION_TEXTURE1DARRAY:
    case DSV_DIMENSION_TEXTURE2DARRAY:
      range.baseMipLevel = d.Texture2DArray.MipSlice;
      range.baseArrayLayer = d.Texture2DArray.FirstArraySlice;
      range.layerCount = d.Texture2DArray.ArraySize;
      isArray = true;
      break;
    case DSV_DIMENSION_TEXTURE2DMS: break;
    case DSV_DIMENSION_TEXTURE2DMSARRAY:
      range.baseArrayLayer = d.Texture2DMSArray.FirstArraySlice;
      range.layerCount = d.Texture2DMSArray.ArraySize;
      isArray = true;
      break;
    default:
      return device().gpu().Refuse("CreateDepthStencilView: ViewDimension " + std::to_string(d.ViewDimension) +
                                   " is not supported");
  }
  const bool multisampledView =
      d.ViewDimension == DSV_DIMENSION_TEXTURE2DMS || d.ViewDimension == DSV_DIMENSION_TEXTURE2DMSARRAY;
  if (std::string reason = CheckSampleDimension(resource, multisampledView, "CreateDepthStencilView");
      !reason.empty())
    return device().gpu().Refuse(reason);
  if (d.Flags & ~UINT(DSV_READ_ONLY_DEPTH | DSV_READ_ONLY_STENCIL))
    return device().gpu().Refuse("CreateDepthStencilView: Flags " + std::to_string(d.Flags) +
                                 " has bits other than DSV_READ_ONLY_DEPTH and DSV_READ_ONLY_STENCIL");
  const DXGI_FORMAT format = d.Format == DXGI_FORMAT_UNKNOWN ? texture->shape().format : d.Format;
  const auto* info = states::GetFormatInfo(format);
  if ((d.Flags & DSV_READ_ONLY_STENCIL) && info && !info->hasStencil)
    return device().gpu().Refuse(std::string("CreateDepthStencilView: DSV_READ_ONLY_STENCIL needs a format with "
                                             "stencil; ") + info->name + " has none");
  return InitTexture(device(), resource, d.Format, ViewType(texture->shape().dimension, isArray, false), range,
                     VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT, "CreateDepthStencilView");
}

// The view a NULL desc means: the whole resource in its own format.
namespace {

SHADER_RESOURCE_VIEW_DESC DefaultDesc(Resource* resource, const SHADER_RESOURCE_VIEW_DESC*) {
  SHADER_RESOURCE_VIEW_DESC d{};
  if (BufferImpl* buffer = AsBuffer(resource)) {
    d.ViewDimension = SRV_DIMENSION_BUFFER;
    UINT stride = buffer->desc().StructureByteStride ? buffer->desc().StructureByteStride : 4;
    d.Buffer = {0, buffer->desc().ByteWidth / stride};
    return d;
  }
  const TextureShape& s = AsTexture(resource)->shape();
  d.Format = s.format;
  if (s.dimension == RESOURCE_DIMENSION_TEXTURE3D) {
    d.ViewDimension = SRV_DIMENSION_TEXTURE3D;
    d.Texture3D = {0, s.mipLevels};
  } else if (s.samples > 1) {
    d.ViewDimension = s.arraySize > 1 ? SRV_DIMENSION_TEXTURE2DMSARRAY : SRV_DIMENSION_TEXTURE2DMS;
    d.Texture2DMSArray = {0, s.arraySize};
  } else if ((s.miscFlags & RESOURCE_MISC_TEXTURECUBE) && s.arraySize > 6) {
    // The whole resource: every cube of a cube array, as the D3D11 runtime does.
    d.ViewDimension = SRV_DIMENSION_TEXTURECUBEARRAY;
    d.TextureCubeArray = {0, s.mipLevels, 0, s.arraySize / 6};
  } else if (s.miscFlags & RESOURCE_MISC_TEXTURECUBE) {
    d.ViewDimension = SRV_DIMENSION_TEXTURECUBE;
    d.TextureCube = {0, s.mipLevels};
  } else if (s.arraySize > 1) {
    d.ViewDimension = s.dimension == RESOURCE_DIMENSION_TEXTURE1D ? SRV_DIMENSION_TEXTURE1DARRAY
                                                                   : SRV_DIMENSION_TEXTURE2DARRAY;
    d.Texture2DArray = {0, s.mipLevels, 0, s.arraySize};
  } else {
    d.ViewDimension = s.dimension == RESOURCE_DIMENSION_TEXTURE1D ? SRV_DIMENSION_TEXTURE1D : SRV_DIMENSION_TEXTURE2D;
    d.Texture2D = {0, s.mipLevels};
  }
  return d;
}

RENDER_TARGET_VIEW_DESC DefaultDesc(Resource* resource, const RENDER_TARGET_VIEW_DESC*) {
  RENDER_TARGET_VIEW_DESC d{};
  const TextureShape& s = AsTexture(resource)->shape();
  d.Format = s.format;
  if (s.dimension == RESOURCE_DIMENSION_TEXTURE3D) {
    d.ViewDimension = RTV_DIMENSION_TEXTURE3D;
    d.Texture3D = {0, 0, s.depth};
  } else if (s.samples > 1) {
    d.ViewDimension = s.arraySize > 1 ? RTV_DIMENSION_TEXTURE2DMSARRAY : RTV_DIMENSION_TEXTURE2DMS;
    d.Texture2DMSArray = {0, s.arraySize};
  } else if (s.arraySize > 1) {
    d.ViewDimension = RTV_DIMENSION_TEXTURE2DARRAY;
    d.Texture2DArray = {0, 0, s.arraySize};
  } else {
    d.ViewDimension = s.dimension == RESOURCE_DIMENSION_TEXTURE1D ? RTV_DIMENSION_TEXTURE1D : RTV_DIMENSION_TEXTURE2D;
  }
  return d;
}

DEPTH_STENCIL_VIEW_DESC DefaultDesc(Resource* resource, const DEPTH_STENCIL_VIEW_DESC*) {
  DEPTH_STENCIL_VIEW_DESC d{};
  const TextureShape& s = AsTexture(resource)->shape();
  d.Format = s.format;
  if (s.samples > 1) {
    d.ViewDimension = DSV_DIMENSION_TEXTURE2DMS;
  } else if (s.arraySize > 1) {
    d.ViewDimension = DSV_DIMENSION_TEXTURE2DARRAY;
    d.Texture2DArray = {0, 0, s.arraySize};
  } else {
    d.ViewDimension = s.dimension == RESOURCE_DIMENSION_TEXTURE1D ? DSV_DIMENSION_TEXTURE1D : DSV_DIMENSION_TEXTURE2D;
  }
  return d;
}

}  // namespace

template <class Interface, class Desc>
HRESULT ViewImpl<Interface, Desc>::Create(DeviceImpl* device, Resource* resource, const Desc* desc,
                                          Interface** out) {
  if (!resource) return device->gpu().Refuse("Create*View: pResource is NULL");
  if (!desc && !AsBuffer(resource) && !AsTexture(resource))
    return device->gpu().Refuse("Create*View: unknown resource");
  if (!desc && AsBuffer(resource) && !std::is_same_v<Desc, SHADER_RESOURCE_VIEW_DESC>)
    return device->gpu().Refuse("Create*View: a buffer view needs a description");
  Desc resolved;
  if (desc)
    resolved = *desc;
  else if constexpr (std::is_same_v<Desc, SHADER_RESOURCE_VIEW_DESC>)
    resolved = DefaultDesc(resource, desc);
  else
    resolved = AsTexture(resource) ? DefaultDesc(resource, desc) : Desc{};
  ComPtr<ViewImpl> view;
  view.Attach(new ViewImpl(device, resolved));
  if (HRESULT hr = view->Initialize(resource); FAILED(hr)) return hr;
  *out = view.Detach();
  return S_OK;
}

template class ViewImpl<ShaderResourceView, SHADER_RESOURCE_VIEW_DESC>;
template class ViewImpl<RenderTargetView, RENDER_TARGET_VIEW_DESC>;
template class ViewImpl<DepthStencilView, DEPTH_STENCIL_VIEW_DESC>;

// ---------------------------------------------------------------------------
// Unordered access views

HRESULT UnorderedAccessViewImpl::Create(DeviceImpl* device, Resource* resource, const UNORDERED_ACCESS_VIEW_DESC* desc,
                                        UnorderedAccessView** out) {
  if (!resource) return device->gpu().Refuse("CreateUnorderedAccessView: pResource is NULL");
  UNORDERED_ACCESS_VIEW_DESC resolved{};
  if (desc) {
    resolved = *desc;
  } else if (BufferImpl* buffer = AsBuffer(resource)) {
    resolved.ViewDimension = UAV_DIMENSION_BUFFER;
    UINT stride = buffer->desc().StructureByteStride ? buffer->desc().StructureByteStride : 4;
    resolved.Format = buffer->desc().StructureByteStride ? DXGI_FORMAT_UNKNOWN : DXGI_FORMAT_R32_UINT;
    resolved.Buffer = {0, buffer->desc().ByteWidth / stride, 0};
  } else if (TextureStorage* texture = AsTexture(resource)) {
    resolved.Format = texture->shape().format;
    if (texture->is3D()) {
      resolved.ViewDimension = UAV_DIMENSION_TEXTURE3D;
      resolved.Texture3D = {0, 0, texture->shape().depth};
    } else {
      resolved.ViewDimension = texture->shape().arraySize > 1 ? UAV_DIMENSION_TEXTURE2DARRAY : UAV_DIMENSION_TEXTURE2D;
      resolved.Texture2DArray = {0, 0, texture->shape().arraySize};
    }
  }
  ComPtr<UnorderedAccessViewImpl> view;
  view.Attach(new UnorderedAccessViewImpl(device, resolved));
  if (HRESULT hr = view->Initialize(resource); FAILED(hr)) return hr;
  *out = view.Detach();
  return S_OK;
}

HRESULT UnorderedAccessViewImpl::Initialize(Resource* resource) {
  const auto& d = desc_;
  BufferImpl* buffer = AsBuffer(resource);
  TextureStorage* texture = AsTexture(resource);
  const UINT bind = buffer ? buffer->desc().BindFlags : texture ? texture->shape().bindFlags : 0;
  if (!(bind & BIND_UNORDERED_ACCESS))
    return device().gpu().Refuse("CreateUnorderedAccessView: the resource lacks BIND_UNORDERED_ACCESS");
  if (d.ViewDimension == UAV_DIMENSION_BUFFER) {
    if (HRESULT hr = InitBuffer(device(), resource, d.Format, d.Buffer.FirstElement, d.Buffer.NumElements, true,
                                "CreateUnorderedAccessView");
        FAILED(hr))
      return hr;
    return CreateCounter(resource);
  }
  if (std::string reason =
          CheckVolumeDimension(texture, d.ViewDimension == UAV_DIMENSION_TEXTURE3D, "CreateUnorderedAccessView");
      !reason.empty())
    return device().gpu().Refuse(reason);
  VkImageSubresourceRange range{VK_IMAGE_ASPECT_COLOR_BIT, d.Texture2D.MipSlice, 1, 0, 1};
  if (d.ViewDimension == UAV_DIMENSION_TEXTURE3D) {
    if (!texture) return device().gpu().Refuse("CreateUnorderedAccessView: a TEXTURE3D view needs a 3D texture");
    // A Vulkan storage view of a 3D image covers every W slice of its level (a
    // RWTexture3D is a 3D view; 2D-array views of 3D images are for attachments
    // only), so a view of fewer W slices, which D3D11 allows, is refused here.
    const UINT wSize = WSliceCount(texture, d.Texture3D.MipSlice, d.Texture3D.FirstWSlice, d.Texture3D.WSize);
    const UINT depth = texture->MipExtent(std::min(d.Texture3D.MipSlice, texture->shape().mipLevels - 1)).depth;
    if (d.Texture3D.FirstWSlice != 0 || wSize != depth)
      return device().gpu().Refuse("CreateUnorderedAccessView: a TEXTURE3D view of W slices " +
                                   std::to_string(d.Texture3D.FirstWSlice) + "+" + std::to_string(wSize) + " of " +
                                   std::to_string(depth) + ": this backend's 3D UAVs cover every W slice of their "
                                   "mip (FirstWSlice 0, WSize -1 or the mip's depth)");
    return InitTexture(device(), resource, d.Format, VK_IMAGE_VIEW_TYPE_3D, range, VK_IMAGE_USAGE_STORAGE_BIT,
                       "CreateUnorderedAccessView");
  }
  bool isArray = d.ViewDimension == UAV_DIMENSION_TEXTURE2DARRAY || d.ViewDimension == UAV_DIMENSION_TEXTURE1DARRAY;
  if (isArray) {
    range.baseArrayLayer = d.Texture2DArray.FirstArraySlice;
    range.layerCount = d.Texture2DArray.ArraySize;
  }
  RESOURCE_DIMENSION dimension = texture ? texture->shape().dimension : RESOURCE_DIMENSION_TEXTURE2D;
  return InitTexture(device(), resource, d.Format, ViewType(dimension, isArray, false), range,
                     VK_IMAGE_USAGE_STORAGE_BIT, "CreateUnorderedAccessView");
}

HRESULT UnorderedAccessViewImpl::CreateCounter(Resource* resource) {
  const UINT flags = desc_.Buffer.Flags & (BUFFER_UAV_FLAG_APPEND | BUFFER_UAV_FLAG_COUNTER);
  if (!flags) return S_OK;
  Gpu& gpu = device().gpu();
  if (flags == (BUFFER_UAV_FLAG_APPEND | BUFFER_UAV_FLAG_COUNTER))
    return gpu.Refuse("CreateUnorderedAccessView: BUFFER_UAV_FLAG_APPEND and BUFFER_UAV_FLAG_COUNTER exclude each other");
  if (!(AsBuffer(resource)->desc().MiscFlags & RESOURCE_MISC_BUFFER_STRUCTURED))
    return gpu.Refuse(std::string("CreateUnorderedAccessView: ") +
                      (flags == BUFFER_UAV_FLAG_APPEND ? "BUFFER_UAV_FLAG_APPEND" : "BUFFER_UAV_FLAG_COUNTER") +
                      " needs a structured buffer (RESOURCE_MISC_BUFFER_STRUCTURED)");
  // The count starts at 0; pUAVInitialCounts and the shaders change it on the GPU.
  const UINT zero = 0;
  const SUBRESOURCE_DATA initial{&zero, 0, 0};
  BUFFER_DESC desc{};
  desc.ByteWidth = sizeof(UINT);
  desc.Usage = USAGE_DEFAULT;
  desc.BindFlags = BIND_UNORDERED_ACCESS;
  desc.MiscFlags = RESOURCE_MISC_BUFFER_ALLOW_RAW_VIEWS;
  BufferImpl* counter = nullptr;
  if (HRESULT hr = BufferImpl::Create(&device(), desc, &initial, &counter); FAILED(hr)) return hr;
  counter_ = Bound<BufferImpl>(counter);
  counter->Release();  // the binding alone keeps it
  return S_OK;
}

}  // namespace rhi::vk
