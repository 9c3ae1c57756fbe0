#include "resource_tracking.h"

namespace rhi::vk {

namespace {
void Wait(VkMemoryBarrier2* barrier, VkPipelineStageFlags2 srcStages, VkAccessFlags2 srcAccess,
          const Access& use) {
  barrier->srcStageMask |= srcStages;
  barrier->srcAccessMask |= srcAccess;
  barrier->dstStageMask |= use.stages;
  barrier->dstAccessMask |= use.access;
}
}  // namespace

void TrackedResource::Use(const Access& use, uint64_t renderingInstance, VkMemoryBarrier2* barrier) {
  const bool sameAttachmentPass = renderingInstance != 0 && renderingInstance == writeRenderingInstance_ &&
                                  use.stages == writeStages_ && readStagesSinceWrite_ == 0;
  if (use.write) {
    if (!sameAttachmentPass && (writeStages_ | readStagesSinceWrite_) != 0) {
      // Write after write needs the writes made visible; write after read only
      // needs the reads to have executed.
      Wait(barrier, writeStages_ | readStagesSinceWrite_, writeAccess_, use);
    }
    writeStages_ = use.stages;
    writeAccess_ = use.access & (VK_ACCESS_2_SHADER_WRITE_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT |
                                 VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT |
                                 VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT | VK_ACCESS_2_TRANSFER_WRITE_BIT |
                                 VK_ACCESS_2_HOST_WRITE_BIT | VK_ACCESS_2_TRANSFORM_FEEDBACK_WRITE_BIT_EXT |
                                 VK_ACCESS_2_TRANSFORM_FEEDBACK_COUNTER_WRITE_BIT_EXT);
    readStagesSinceWrite_ = 0;
    readAccessSinceWrite_ = 0;
    writeRenderingInstance_ = renderingInstance;
    return;
  }
  // Read after write: wait once per reading stage/access.
  const bool alreadyVisible = (readStagesSinceWrite_ & use.stages) == use.stages &&
                              (readAccessSinceWrite_ & use.access) == use.access;
  if (writeStages_ != 0 && !alreadyVisible) Wait(barrier, writeStages_, writeAccess_, use);
  readStagesSinceWrite_ |= use.stages;
  readAccessSinceWrite_ |= use.access;
}

}  // namespace rhi::vk
