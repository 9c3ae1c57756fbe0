// Automatic synchronization: every buffer and image remembers how the GPU last
// touched it, and a use that conflicts with that history needs a barrier.
//
// Images live in VK_IMAGE_LAYOUT_GENERAL for their whole life (D3D11 has no
// layouts, and GENERAL is valid for every use the backend makes), so the
// tracker only decides memory dependencies; the backend emits them as one
// global VkMemoryBarrier2 per batch.
#pragma once

#include <vulkan/vulkan.h>

#include <cstdint>

namespace rhi::vk {

struct Access {
  VkPipelineStageFlags2 stages = 0;
  VkAccessFlags2 access = 0;
  bool write = false;
};

// The access bits of a use that are writes (what a later use must wait for).
inline constexpr VkAccessFlags2 kWriteAccess =
    VK_ACCESS_2_SHADER_WRITE_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT | VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT |
    VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT | VK_ACCESS_2_TRANSFER_WRITE_BIT | VK_ACCESS_2_HOST_WRITE_BIT |
    VK_ACCESS_2_TRANSFORM_FEEDBACK_WRITE_BIT_EXT | VK_ACCESS_2_TRANSFORM_FEEDBACK_COUNTER_WRITE_BIT_EXT;

class TrackedResource {
 public:
  // Records `use` and adds to `barrier` what must be waited for before it.
  // `renderingInstance` is non-zero for attachment writes: attachment writes
  // within one rendering instance are ordered by the rasterizer, not barriers.
  void Use(const Access& use, uint64_t renderingInstance, VkMemoryBarrier2* barrier) {
    // Inline: draws repeat uses that change nothing (a read already made
    // visible since the last write, another attachment write in the same
    // rendering instance); only the others take the full path.
    if (!use.write ? IsVisibleTo(use) : IsSameAttachmentWrite(use, renderingInstance)) return;
    Record(use, renderingInstance, barrier);
  }
  uint64_t lastUseSerial = 0;

 private:
  bool IsVisibleTo(const Access& read) const {
    return (readStagesSinceWrite_ & read.stages) == read.stages && (readAccessSinceWrite_ & read.access) == read.access;
  }
  bool IsSameAttachmentWrite(const Access& write, uint64_t renderingInstance) const {
    return renderingInstance != 0 && renderingInstance == writeRenderingInstance_ && write.stages == writeStages_ &&
           (write.access & kWriteAccess) == writeAccess_ && readStagesSinceWrite_ == 0;
  }
  void Record(const Access& use, uint64_t renderingInstance, VkMemoryBarrier2* barrier);

  VkPipelineStageFlags2 writeStages_ = 0;
  VkAccessFlags2 writeAccess_ = 0;
  VkPipelineStageFlags2 readStagesSinceWrite_ = 0;
  VkAccessFlags2 readAccessSinceWrite_ = 0;
  uint64_t writeRenderingInstance_ = 0;
};

// Conventional uses.
namespace uses {
inline constexpr Access kVertexBuffer{VK_PIPELINE_STAGE_2_VERTEX_ATTRIBUTE_INPUT_BIT,
                                      VK_ACCESS_2_VERTEX_ATTRIBUTE_READ_BIT, false};
inline constexpr Access kIndexBuffer{VK_PIPELINE_STAGE_2_INDEX_INPUT_BIT, VK_ACCESS_2_INDEX_READ_BIT, false};
inline constexpr Access kIndirectArgs{VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT, VK_ACCESS_2_INDIRECT_COMMAND_READ_BIT,
                                      false};
inline constexpr Access kTransferRead{VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_READ_BIT, false};
inline constexpr Access kTransferWrite{VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, true};
inline constexpr Access kColorAttachment{VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                                         VK_ACCESS_2_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT,
                                         true};
inline constexpr Access kDepthAttachment{
    VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT,
    VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT | VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT, true};
// Depth and stencil tests through a read-only depth-stencil view.
inline constexpr Access kDepthAttachmentRead{
    VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT,
    VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT, false};
inline constexpr Access kTransformFeedbackWrite{
    VK_PIPELINE_STAGE_2_TRANSFORM_FEEDBACK_BIT_EXT,
    VK_ACCESS_2_TRANSFORM_FEEDBACK_WRITE_BIT_EXT | VK_ACCESS_2_TRANSFORM_FEEDBACK_COUNTER_READ_BIT_EXT |
        VK_ACCESS_2_TRANSFORM_FEEDBACK_COUNTER_WRITE_BIT_EXT,
    true};
inline constexpr Access kHostRead{VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT, false};
}  // namespace uses

}  // namespace rhi::vk
