// Clears, Map/Unmap, uploads, copies, resolves and Flush.
#include <algorithm>
#include <cstring>
#include <string>
#include <tuple>

#include "context.h"
#include "queries.h"
#include "resources.h"
#include "states/formats.h"
#include "views.h"

namespace rhi::vk {

namespace {

VkImageSubresourceRange WholeRange(const TextureStorage& texture) {
  return {texture.aspects(), 0, VK_REMAINING_MIP_LEVELS, 0, VK_REMAINING_ARRAY_LAYERS};
}

// Copies between an image and a buffer address one aspect at a time; a
// D3D11 depth-stencil subresource copy means its depth.
VkImageSubresourceLayers CopyLayers(const TextureStorage& texture, UINT subresource) {
  VkImageSubresourceLayers layers = texture.Layers(subresource);
  if (layers.aspectMask & VK_IMAGE_ASPECT_DEPTH_BIT) layers.aspectMask = VK_IMAGE_ASPECT_DEPTH_BIT;
  return layers;
}

}  // namespace

void ContextImpl::InitializeImageLayout(TextureStorage& texture) {
  // Images live in GENERAL for their whole life; this is their only transition.
  EndRendering();
  VkImageMemoryBarrier2 barrier{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
  barrier.srcStageMask = VK_PIPELINE_STAGE_2_NONE;
  barrier.dstStageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
  barrier.dstAccessMask = VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT;
  barrier.oldLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  barrier.newLayout = VK_IMAGE_LAYOUT_GENERAL;
  barrier.srcQueueFamilyIndex = barrier.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  barrier.image = texture.image();
  barrier.subresourceRange = WholeRange(texture);
  VkDependencyInfo dependency{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
  dependency.imageMemoryBarrierCount = 1;
  dependency.pImageMemoryBarriers = &barrier;
  vkCmdPipelineBarrier2(Commands(), &dependency);
}

void ContextImpl::EmitBarriers() {
  EndRendering();
  VkDependencyInfo dependency{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
  dependency.memoryBarrierCount = 1;
  dependency.pMemoryBarriers = &pendingBarrier_;
  vkCmdPipelineBarrier2(Commands(), &dependency);
  pendingBarrier_ = {VK_STRUCTURE_TYPE_MEMORY_BARRIER_2};
}

// ---------------------------------------------------------------------------
// Uploads

void ContextImpl::UploadBuffer(BufferImpl& buffer, VkDeviceSize offset, const void* data, VkDeviceSize size) {
  HostSlice staging = device_->hostSlices().Allocate(size, 16);
  std::memcpy(staging.data, data, size);
  EndRendering();
  Use(buffer, uses::kTransferWrite);
  FlushBarriers();
  VkBufferCopy region{staging.offset, offset, size};
  vkCmdCopyBuffer(Commands(), staging.buffer, buffer.handle(), 1, &region);
  device_->hostSlices().Release(staging);
}

namespace {

// D3D11's rule for block-compressed regions: they start on a 4x4 block and cover whole
// blocks, except that they may end at the subresource's edge (a 2x2 level is one block).
std::string BlockAlignmentError(const TextureStorage& texture, UINT subresource, VkOffset3D origin, VkExtent3D extent) {
  const states::FormatInfo& format = *states::GetFormatInfo(texture.shape().format);
  const UINT bs = format.blockSize;
  if (bs == 1) return {};
  const VkExtent3D level = texture.MipExtent(subresource % texture.shape().mipLevels);
  const bool aligned = origin.x % bs == 0 && origin.y % bs == 0 &&
                       (extent.width % bs == 0 || origin.x + extent.width == level.width) &&
                       (extent.height % bs == 0 || origin.y + extent.height == level.height);
  if (aligned) return {};
  return std::string("the region at (") + std::to_string(origin.x) + ", " + std::to_string(origin.y) + ") of " +
         std::to_string(extent.width) + "x" + std::to_string(extent.height) + " texels of a " + format.name +
         " subresource (" + std::to_string(level.width) + "x" + std::to_string(level.height) +
         ") is not aligned to its 4x4 blocks";
}

}  // namespace

void ContextImpl::UploadTexture(TextureStorage& texture, UINT subresource, const BOX* box, const void* data,
                                UINT rowPitch, UINT depthPitch) {
  // Rows are rows of 4x4 blocks for block-compressed formats (box offsets are block-aligned).
  const states::FormatInfo& format = *states::GetFormatInfo(texture.shape().format);
  VkOffset3D origin{0, 0, 0};
  VkExtent3D extent = texture.MipExtent(subresource % texture.shape().mipLevels);
  if (box) {
    origin = {static_cast<int32_t>(box->left), static_cast<int32_t>(box->top), 0};
    extent = {box->right - box->left, box->bottom - box->top, 1};
    // Only 3D textures have W slices; D3D11 ignores front/back for the others (0 and 1).
    if (texture.is3D()) {
      origin.z = static_cast<int32_t>(box->front);
      extent.depth = box->back - box->front;
    }
  }
  const VkDeviceSize tightRow = states::RowPitchBytes(format, extent.width);
  const UINT rows = states::RowCount(format, extent.height);
  const auto* source = static_cast<const uint8_t*>(data);
  auto sourceRow = [&](UINT z, UINT y) { return source + VkDeviceSize(z) * depthPitch + VkDeviceSize(y) * rowPitch; };
  if (texture.isStaging()) {
    uint8_t* dst = texture.stagingData() + texture.SubresourceOffset(subresource);
    const UINT dstRow = texture.RowPitch(subresource), dstSlice = texture.DepthPitch(subresource);
    for (UINT z = 0; z < extent.depth; ++z)
      for (UINT y = 0; y < rows; ++y)
        std::memcpy(dst + VkDeviceSize(origin.z + z) * dstSlice + (origin.y / format.blockSize + y) * dstRow +
                        origin.x / format.blockSize * format.bytesPerElement,
                    sourceRow(z, y), tightRow);
    return;
  }
  HostSlice staging = device_->hostSlices().Allocate(tightRow * rows * extent.depth, 16);
  for (UINT z = 0; z < extent.depth; ++z)
    for (UINT y = 0; y < rows; ++y)
      std::memcpy(staging.data + (VkDeviceSize(z) * rows + y) * tightRow, sourceRow(z, y), tightRow);
  EndRendering();
  Use(texture, uses::kTransferWrite);
  FlushBarriers();
  VkBufferImageCopy region{};
  region.bufferOffset = staging.offset;
  region.imageSubresource = CopyLayers(texture, subresource);
  region.imageOffset = origin;
  region.imageExtent = extent;
  vkCmdCopyBufferToImage(Commands(), staging.buffer, texture.image(), VK_IMAGE_LAYOUT_GENERAL, 1, &region);
  device_->hostSlices().Release(staging);
}

void ContextImpl::UpdateSubresource(Resource* pDstResource, UINT DstSubresource, const BOX* pDstBox,
                                    const void* pSrcData, UINT SrcRowPitch, UINT SrcDepthPitch) {
  if (predicationSkips_) return;
  if (BufferImpl* buffer = AsBuffer(pDstResource)) {
    if (buffer->desc().Usage != USAGE_DEFAULT) {
      ReportDrawError("UpdateSubresource: only USAGE_DEFAULT resources can be updated");
      return;
    }
    UINT begin = pDstBox ? pDstBox->left : 0;
    UINT end = pDstBox ? pDstBox->right : buffer->desc().ByteWidth;
    if (begin >= end || end > buffer->desc().ByteWidth) return;  // D3D11: an empty or outside box does nothing
    UploadBuffer(*buffer, begin, pSrcData, end - begin);
    return;
  }
  TextureStorage* texture = AsTexture(pDstResource);
  if (!texture || texture->shape().usage != USAGE_DEFAULT || DstSubresource >= texture->subresourceCount()) {
    ReportDrawError("UpdateSubresource: the destination must be a USAGE_DEFAULT resource and a valid subresource");
    return;
  }
  if (pDstBox) {
    // D3D11: an empty box, or one reaching past the subresource, updates nothing.
    const VkExtent3D mip = texture->MipExtent(DstSubresource % texture->shape().mipLevels);
    if (pDstBox->left >= pDstBox->right || pDstBox->top >= pDstBox->bottom || pDstBox->right > mip.width ||
        pDstBox->bottom > mip.height ||
        (texture->is3D() && (pDstBox->front >= pDstBox->back || pDstBox->back > mip.depth)))
      return;
    const VkOffset3D origin{static_cast<int32_t>(pDstBox->left), static_cast<int32_t>(pDstBox->top), 0};
    const VkExtent3D extent{pDstBox->right - pDstBox->left, pDstBox->bottom - pDstBox->top, 1};
    if (std::string reason = BlockAlignmentError(*texture, DstSubresource, origin, extent); !reason.empty()) {
      ReportDrawError("UpdateSubresource: pDstBox: " + reason);
      return;
    }
  }
  UploadTexture(*texture, DstSubresource, pDstBox, pSrcData, SrcRowPitch, SrcDepthPitch);
}

// ---------------------------------------------------------------------------
// Clears

void ContextImpl::ClearRenderTargetView(RenderTargetView* pRenderTargetView, const FLOAT ColorRGBA[4]) {
  if (predicationSkips_) return;
  auto* view = static_cast<RenderTargetViewImpl*>(pRenderTargetView);
  TextureStorage& texture = view->texture();
  const auto* format = states::GetFormatInfo(view->format());
  VkClearColorValue color{};
  for (int i = 0; i < 4; ++i) {
    color.float32[i] = ColorRGBA[i];
    if (format->kind == states::ComponentKind::Uint) color.uint32[i] = static_cast<uint32_t>(ColorRGBA[i]);
    if (format->kind == states::ComponentKind::Sint) color.int32[i] = static_cast<int32_t>(ColorRGBA[i]);
  }
  // Formats without alpha (B8G8R8X8) keep alpha at 1 so that it reads as 1.
  if (format->alphaIsOne) color.float32[3] = 1.0f;
  EndRendering();
  const VkImageSubresourceRange range = view->range();
  // vkCmdClearColorImage would clear every W slice of a 3D mip; a TEXTURE3D view clears its own.
  if (format->vkFormat == texture.vkFormat() && !texture.is3D()) {
    Use(texture, uses::kTransferWrite);
    FlushBarriers();
    vkCmdClearColorImage(Commands(), texture.image(), VK_IMAGE_LAYOUT_GENERAL, &color, 1, &range);
    return;
  }
  // A view that reinterprets a typeless texture (R8G8B8A8_UNORM of an image stored
  // as R8G8B8A8_UINT): vkCmdClearColorImage would read the colour in the image's
  // format, a rendering pass's clear reads it in the view's. W slices of a 3D
  // texture are cleared as the view's layers.
  Use(texture, uses::kColorAttachment);
  FlushBarriers();
  VkRenderingAttachmentInfo attachment{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
  attachment.imageView = view->imageView();
  attachment.imageLayout = VK_IMAGE_LAYOUT_GENERAL;
  attachment.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
  attachment.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
  attachment.clearValue.color = color;
  const VkExtent3D mip = texture.MipExtent(range.baseMipLevel);
  VkRenderingInfo info{VK_STRUCTURE_TYPE_RENDERING_INFO};
  info.renderArea = {{0, 0}, {mip.width, mip.height}};
  info.layerCount = range.layerCount;
  info.colorAttachmentCount = 1;
  info.pColorAttachments = &attachment;
  vkCmdBeginRendering(Commands(), &info);
  vkCmdEndRendering(Commands());
}

void ContextImpl::ClearDepthStencilView(DepthStencilView* pDepthStencilView, UINT ClearFlags, FLOAT Depth,
                                        UINT8 Stencil) {
  if (predicationSkips_) return;
  auto* view = static_cast<DepthStencilViewImpl*>(pDepthStencilView);
  TextureStorage& texture = view->texture();
  VkImageSubresourceRange range = view->range();
  range.aspectMask = 0;
  if (ClearFlags & CLEAR_DEPTH) range.aspectMask |= VK_IMAGE_ASPECT_DEPTH_BIT;
  if ((ClearFlags & CLEAR_STENCIL) && (texture.aspects() & VK_IMAGE_ASPECT_STENCIL_BIT))
    range.aspectMask |= VK_IMAGE_ASPECT_STENCIL_BIT;
  if (!range.aspectMask) return;
  EndRendering();
  Use(texture, uses::kTransferWrite);
  FlushBarriers();
  VkClearDepthStencilValue value{Depth, Stencil};
  vkCmdClearDepthStencilImage(Commands(), texture.image(), VK_IMAGE_LAYOUT_GENERAL, &value, 1, &range);
}

void ContextImpl::ClearUnorderedAccessViewUint(UnorderedAccessView* pUnorderedAccessView, const UINT Values[4]) {
  if (predicationSkips_) return;
  auto* view = static_cast<UnorderedAccessViewImpl*>(pUnorderedAccessView);
  EndRendering();
  if (BufferImpl* buffer = view->buffer()) {
    Use(*buffer, uses::kTransferWrite);
    FlushBarriers();
    // Raw, structured and 32-bit typed views clear with the first value, as D3D11 does.
    VkDescriptorBufferInfo range = view->bufferRange();
    vkCmdFillBuffer(Commands(), range.buffer, range.offset, range.range, Values[0]);
    return;
  }
  TextureStorage& texture = *view->texture();
  Use(texture, uses::kTransferWrite);
  FlushBarriers();
  VkClearColorValue color{};
  std::memcpy(color.uint32, Values, sizeof color.uint32);
  VkImageSubresourceRange range = view->range();
  vkCmdClearColorImage(Commands(), texture.image(), VK_IMAGE_LAYOUT_GENERAL, &color, 1, &range);
}

void ContextImpl::ClearUnorderedAccessViewFloat(UnorderedAccessView* pUnorderedAccessView, const FLOAT Values[4]) {
  if (predicationSkips_) return;
  auto* view = static_cast<UnorderedAccessViewImpl*>(pUnorderedAccessView);
  if (view->buffer()) {
    UINT bits[4];
    std::memcpy(bits, Values, sizeof bits);
    ClearUnorderedAccessViewUint(pUnorderedAccessView, bits);
    return;
  }
  TextureStorage& texture = *view->texture();
  EndRendering();
  Use(texture, uses::kTransferWrite);
  FlushBarriers();
  VkClearColorValue color{};
  std::memcpy(color.float32, Values, sizeof color.float32);
  VkImageSubresourceRange range = view->range();
  vkCmdClearColorImage(Commands(), texture.image(), VK_IMAGE_LAYOUT_GENERAL, &color, 1, &range);
}

// ---------------------------------------------------------------------------
// Map / Unmap

HRESULT ContextImpl::Map(Resource* pResource, UINT Subresource, MAP MapType, UINT MapFlags,
                         MAPPED_SUBRESOURCE* pMappedResource) {
  Gpu& gpu = device_->gpu();
  if (BufferImpl* buffer = AsBuffer(pResource); buffer && buffer->isDynamic()) {
    if (MapType == MAP_WRITE_DISCARD) {
      buffer->Rename();
      // The bound storage moved: descriptors and vertex buffers must be re-emitted.
      descriptorsDirty_ = vertexBuffersDirty_ = true;
    } else if (MapType != MAP_WRITE_NO_OVERWRITE) {
      return gpu.Refuse("Map: a USAGE_DYNAMIC buffer maps with WRITE_DISCARD or WRITE_NO_OVERWRITE only");
    }
    *pMappedResource = {buffer->hostData(), buffer->desc().ByteWidth, buffer->desc().ByteWidth};
    return S_OK;
  }
  TrackedResource* tracked = nullptr;
  MAPPED_SUBRESOURCE mapped{};
  if (BufferImpl* buffer = AsBuffer(pResource); buffer && buffer->isStaging()) {
    tracked = buffer;
    mapped = {buffer->hostData(), buffer->desc().ByteWidth, buffer->desc().ByteWidth};
  } else if (TextureStorage* texture = AsTexture(pResource);
             texture && texture->isStaging() && Subresource < texture->subresourceCount()) {
    tracked = texture;
    mapped = {texture->stagingData() + texture->SubresourceOffset(Subresource), texture->RowPitch(Subresource),
              texture->DepthPitch(Subresource)};
  } else {
    return gpu.Refuse("Map: only USAGE_DYNAMIC and USAGE_STAGING resources can be mapped (valid subresource)");
  }
  if (MapType == MAP_WRITE_DISCARD || MapType == MAP_WRITE_NO_OVERWRITE)
    return gpu.Refuse("Map: WRITE_DISCARD and WRITE_NO_OVERWRITE are for USAGE_DYNAMIC resources");
  // The CPU must see what the GPU wrote, and must not overwrite what it still reads.
  if (!gpu.IsComplete(tracked->lastUseSerial)) {
    if (MapFlags & MAP_FLAG_DO_NOT_WAIT) {
      if (tracked->lastUseSerial == gpu.RecordingSerial()) Flush();
      return DXGI_ERROR_WAS_STILL_DRAWING;
    }
    if (tracked->lastUseSerial == gpu.RecordingSerial()) Flush();
    gpu.WaitFor(tracked->lastUseSerial);
  }
  *pMappedResource = mapped;
  return S_OK;
}

void ContextImpl::Unmap(Resource*, UINT) {
  // Host memory is coherent: nothing to flush.
}

// ---------------------------------------------------------------------------
// Copies

namespace {

struct CopyRegion {
  VkOffset3D srcOffset{0, 0, 0};
  VkOffset3D dstOffset{0, 0, 0};
  VkExtent3D extent{};
};

}  // namespace

void ContextImpl::CopyResource(Resource* pDstResource, Resource* pSrcResource) {
  if (predicationSkips_) return;
  if (BufferImpl* dst = AsBuffer(pDstResource)) {
    BufferImpl* src = AsBuffer(pSrcResource);
    if (!src || src->desc().ByteWidth != dst->desc().ByteWidth) {
      ReportDrawError("CopyResource: source and destination must be buffers of the same size");
      return;
    }
    CopySubresourceRegion(pDstResource, 0, 0, 0, 0, pSrcResource, 0, nullptr);
    return;
  }
  TextureStorage* dst = AsTexture(pDstResource);
  TextureStorage* src = AsTexture(pSrcResource);
  if (!src || src->subresourceCount() != dst->subresourceCount() || src->shape().width != dst->shape().width ||
      src->shape().height != dst->shape().height || src->shape().depth != dst->shape().depth ||
      src->shape().dimension != dst->shape().dimension) {
    ReportDrawError("CopyResource: source and destination must be textures of the same shape");
    return;
  }
  for (UINT sub = 0; sub < dst->subresourceCount(); ++sub)
    CopySubresourceRegion(pDstResource, sub, 0, 0, 0, pSrcResource, sub, nullptr);
}

void ContextImpl::CopyStructureCount(Buffer* pDstBuffer, UINT DstAlignedByteOffset, UnorderedAccessView* pSrcView) {
  auto* dst = static_cast<BufferImpl*>(pDstBuffer);
  auto* view = static_cast<UnorderedAccessViewImpl*>(pSrcView);
  BufferImpl* counter = view ? view->counter() : nullptr;
  std::string reason;
  if (!dst || !view)
    reason = "pDstBuffer and pSrcView must not be NULL";
  else if (!counter)
    reason = "pSrcView has no hidden counter (a structured-buffer UAV created with BUFFER_UAV_FLAG_APPEND or "
             "BUFFER_UAV_FLAG_COUNTER)";
  else if (DstAlignedByteOffset % 4 != 0 || dst->desc().ByteWidth < 4 ||
           DstAlignedByteOffset > dst->desc().ByteWidth - 4)
    reason = "DstAlignedByteOffset (" + std::to_string(DstAlignedByteOffset) +
             ") must be a multiple of 4 with 4 bytes of pDstBuffer after it";
  else if (dst->isDynamic() || dst->desc().Usage == USAGE_IMMUTABLE)
    reason = "pDstBuffer must be a DEFAULT or STAGING buffer (the GPU writes it)";
  if (!reason.empty()) {
    ReportDrawError("CopyStructureCount: " + reason + "; the call is ignored");
    return;
  }
  EndRendering();
  Use(*counter, uses::kTransferRead);
  Use(*dst, uses::kTransferWrite);
  FlushBarriers();
  const VkBufferCopy region{counter->baseOffset(), dst->baseOffset() + DstAlignedByteOffset, sizeof(UINT)};
  vkCmdCopyBuffer(Commands(), counter->handle(), dst->handle(), 1, &region);
  if (dst->isStaging()) {
    Use(*dst, uses::kHostRead);
    FlushBarriers();
  }
}

void ContextImpl::CopySubresourceRegion(Resource* pDstResource, UINT DstSubresource, UINT DstX, UINT DstY, UINT DstZ,
                                        Resource* pSrcResource, UINT SrcSubresource, const BOX* pSrcBox) {
  if (predicationSkips_) return;
  EndRendering();
  if (BufferImpl* dst = AsBuffer(pDstResource)) {
    BufferImpl* src = AsBuffer(pSrcResource);
    if (!src || dst->isDynamic()) {
      ReportDrawError("CopySubresourceRegion: buffer copies need a buffer source and a non-dynamic destination");
      return;
    }
    UINT begin = pSrcBox ? pSrcBox->left : 0;
    UINT end = pSrcBox ? pSrcBox->right : src->desc().ByteWidth;
    if (begin >= end || end > src->desc().ByteWidth || DstX + (end - begin) > dst->desc().ByteWidth) return;
    Use(*src, uses::kTransferRead);
    Use(*dst, uses::kTransferWrite);
    FlushBarriers();
    VkBufferCopy region{src->baseOffset() + begin, DstX, end - begin};
    vkCmdCopyBuffer(Commands(), src->handle(), dst->handle(), 1, &region);
    if (dst->isStaging()) {
      Use(*dst, uses::kHostRead);
      FlushBarriers();
    }
    return;
  }
  TextureStorage* dst = AsTexture(pDstResource);
  TextureStorage* src = AsTexture(pSrcResource);
  if (!dst || !src || DstSubresource >= dst->subresourceCount() || SrcSubresource >= src->subresourceCount()) {
    ReportDrawError("CopySubresourceRegion: invalid texture or subresource");
    return;
  }
  if (src->is3D() != dst->is3D()) {
    ReportDrawError("CopySubresourceRegion: source and destination must both be 3D textures or neither");
    return;
  }
  // W slices (box front/back, DstZ) exist in 3D textures only; D3D11 ignores them elsewhere.
  const bool volume = src->is3D();
  CopyRegion region;
  region.extent = src->MipExtent(SrcSubresource % src->shape().mipLevels);
  if (pSrcBox) {
    region.srcOffset = {static_cast<int32_t>(pSrcBox->left), static_cast<int32_t>(pSrcBox->top),
                        volume ? static_cast<int32_t>(pSrcBox->front) : 0};
    region.extent = {pSrcBox->right - pSrcBox->left, pSrcBox->bottom - pSrcBox->top,
                     volume ? pSrcBox->back - pSrcBox->front : 1};
  }
  region.dstOffset = {static_cast<int32_t>(DstX), static_cast<int32_t>(DstY), volume ? static_cast<int32_t>(DstZ) : 0};
  for (auto [texture, sub, offset, what] : {std::tuple{src, SrcSubresource, region.srcOffset, "pSrcBox"},
                                           std::tuple{dst, DstSubresource, region.dstOffset, "DstX, DstY"}}) {
    if (std::string reason = BlockAlignmentError(*texture, sub, offset, region.extent); !reason.empty()) {
      ReportDrawError(std::string("CopySubresourceRegion: ") + what + ": " + reason);
      return;
    }
  }
  Use(*src, uses::kTransferRead);
  Use(*dst, uses::kTransferWrite);
  FlushBarriers();
  VkCommandBuffer commands = Commands();
  // Offsets and rows count 4x4 blocks for block-compressed formats (bs = 4).
  const states::FormatInfo& format = *states::GetFormatInfo(src->shape().format);
  const UINT bpe = format.bytesPerElement, bs = format.blockSize;
  auto bufferCopy = [&](const TextureStorage& staging, UINT sub, VkOffset3D imageOffset, VkOffset3D bufferOffset,
                        const TextureStorage& image, UINT imageSub) {
    VkBufferImageCopy copy{};
    copy.bufferOffset = staging.SubresourceOffset(sub) + VkDeviceSize(bufferOffset.z) * staging.DepthPitch(sub) +
                        VkDeviceSize(bufferOffset.y / bs) * staging.RowPitch(sub) +
                        VkDeviceSize(bufferOffset.x / bs) * bpe;
    copy.bufferRowLength = staging.RowPitch(sub) / bpe * bs;
    copy.bufferImageHeight = staging.DepthPitch(sub) / staging.RowPitch(sub) * bs;  // a W slice's texel rows
    copy.imageSubresource = CopyLayers(image, imageSub);
    copy.imageOffset = imageOffset;
    copy.imageExtent = region.extent;
    return copy;
  };
  if (src->isStaging() && dst->isStaging()) {
    auto rowOffset = [&](const TextureStorage& t, UINT sub, VkOffset3D at, UINT z, UINT y) {
      return t.SubresourceOffset(sub) + VkDeviceSize(at.z + z) * t.DepthPitch(sub) +
             VkDeviceSize(at.y / bs + y) * t.RowPitch(sub) + VkDeviceSize(at.x / bs) * bpe;
    };
    for (UINT z = 0; z < region.extent.depth; ++z)
      for (UINT y = 0; y < states::RowCount(format, region.extent.height); ++y) {
        VkBufferCopy row{rowOffset(*src, SrcSubresource, region.srcOffset, z, y),
                         rowOffset(*dst, DstSubresource, region.dstOffset, z, y),
                         states::RowPitchBytes(format, region.extent.width)};
        vkCmdCopyBuffer(commands, src->stagingBuffer(), dst->stagingBuffer(), 1, &row);
      }
  } else if (dst->isStaging()) {
    VkBufferImageCopy copy = bufferCopy(*dst, DstSubresource, region.srcOffset, region.dstOffset, *src, SrcSubresource);
    vkCmdCopyImageToBuffer(commands, src->image(), VK_IMAGE_LAYOUT_GENERAL, dst->stagingBuffer(), 1, &copy);
  } else if (src->isStaging()) {
    VkBufferImageCopy copy = bufferCopy(*src, SrcSubresource, region.dstOffset, region.srcOffset, *dst, DstSubresource);
    vkCmdCopyBufferToImage(commands, src->stagingBuffer(), dst->image(), VK_IMAGE_LAYOUT_GENERAL, 1, &copy);
  } else {
    VkImageCopy copy{CopyLayers(*src, SrcSubresource), region.srcOffset, CopyLayers(*dst, DstSubresource),
                     region.dstOffset, region.extent};
    copy.srcSubresource.aspectMask = src->aspects();
    copy.dstSubresource.aspectMask = dst->aspects();
    vkCmdCopyImage(commands, src->image(), VK_IMAGE_LAYOUT_GENERAL, dst->image(), VK_IMAGE_LAYOUT_GENERAL, 1, &copy);
  }
  if (dst->isStaging()) {
    Use(*dst, uses::kHostRead);
    FlushBarriers();
  }
}

namespace {

// D3D11's ResolveSubresource rules; empty when the resolve may go ahead.
std::string ResolveRefusal(const TextureStorage* dst, UINT dstSub, const TextureStorage* src, UINT srcSub,
                           DXGI_FORMAT format) {
  if (!dst || !src || src->shape().samples < 2 || dst->shape().samples != 1)
    return "needs a multisampled source and a single-sampled destination";
  if (dstSub >= dst->subresourceCount() || srcSub >= src->subresourceCount()) return "a subresource is out of range";
  const VkExtent3D from = src->MipExtent(0), to = dst->MipExtent(dstSub % dst->shape().mipLevels);
  if (from.width != to.width || from.height != to.height) return "source and destination sizes differ";
  const auto* info = states::GetFormatInfo(format);
  if (!info || info->kind == states::ComponentKind::Typeless)
    return "Format must be a typed format";
  // The resolve averages the samples: integers and depth have no average in D3D11.
  if (info->kind == states::ComponentKind::Uint || info->kind == states::ComponentKind::Sint ||
      info->kind == states::ComponentKind::Depth || info->isDepth)
    return std::string(info->name) + " cannot be resolved (integer and depth formats have no average)";
  if (!states::IsViewCompatible(src->shape().format, format) || !states::IsViewCompatible(dst->shape().format, format))
    return std::string(info->name) + " is not compatible with both resources' formats";
  // vkCmdResolveImage reads and writes the images' own formats; resolving as
  // another member of a typeless family goes through views of `format` as
  // rendering attachments, which both images must allow.
  const bool reinterprets = src->vkFormat() != info->vkFormat || dst->vkFormat() != info->vkFormat;
  if (reinterprets && !((src->shape().bindFlags & dst->shape().bindFlags) & BIND_RENDER_TARGET))
    return std::string("resolving a typeless resource as ") + info->name +
           " needs BIND_RENDER_TARGET on both resources in this backend";
  return {};
}

// A view of one subresource of `texture` in `format`, as a colour attachment.
VkImageView AttachmentView(Gpu& gpu, const TextureStorage& texture, UINT subresource, VkFormat format) {
  VkImageViewUsageCreateInfo usage{VK_STRUCTURE_TYPE_IMAGE_VIEW_USAGE_CREATE_INFO};
  usage.usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT;
  VkImageViewCreateInfo info{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
  info.pNext = &usage;
  info.image = texture.image();
  info.viewType = VK_IMAGE_VIEW_TYPE_2D;
  info.format = format;
  const VkImageSubresourceLayers layers = texture.Layers(subresource);
  info.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, layers.mipLevel, 1, layers.baseArrayLayer, 1};
  VkImageView view = VK_NULL_HANDLE;
  vkCreateImageView(gpu.Device(), &info, nullptr, &view);
  return view;
}

}  // namespace

void ContextImpl::ResolveSubresource(Resource* pDstResource, UINT DstSubresource, Resource* pSrcResource,
                                     UINT SrcSubresource, DXGI_FORMAT Format) {
  if (predicationSkips_) return;
  TextureStorage* dst = AsTexture(pDstResource);
  TextureStorage* src = AsTexture(pSrcResource);
  if (std::string reason = ResolveRefusal(dst, DstSubresource, src, SrcSubresource, Format); !reason.empty()) {
    ReportDrawError("ResolveSubresource: " + reason + "; nothing is resolved");
    return;
  }
  EndRendering();
  const VkFormat format = states::GetFormatInfo(Format)->vkFormat;
  if (src->vkFormat() != format || dst->vkFormat() != format) {
    ResolveThroughRendering(*dst, DstSubresource, *src, SrcSubresource, format);
    return;
  }
  Use(*src, uses::kTransferRead);
  Use(*dst, uses::kTransferWrite);
  FlushBarriers();
  VkImageResolve region{src->Layers(SrcSubresource), {0, 0, 0}, dst->Layers(DstSubresource), {0, 0, 0},
                        dst->MipExtent(DstSubresource % dst->shape().mipLevels)};
  vkCmdResolveImage(Commands(), src->image(), VK_IMAGE_LAYOUT_GENERAL, dst->image(), VK_IMAGE_LAYOUT_GENERAL, 1,
                    &region);
}

void ContextImpl::ResolveThroughRendering(TextureStorage& dst, UINT dstSub, TextureStorage& src, UINT srcSub,
                                          VkFormat format) {
  Gpu& gpu = device_->gpu();
  VkImageView from = AttachmentView(gpu, src, srcSub, format);
  VkImageView to = AttachmentView(gpu, dst, dstSub, format);
  // The source is only loaded (STORE_OP_NONE); the resolve writes the destination at the end of the instance.
  Use(src, {VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT, VK_ACCESS_2_COLOR_ATTACHMENT_READ_BIT, false});
  Use(dst, uses::kColorAttachment);
  FlushBarriers();
  VkRenderingAttachmentInfo attachment{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
  attachment.imageView = from;
  attachment.imageLayout = VK_IMAGE_LAYOUT_GENERAL;
  attachment.loadOp = VK_ATTACHMENT_LOAD_OP_LOAD;
  attachment.storeOp = VK_ATTACHMENT_STORE_OP_NONE;
  attachment.resolveMode = VK_RESOLVE_MODE_AVERAGE_BIT;
  attachment.resolveImageView = to;
  attachment.resolveImageLayout = VK_IMAGE_LAYOUT_GENERAL;
  const VkExtent3D extent = src.MipExtent(0);
  VkRenderingInfo info{VK_STRUCTURE_TYPE_RENDERING_INFO};
  info.renderArea = {{0, 0}, {extent.width, extent.height}};
  info.layerCount = 1;
  info.colorAttachmentCount = 1;
  info.pColorAttachments = &attachment;
  vkCmdBeginRendering(Commands(), &info);
  vkCmdEndRendering(Commands());
  VkDevice vkDevice = gpu.Device();
  gpu.DeferDestroy([=] {
    vkDestroyImageView(vkDevice, from, nullptr);
    vkDestroyImageView(vkDevice, to, nullptr);
  });
}

// ---------------------------------------------------------------------------
// Submission

void ContextImpl::Flush() {
  Gpu& gpu = device_->gpu();
  if (!gpu.HasPendingCommands()) return;
  EndRendering();
  queries_->Suspend(Commands());
  gpu.Submit();
  // A new command buffer starts with no state bound.
  boundPipeline_ = nullptr;
  descriptorsDirty_ = vertexBuffersDirty_ = true;
  dynamicDirty_.All();
  queries_->Resume(Commands());
}

}  // namespace rhi::vk
