#version 450
// DrawAuto's GPU step: turns the transform feedback byte counter of a
// stream-output buffer into VkDrawIndirectCommand arguments, so the CPU never
// waits for the count. Layout: see StreamOutCounter in resources.h.
layout(local_size_x = 1) in;

layout(std430, set = 0, binding = 0) buffer Counter {
  uint byteCount;   // written by vkCmdEndTransformFeedbackEXT
  uint unused[3];
  uint vertexCount;  // VkDrawIndirectCommand
  uint instanceCount;
  uint firstVertex;
  uint firstInstance;
};

layout(push_constant) uniform Params {
  uint vertexStride;
  uint vertexBufferOffset;  // IASetVertexBuffers' offset: those bytes are not drawn
};

void main() {
  uint bytes = byteCount > vertexBufferOffset ? byteCount - vertexBufferOffset : 0u;
  vertexCount = vertexStride == 0u ? 0u : bytes / vertexStride;
  instanceCount = 1u;
  firstVertex = 0u;
  firstInstance = 0u;
}
