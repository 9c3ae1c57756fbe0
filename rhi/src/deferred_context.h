// Deferred contexts and command lists (deferred_context.cpp).
//
// A deferred context records every call as a closure that holds references to
// the objects it names; FinishCommandList moves the closures into a command
// list, and ExecuteCommandList replays them on the immediate context. This is
// the runtime emulation D3D11 itself uses when a driver reports no command-list
// support (FEATURE_THREADING.DriverCommandLists FALSE), and what DXVK's early
// versions did. Recording touches only the deferred context, so each one may
// record on its own thread.
#pragma once

#include <array>
#include <functional>
#include <vector>

#include "device.h"
#include "rhi/shader_bindings.h"

namespace rhi::vk {

// Everything ClearState resets, as the getters return it: what a command list
// starts from, what ExecuteCommandList(..., TRUE) restores, and what a deferred
// context's getters answer from.
struct ContextState {
  struct Stage {
    ComPtr<DeviceChild> shader;
    std::array<ComPtr<Buffer>, COMMONSHADER_CONSTANT_BUFFER_API_SLOT_COUNT> constantBuffers;
    std::array<ComPtr<ShaderResourceView>, COMMONSHADER_INPUT_RESOURCE_SLOT_COUNT> shaderResources;
    std::array<ComPtr<SamplerState>, COMMONSHADER_SAMPLER_SLOT_COUNT> samplers;
  };
  ComPtr<InputLayout> inputLayout;
  std::array<ComPtr<Buffer>, IA_VERTEX_INPUT_RESOURCE_SLOT_COUNT> vertexBuffers;
  std::array<UINT, IA_VERTEX_INPUT_RESOURCE_SLOT_COUNT> strides{}, offsets{};
  ComPtr<Buffer> indexBuffer;
  DXGI_FORMAT indexFormat = DXGI_FORMAT_UNKNOWN;
  UINT indexOffset = 0;
  PRIMITIVE_TOPOLOGY topology = PRIMITIVE_TOPOLOGY_UNDEFINED;
  std::array<Stage, kShaderStageCount> stages;
  std::array<ComPtr<UnorderedAccessView>, PS_CS_UAV_REGISTER_COUNT> computeUavs;
  std::array<ComPtr<Buffer>, SO_BUFFER_SLOT_COUNT> streamOut;
  ComPtr<RasterizerState> rasterizer;
  std::vector<VIEWPORT> viewports;
  std::vector<RECT> scissors;
  std::array<ComPtr<RenderTargetView>, SIMULTANEOUS_RENDER_TARGET_COUNT> renderTargets;
  ComPtr<DepthStencilView> depthStencil;
  std::array<ComPtr<UnorderedAccessView>, PS_CS_UAV_REGISTER_COUNT> graphicsUavs;
  ComPtr<BlendState> blend;
  std::array<FLOAT, 4> blendFactor{1, 1, 1, 1};
  UINT sampleMask = DEFAULT_SAMPLE_MASK;
  ComPtr<DepthStencilState> depthStencilState;
  UINT stencilRef = 0;
  ComPtr<Predicate> predicate;
  BOOL predicateValue = FALSE;

  // Reads `context`'s state through its getters.
  void Capture(DeviceContext* context);
  // Binds this state on `context` (which ClearState left at the defaults).
  void Apply(DeviceContext* context) const;
};

class CommandListImpl final : public DeviceChildImpl<CommandList> {
 public:
  using Command = std::function<void(DeviceContext*)>;
  CommandListImpl(DeviceImpl* device, std::vector<Command> commands)
      : DeviceChildImpl(device), commands_(std::move(commands)) {}
  UINT GetContextFlags() override { return 0; }
  void Replay(DeviceContext* context) const {
    for (const Command& command : commands_) command(context);
  }

 private:
  std::vector<Command> commands_;
};

HRESULT CreateDeferredContext(DeviceImpl* device, DeviceContext** out);

}  // namespace rhi::vk
