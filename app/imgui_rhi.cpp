// Dear ImGui renderer backend over the RHI; see imgui_rhi.h.
#include "imgui_rhi.h"

#include <imgui.h>

#include <algorithm>
#include <cstring>
#include <vector>

#include "fx/shader_directory.h"
#include "hlsl/hlsl_compiler.h"

using rhi::ComPtr;
using rhi::UINT;

namespace {


struct BackendData {
  rhi::Device* device = nullptr;
  rhi::DeviceContext* context = nullptr;
  ComPtr<rhi::Buffer> vertexBuffer, indexBuffer, constants;
  ComPtr<rhi::VertexShader> vertexShader;
  ComPtr<rhi::PixelShader> pixelShader;
  ComPtr<rhi::InputLayout> inputLayout;
  ComPtr<rhi::Texture2D> fontTexture;
  ComPtr<rhi::ShaderResourceView> fontView;
  ComPtr<rhi::SamplerState> fontSampler;
  ComPtr<rhi::BlendState> blendState;
  ComPtr<rhi::RasterizerState> rasterizerState;
  ComPtr<rhi::DepthStencilState> depthStencilState;
  int vertexBufferSize = 5000;  // in vertices / indices, as imgui_impl_dx11
  int indexBufferSize = 10000;
};

struct alignas(16) VertexConstants {
  float mvp[4][4];
};

BackendData* GetBackendData() {
  return ImGui::GetCurrentContext() ? static_cast<BackendData*>(ImGui::GetIO().BackendRendererUserData) : nullptr;
}

bool Compile(const char* entry, const char* profile, std::vector<uint32_t>* spirv, std::string* error) {
  hlsl::CompileResult result = hlsl::CompileHlslFile(fx::ShaderDirectory() + "/imgui.hlsl", entry, profile);
  if (!result.ok) {
    *error = result.FormatErrors();
    return false;
  }
  *spirv = std::move(result.spirv);
  return true;
}

bool Succeeded(rhi::HRESULT hr, const char* what, std::string* error) {
  if (rhi::SUCCEEDED(hr)) return true;
  *error = std::string("imgui_rhi: ") + what + " failed";
  return false;
}

bool CreateFontsTexture(BackendData* bd, std::string* error) {
  ImGuiIO& io = ImGui::GetIO();
  unsigned char* pixels = nullptr;
  int width = 0, height = 0;
  io.Fonts->GetTexDataAsRGBA32(&pixels, &width, &height);

  rhi::TEXTURE2D_DESC desc{};
  desc.Width = static_cast<UINT>(width);
  desc.Height = static_cast<UINT>(height);
  desc.MipLevels = 1;
  desc.ArraySize = 1;
  desc.Format = rhi::DXGI_FORMAT_R8G8B8A8_UNORM;
  desc.SampleDesc = {1, 0};
  desc.Usage = rhi::USAGE_IMMUTABLE;
  desc.BindFlags = rhi::BIND_SHADER_RESOURCE;
  rhi::SUBRESOURCE_DATA init{pixels, desc.Width * 4, 0};
  if (!Succeeded(bd->device->CreateTexture2D(&desc, &init, bd->fontTexture.ReleaseAndGetAddressOf()),
                 "CreateTexture2D(font atlas)", error) ||
      !Succeeded(bd->device->CreateShaderResourceView(bd->fontTexture.Get(), nullptr,
                                                      bd->fontView.ReleaseAndGetAddressOf()),
                 "CreateShaderResourceView(font atlas)", error))
    return false;
  io.Fonts->SetTexID(static_cast<ImTextureID>(bd->fontView.Get()));

  rhi::SAMPLER_DESC sampler;  // as imgui_impl_dx11: linear, wrap, one mip
  sampler.Filter = rhi::FILTER_MIN_MAG_MIP_LINEAR;
  sampler.AddressU = sampler.AddressV = sampler.AddressW = rhi::TEXTURE_ADDRESS_WRAP;
  sampler.ComparisonFunc = rhi::COMPARISON_ALWAYS;
  sampler.MinLOD = 0.0f;
  sampler.MaxLOD = 0.0f;
  return Succeeded(bd->device->CreateSamplerState(&sampler, bd->fontSampler.ReleaseAndGetAddressOf()),
                   "CreateSamplerState", error);
}

void SetupRenderState(ImDrawData* drawData, BackendData* bd) {
  rhi::DeviceContext* ctx = bd->context;
  rhi::VIEWPORT viewport{};
  viewport.Width = drawData->DisplaySize.x * drawData->FramebufferScale.x;
  viewport.Height = drawData->DisplaySize.y * drawData->FramebufferScale.y;
  viewport.MaxDepth = 1.0f;
  ctx->RSSetViewports(1, &viewport);

  const UINT stride = sizeof(ImDrawVert), offset = 0;
  rhi::Buffer* vb = bd->vertexBuffer.Get();
  ctx->IASetInputLayout(bd->inputLayout.Get());
  ctx->IASetVertexBuffers(0, 1, &vb, &stride, &offset);
  ctx->IASetIndexBuffer(bd->indexBuffer.Get(),
                        sizeof(ImDrawIdx) == 2 ? rhi::DXGI_FORMAT_R16_UINT : rhi::DXGI_FORMAT_R32_UINT, 0);
  ctx->IASetPrimitiveTopology(rhi::PRIMITIVE_TOPOLOGY_TRIANGLELIST);
  ctx->VSSetShader(bd->vertexShader.Get(), nullptr, 0);
  rhi::Buffer* cb = bd->constants.Get();
  ctx->VSSetConstantBuffers(0, 1, &cb);
  ctx->PSSetShader(bd->pixelShader.Get(), nullptr, 0);
  rhi::SamplerState* sampler = bd->fontSampler.Get();
  ctx->PSSetSamplers(0, 1, &sampler);
  ctx->GSSetShader(nullptr, nullptr, 0);
  ctx->HSSetShader(nullptr, nullptr, 0);
  ctx->DSSetShader(nullptr, nullptr, 0);
  ctx->SOSetTargets(0, nullptr, nullptr);

  const float blendFactor[4] = {0, 0, 0, 0};
  ctx->OMSetBlendState(bd->blendState.Get(), blendFactor, 0xffffffffu);
  ctx->OMSetDepthStencilState(bd->depthStencilState.Get(), 0);
  ctx->RSSetState(bd->rasterizerState.Get());
}

// Makes room for the frame's vertices and indices: regrown DYNAMIC buffers, as imgui_impl_dx11.
bool EnsureBuffers(BackendData* bd, const ImDrawData* drawData) {
  if (!bd->vertexBuffer || bd->vertexBufferSize < drawData->TotalVtxCount) {
    bd->vertexBuffer.Reset();
    bd->vertexBufferSize = std::max(bd->vertexBufferSize, drawData->TotalVtxCount + 5000);
    rhi::BUFFER_DESC desc{static_cast<UINT>(bd->vertexBufferSize * sizeof(ImDrawVert)), rhi::USAGE_DYNAMIC,
                          rhi::BIND_VERTEX_BUFFER, rhi::CPU_ACCESS_WRITE, 0, 0};
    if (rhi::FAILED(bd->device->CreateBuffer(&desc, nullptr, bd->vertexBuffer.GetAddressOf()))) return false;
  }
  if (!bd->indexBuffer || bd->indexBufferSize < drawData->TotalIdxCount) {
    bd->indexBuffer.Reset();
    bd->indexBufferSize = std::max(bd->indexBufferSize, drawData->TotalIdxCount + 10000);
    rhi::BUFFER_DESC desc{static_cast<UINT>(bd->indexBufferSize * sizeof(ImDrawIdx)), rhi::USAGE_DYNAMIC,
                          rhi::BIND_INDEX_BUFFER, rhi::CPU_ACCESS_WRITE, 0, 0};
    if (rhi::FAILED(bd->device->CreateBuffer(&desc, nullptr, bd->indexBuffer.GetAddressOf()))) return false;
  }
  return true;
}

}  // namespace

bool ImGui_ImplRhi_Init(rhi::Device* device, rhi::DeviceContext* context, std::string* error) {
  ImGuiIO& io = ImGui::GetIO();
  IM_ASSERT(io.BackendRendererUserData == nullptr && "a renderer backend is already initialised");
  auto* bd = new BackendData();
  bd->device = device;
  bd->context = context;
  io.BackendRendererUserData = bd;
  io.BackendRendererName = "imgui_impl_rhi";
  io.BackendFlags |= ImGuiBackendFlags_RendererHasVtxOffset;  // DrawIndexed's BaseVertexLocation
  if (!ImGui_ImplRhi_CreateDeviceObjects(error)) {
    ImGui_ImplRhi_Shutdown();
    return false;
  }
  return true;
}

void ImGui_ImplRhi_Shutdown() {
  BackendData* bd = GetBackendData();
  if (!bd) return;
  ImGui_ImplRhi_InvalidateDeviceObjects();
  ImGuiIO& io = ImGui::GetIO();
  io.BackendRendererName = nullptr;
  io.BackendRendererUserData = nullptr;
  delete bd;
}

void ImGui_ImplRhi_NewFrame() {
  BackendData* bd = GetBackendData();
  IM_ASSERT(bd && "ImGui_ImplRhi_Init was not called");
  if (!bd->fontSampler) {
    std::string error;
    ImGui_ImplRhi_CreateDeviceObjects(&error);
  }
}

bool ImGui_ImplRhi_CreateDeviceObjects(std::string* error) {
  BackendData* bd = GetBackendData();
  if (!bd) return false;
  if (bd->fontSampler) ImGui_ImplRhi_InvalidateDeviceObjects();
  rhi::Device* device = bd->device;

  std::vector<uint32_t> vsCode, psCode;
  if (!Compile("VSMain", "vs_5_0", &vsCode, error) || !Compile("PSMain", "ps_5_0", &psCode, error)) return false;
  if (!Succeeded(device->CreateVertexShader(vsCode.data(), vsCode.size() * 4, nullptr,
                                            bd->vertexShader.GetAddressOf()),
                 "CreateVertexShader", error) ||
      !Succeeded(device->CreatePixelShader(psCode.data(), psCode.size() * 4, nullptr, bd->pixelShader.GetAddressOf()),
                 "CreatePixelShader", error))
    return false;

  const rhi::INPUT_ELEMENT_DESC layout[] = {
      {"POSITION", 0, rhi::DXGI_FORMAT_R32G32_FLOAT, 0, static_cast<UINT>(offsetof(ImDrawVert, pos)),
       rhi::INPUT_PER_VERTEX_DATA, 0},
      {"TEXCOORD", 0, rhi::DXGI_FORMAT_R32G32_FLOAT, 0, static_cast<UINT>(offsetof(ImDrawVert, uv)),
       rhi::INPUT_PER_VERTEX_DATA, 0},
      {"COLOR", 0, rhi::DXGI_FORMAT_R8G8B8A8_UNORM, 0, static_cast<UINT>(offsetof(ImDrawVert, col)),
       rhi::INPUT_PER_VERTEX_DATA, 0},
  };
  if (!Succeeded(device->CreateInputLayout(layout, 3, vsCode.data(), vsCode.size() * 4,
                                           bd->inputLayout.GetAddressOf()),
                 "CreateInputLayout", error))
    return false;

  rhi::BUFFER_DESC cbDesc{sizeof(VertexConstants), rhi::USAGE_DYNAMIC, rhi::BIND_CONSTANT_BUFFER,
                          rhi::CPU_ACCESS_WRITE, 0, 0};
  if (!Succeeded(device->CreateBuffer(&cbDesc, nullptr, bd->constants.GetAddressOf()), "CreateBuffer(constants)",
                 error))
    return false;

  rhi::BLEND_DESC blend;
  blend.RenderTarget[0].BlendEnable = rhi::TRUE;
  blend.RenderTarget[0].SrcBlend = rhi::BLEND_SRC_ALPHA;
  blend.RenderTarget[0].DestBlend = rhi::BLEND_INV_SRC_ALPHA;
  blend.RenderTarget[0].BlendOp = rhi::BLEND_OP_ADD;
  blend.RenderTarget[0].SrcBlendAlpha = rhi::BLEND_ONE;
  blend.RenderTarget[0].DestBlendAlpha = rhi::BLEND_INV_SRC_ALPHA;
  blend.RenderTarget[0].BlendOpAlpha = rhi::BLEND_OP_ADD;
  blend.RenderTarget[0].RenderTargetWriteMask = rhi::COLOR_WRITE_ENABLE_ALL;
  rhi::RASTERIZER_DESC rasterizer;
  rasterizer.FillMode = rhi::FILL_SOLID;
  rasterizer.CullMode = rhi::CULL_NONE;
  rasterizer.ScissorEnable = rhi::TRUE;
  rasterizer.DepthClipEnable = rhi::TRUE;
  rhi::DEPTH_STENCIL_DESC depth;
  depth.DepthEnable = rhi::FALSE;
  depth.DepthWriteMask = rhi::DEPTH_WRITE_MASK_ALL;
  depth.DepthFunc = rhi::COMPARISON_ALWAYS;
  depth.StencilEnable = rhi::FALSE;
  if (!Succeeded(device->CreateBlendState(&blend, bd->blendState.GetAddressOf()), "CreateBlendState", error) ||
      !Succeeded(device->CreateRasterizerState(&rasterizer, bd->rasterizerState.GetAddressOf()),
                 "CreateRasterizerState", error) ||
      !Succeeded(device->CreateDepthStencilState(&depth, bd->depthStencilState.GetAddressOf()),
                 "CreateDepthStencilState", error))
    return false;

  return CreateFontsTexture(bd, error);
}

void ImGui_ImplRhi_InvalidateDeviceObjects() {
  BackendData* bd = GetBackendData();
  if (!bd) return;
  bd->fontSampler.Reset();
  bd->fontView.Reset();
  bd->fontTexture.Reset();
  ImGui::GetIO().Fonts->SetTexID(nullptr);
  bd->indexBuffer.Reset();
  bd->vertexBuffer.Reset();
  bd->blendState.Reset();
  bd->depthStencilState.Reset();
  bd->rasterizerState.Reset();
  bd->pixelShader.Reset();
  bd->constants.Reset();
  bd->inputLayout.Reset();
  bd->vertexShader.Reset();
}

void ImGui_ImplRhi_RenderDrawData(ImDrawData* drawData) {
  // Nothing to draw into while minimised.
  if (drawData->DisplaySize.x <= 0.0f || drawData->DisplaySize.y <= 0.0f) return;
  BackendData* bd = GetBackendData();
  if (!bd || !bd->fontSampler) return;
  if (drawData->TotalVtxCount == 0) return;
  if (!EnsureBuffers(bd, drawData)) return;
  rhi::DeviceContext* ctx = bd->context;

  // Every list into one vertex and one index buffer.
  rhi::MAPPED_SUBRESOURCE vertices{}, indices{};
  if (rhi::FAILED(ctx->Map(bd->vertexBuffer.Get(), 0, rhi::MAP_WRITE_DISCARD, 0, &vertices))) return;
  if (rhi::FAILED(ctx->Map(bd->indexBuffer.Get(), 0, rhi::MAP_WRITE_DISCARD, 0, &indices))) {
    ctx->Unmap(bd->vertexBuffer.Get(), 0);
    return;
  }
  auto* vtxDst = static_cast<ImDrawVert*>(vertices.pData);
  auto* idxDst = static_cast<ImDrawIdx*>(indices.pData);
  for (int n = 0; n < drawData->CmdListsCount; ++n) {
    const ImDrawList* list = drawData->CmdLists[n];
    std::memcpy(vtxDst, list->VtxBuffer.Data, list->VtxBuffer.Size * sizeof(ImDrawVert));
    std::memcpy(idxDst, list->IdxBuffer.Data, list->IdxBuffer.Size * sizeof(ImDrawIdx));
    vtxDst += list->VtxBuffer.Size;
    idxDst += list->IdxBuffer.Size;
  }
  ctx->Unmap(bd->vertexBuffer.Get(), 0);
  ctx->Unmap(bd->indexBuffer.Get(), 0);

  // Orthographic projection of DisplayPos .. DisplayPos + DisplaySize, column-major as the cbuffer.
  {
    rhi::MAPPED_SUBRESOURCE mapped{};
    if (rhi::FAILED(ctx->Map(bd->constants.Get(), 0, rhi::MAP_WRITE_DISCARD, 0, &mapped))) return;
    const float L = drawData->DisplayPos.x, R = drawData->DisplayPos.x + drawData->DisplaySize.x;
    const float T = drawData->DisplayPos.y, B = drawData->DisplayPos.y + drawData->DisplaySize.y;
    const VertexConstants constants{{
        {2.0f / (R - L), 0.0f, 0.0f, 0.0f},
        {0.0f, 2.0f / (T - B), 0.0f, 0.0f},
        {0.0f, 0.0f, 0.5f, 0.0f},
        {(R + L) / (L - R), (T + B) / (B - T), 0.5f, 1.0f},
    }};
    std::memcpy(mapped.pData, &constants, sizeof constants);
    ctx->Unmap(bd->constants.Get(), 0);
  }

  SetupRenderState(drawData, bd);

  // Draw commands, with our own offsets into the merged buffers.
  const ImVec2 clipOffset = drawData->DisplayPos, clipScale = drawData->FramebufferScale;
  const float fbWidth = drawData->DisplaySize.x * clipScale.x, fbHeight = drawData->DisplaySize.y * clipScale.y;
  int globalIdxOffset = 0, globalVtxOffset = 0;
  for (int n = 0; n < drawData->CmdListsCount; ++n) {
    const ImDrawList* list = drawData->CmdLists[n];
    for (int i = 0; i < list->CmdBuffer.Size; ++i) {
      const ImDrawCmd* cmd = &list->CmdBuffer[i];
      if (cmd->UserCallback != nullptr) {
        if (cmd->UserCallback == ImDrawCallback_ResetRenderState)
          SetupRenderState(drawData, bd);
        else
          cmd->UserCallback(list, cmd);
        continue;
      }
      // Clip rectangle in framebuffer pixels, clamped to the target.
      const float x0 = std::max(0.0f, (cmd->ClipRect.x - clipOffset.x) * clipScale.x);
      const float y0 = std::max(0.0f, (cmd->ClipRect.y - clipOffset.y) * clipScale.y);
      const float x1 = std::min(fbWidth, (cmd->ClipRect.z - clipOffset.x) * clipScale.x);
      const float y1 = std::min(fbHeight, (cmd->ClipRect.w - clipOffset.y) * clipScale.y);
      if (x1 <= x0 || y1 <= y0) continue;
      const rhi::RECT scissor{static_cast<rhi::INT>(x0), static_cast<rhi::INT>(y0), static_cast<rhi::INT>(x1),
                              static_cast<rhi::INT>(y1)};
      ctx->RSSetScissorRects(1, &scissor);
      rhi::ShaderResourceView* texture = static_cast<rhi::ShaderResourceView*>(cmd->GetTexID());
      ctx->PSSetShaderResources(0, 1, &texture);
      ctx->DrawIndexed(cmd->ElemCount, cmd->IdxOffset + static_cast<UINT>(globalIdxOffset),
                       static_cast<rhi::INT>(cmd->VtxOffset) + globalVtxOffset);
    }
    globalIdxOffset += list->IdxBuffer.Size;
    globalVtxOffset += list->VtxBuffer.Size;
  }
  // Unbind the texture so that the application may render into it next.
  rhi::ShaderResourceView* none = nullptr;
  ctx->PSSetShaderResources(0, 1, &none);
}
