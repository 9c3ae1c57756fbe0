// ID3DUserDefinedAnnotation on the Vulkan context: BeginEvent / EndEvent /
// SetMarker become VK_EXT_debug_utils command-buffer labels (seen by RenderDoc,
// Nsight and the validation layer's messages) when the instance enabled the
// extension, which it does with the validation layer; otherwise they do nothing.
#include "context.h"

namespace rhi::vk {

void Gpu::LoadDebugLabelEntryPoints() {
  vkCmdBeginDebugUtilsLabelEXT = reinterpret_cast<PFN_vkCmdBeginDebugUtilsLabelEXT>(
      vkGetInstanceProcAddr(instance_, "vkCmdBeginDebugUtilsLabelEXT"));
  vkCmdEndDebugUtilsLabelEXT = reinterpret_cast<PFN_vkCmdEndDebugUtilsLabelEXT>(
      vkGetInstanceProcAddr(instance_, "vkCmdEndDebugUtilsLabelEXT"));
  vkCmdInsertDebugUtilsLabelEXT = reinterpret_cast<PFN_vkCmdInsertDebugUtilsLabelEXT>(
      vkGetInstanceProcAddr(instance_, "vkCmdInsertDebugUtilsLabelEXT"));
  if (!vkCmdBeginDebugUtilsLabelEXT || !vkCmdEndDebugUtilsLabelEXT || !vkCmdInsertDebugUtilsLabelEXT)
    vkCmdBeginDebugUtilsLabelEXT = nullptr, vkCmdEndDebugUtilsLabelEXT = nullptr,
    vkCmdInsertDebugUtilsLabelEXT = nullptr;
}

void ContextImpl::BeginEvent(const char* name) {
  Gpu& gpu = device_->gpu();
  if (!gpu.vkCmdBeginDebugUtilsLabelEXT) return;
  VkDebugUtilsLabelEXT label{VK_STRUCTURE_TYPE_DEBUG_UTILS_LABEL_EXT};
  label.pLabelName = name ? name : "";
  gpu.vkCmdBeginDebugUtilsLabelEXT(Commands(), &label);
}

void ContextImpl::EndEvent() {
  Gpu& gpu = device_->gpu();
  if (gpu.vkCmdEndDebugUtilsLabelEXT) gpu.vkCmdEndDebugUtilsLabelEXT(Commands());
}

void ContextImpl::SetMarker(const char* name) {
  Gpu& gpu = device_->gpu();
  if (!gpu.vkCmdInsertDebugUtilsLabelEXT) return;
  VkDebugUtilsLabelEXT label{VK_STRUCTURE_TYPE_DEBUG_UTILS_LABEL_EXT};
  label.pLabelName = name ? name : "";
  gpu.vkCmdInsertDebugUtilsLabelEXT(Commands(), &label);
}

}  // namespace rhi::vk
