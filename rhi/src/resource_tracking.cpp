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

void TrackedResource::Record(const Access& use, uint64_t renderingInstance, VkMemoryBarrier2* barrier) {
  const bool sameAttachmentPass = renderingInstance != 0 && renderingInstance == writeRenderingInstance_ &&
                                  use.stages == writeStages_ && readStagesSinceWrite_ == 0;
  if (use.write) {
    if (!sameAttachmentPass && (writeStages_ | readStagesSinceWrite_) != 0) {
      // Write after write needs the writes made visible; write after read only
      // needs the reads to have executed.
      Wait(barrier, writeStages_ | readStagesSinceWrite_, writeAccess_, use);
    }
    writeStages_ = use.stages;
    writeAccess_ = use.access & kWriteAccess;
    readStagesSinceWrite_ = 0;
    readAccessSinceWrite_ = 0;
    writeRenderingInstance_ = renderingInstance;
    return;
  }
  // Read after write: wait once per reading stage/access.
  if (writeStages_ != 0 && !IsVisibleTo(use)) Wait(barrier, writeStages_, writeAccess_, use);
  readStagesSinceWrite_ |= use.stages;
  readAccessSinceWrite_ |= use.access;
}

}  // namespace rhi::vk
