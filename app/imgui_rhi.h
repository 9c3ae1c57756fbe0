// Dear ImGui renderer backend over the project's D3D11-shaped RHI (rhi/rhi.h).
//
// The counterpart of Dear ImGui's imgui_impl_dx11 with rhi:: in place of ID3D11*:
// the font atlas is an IMMUTABLE R8G8B8A8_UNORM texture with an SRV and a linear/wrap
// sampler; vertices and indices go into DYNAMIC buffers written with MAP_WRITE_DISCARD
// and regrown when a frame needs more; blending is SRC_ALPHA / INV_SRC_ALPHA (alpha:
// ONE / INV_SRC_ALPHA), culling off, scissor test on with one rect per draw command,
// no depth. Shaders are shaders_hlsl/imgui.hlsl (VSMain / PSMain), compiled in-process
// with hlsl::CompileHlsl. Nothing here touches Vulkan.
//
// ImTextureID is an rhi::ShaderResourceView*: ImGui::Image((ImTextureID)srv, ...) draws
// any texture the application has.
//
// Differences from imgui_impl_dx11: the RHI has no Get* methods, so the caller's
// pipeline state is not saved and restored; RenderDrawData leaves the ImGui state bound
// (input layout, buffers, shaders, blend, depth-stencil, rasterizer with the scissor test
// on, viewport, scissor, PS s0, VS b0; PS t0 is unbound at the end): call ClearState or
// rebind what later draws need. The caller binds the render target before calling it, as
// with imgui_impl_dx11; the viewport covers DisplaySize * FramebufferScale.
#pragma once

#include <string>

#include "rhi/rhi.h"

struct ImDrawData;

// Creates the shaders, states and font atlas. Call after ImGui::CreateContext() and after
// the font atlas is configured. Returns false with a reason in *error.
bool ImGui_ImplRhi_Init(rhi::Device* device, rhi::DeviceContext* context, std::string* error);
void ImGui_ImplRhi_Shutdown();
// Recreates the device objects if ImGui_ImplRhi_InvalidateDeviceObjects dropped them.
void ImGui_ImplRhi_NewFrame();
// Records the draw data into the bound render target.
void ImGui_ImplRhi_RenderDrawData(ImDrawData* drawData);

// Like imgui_impl_dx11: releases / recreates every RHI object (e.g. around a device change).
bool ImGui_ImplRhi_CreateDeviceObjects(std::string* error);
void ImGui_ImplRhi_InvalidateDeviceObjects();
