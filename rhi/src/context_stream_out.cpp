// Stream output and DrawAuto over VK_EXT_transform_feedback.
//
// Every stream-output buffer owns a counter (resources.h). Stream-out always
// resumes from that counter, so D3D11's offsets become counter writes: an
// explicit SOSetTargets offset is stored into the counter before the next
// stream-out, and -1 ("append") leaves it alone. DrawAuto then draws
// (counter - vertex buffer offset) / stride vertices, with the count turned
// into indirect arguments on the GPU.
#include "context.h"
#include "pipelines.h"
#include "resources.h"
#include "shaders.h"

namespace rhi::vk {

namespace {
constexpr Access kCounterComputeUpdate{VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                                       VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                                       true};
constexpr Access kCounterNativeDrawRead{VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT,
                                        VK_ACCESS_2_TRANSFORM_FEEDBACK_COUNTER_READ_BIT_EXT, false};
}  // namespace

void ContextImpl::PrepareStreamOutTargets() {
  for (StreamOutTarget& target : streamOut_) {
    if (!target.buffer) continue;
    StreamOutCounter& counter = target.buffer->soCounter();
    if (target.offsetPending || !counter.valid) {
      // D3D11: an explicit offset restarts there; -1 on a never-written buffer starts at 0.
      const uint32_t start = target.offset == UINT(-1) ? 0 : target.offset;
      EndRendering();
      Use(counter, uses::kTransferWrite);
      FlushBarriers();
      vkCmdUpdateBuffer(Commands(), counter.buffer, StreamOutCounter::kCounterOffset, sizeof start, &start);
      counter.valid = true;
      target.offsetPending = false;
    }
    Use(*target.buffer, uses::kTransformFeedbackWrite);
    Use(counter, uses::kTransformFeedbackWrite);
  }
}

void ContextImpl::BeginStreamOut(const GraphicsPipeline& pipeline) {
  if (!pipeline.streamOutput) return;
  Gpu& gpu = device_->gpu();
  std::array<VkBuffer, SO_BUFFER_SLOT_COUNT> counters{};
  std::array<VkDeviceSize, SO_BUFFER_SLOT_COUNT> counterOffsets{};
  for (uint32_t slot = 0; slot < SO_BUFFER_SLOT_COUNT; ++slot) {
    BufferImpl* buffer = streamOut_[slot].buffer.Get();
    if (!buffer) continue;
    VkBuffer handle = buffer->handle();
    VkDeviceSize offset = 0;
    VkDeviceSize size = buffer->desc().ByteWidth;
    gpu.vkCmdBindTransformFeedbackBuffersEXT(Commands(), slot, 1, &handle, &offset, &size);
    counters[slot] = buffer->soCounter().buffer;
  }
  gpu.vkCmdBeginTransformFeedbackEXT(Commands(), 0, SO_BUFFER_SLOT_COUNT, counters.data(), counterOffsets.data());
}

void ContextImpl::EndStreamOut(const GraphicsPipeline& pipeline) {
  if (!pipeline.streamOutput) return;
  std::array<VkBuffer, SO_BUFFER_SLOT_COUNT> counters{};
  std::array<VkDeviceSize, SO_BUFFER_SLOT_COUNT> counterOffsets{};
  for (uint32_t slot = 0; slot < SO_BUFFER_SLOT_COUNT; ++slot)
    if (streamOut_[slot].buffer) counters[slot] = streamOut_[slot].buffer->soCounter().buffer;
  device_->gpu().vkCmdEndTransformFeedbackEXT(Commands(), 0, SO_BUFFER_SLOT_COUNT, counters.data(),
                                              counterOffsets.data());
}

void ContextImpl::WriteDrawAutoArgs(BufferImpl& buffer, UINT stride, UINT vertexBufferOffset) {
  StreamOutCounter& counter = buffer.soCounter();
  EndRendering();
  Use(counter, kCounterComputeUpdate);
  FlushBarriers();
  const ComputePipeline& pipeline = device_->pipelines().DrawAutoArgs();
  VkCommandBuffer commands = Commands();
  vkCmdBindPipeline(commands, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline.pipeline);
  VkDescriptorBufferInfo info{counter.buffer, 0, StreamOutCounter::kSize};
  VkWriteDescriptorSet write{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
  write.dstBinding = 0;
  write.descriptorCount = 1;
  write.descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
  write.pBufferInfo = &info;
  device_->gpu().vkCmdPushDescriptorSetKHR(commands, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline.layout->layout, 0, 1,
                                           &write);
  const uint32_t params[2] = {stride, vertexBufferOffset};
  vkCmdPushConstants(commands, pipeline.layout->layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof params, params);
  vkCmdDispatch(commands, 1, 1, 1);
}

void ContextImpl::DrawAuto() {
  if (predicationSkips_) return;
  BufferImpl* source = vertexBuffers_[0].buffer.Get();
  if (!source || !(source->desc().BindFlags & BIND_STREAM_OUTPUT)) {
    ReportDrawError("DrawAuto: input slot 0 must hold a buffer created with BIND_STREAM_OUTPUT");
    return;
  }
  StreamOutCounter& counter = source->soCounter();
  if (!counter.valid) return;  // nothing was ever streamed into it: zero vertices
  const UINT stride = vertexBuffers_[0].stride;
  const UINT offset = vertexBuffers_[0].offset;
  const bool native = device_->gpu().NativeDrawAuto() && device_->gpu().Caps().transformFeedbackDraw;
  if (!native) WriteDrawAutoArgs(*source, stride, offset);
  const GraphicsPipeline* pipeline =
      PrepareDraw("DrawAuto", &counter, native ? kCounterNativeDrawRead : uses::kIndirectArgs);
  if (!pipeline) return;
  BeginStreamOut(*pipeline);
  if (native) {
    device_->gpu().vkCmdDrawIndirectByteCountEXT(Commands(), 1, 0, counter.buffer, StreamOutCounter::kCounterOffset,
                                                 offset, stride);
  } else {
    vkCmdDrawIndirect(Commands(), counter.buffer, StreamOutCounter::kDrawArgsOffset, 1, 0);
  }
  EndStreamOut(*pipeline);
}

}  // namespace rhi::vk
