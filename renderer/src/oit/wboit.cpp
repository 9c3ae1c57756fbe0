// Weighted blended OIT (document 000, Tables 1 and 2; shaders_hlsl/oit/wboit.fxh)
// and the machinery it shares with colored OIT (colored.cpp).
#include "oit/weighted_blended.h"

#include "fx/effect.h"
#include "renderer/effect_files.h"
#include "rhi/format_info.h"

namespace renderer::oit {
namespace {

using rhi::ComPtr;

// A render target the method accumulates into and the compose pass reads.
struct AccumulationTarget {
  ComPtr<rhi::Texture2D> texture;
  ComPtr<rhi::RenderTargetView> rtv;
  ComPtr<rhi::ShaderResourceView> srv;
  uint64_t bytes = 0;

  bool Create(rhi::Device* device, const FrameDesc& frame, rhi::DXGI_FORMAT format) {
    const rhi::TEXTURE2D_DESC d{frame.width,         frame.height, 1, 1, format, {frame.sampleCount, 0},
                                rhi::USAGE_DEFAULT, rhi::BIND_RENDER_TARGET | rhi::BIND_SHADER_RESOURCE,
                                0,                   0};
    bytes = rhi::TextureBytes(d);
    return rhi::SUCCEEDED(device->CreateTexture2D(&d, nullptr, texture.GetAddressOf())) &&
           rhi::SUCCEEDED(device->CreateRenderTargetView(texture.Get(), nullptr, rtv.GetAddressOf())) &&
           rhi::SUCCEEDED(device->CreateShaderResourceView(texture.Get(), nullptr, srv.GetAddressOf()));
  }
};

class WeightedBlendedMethod final : public Method {
 public:
  explicit WeightedBlendedMethod(bool transmission) : transmission_(transmission) {}

  bool Initialize(const MethodInfo& info, const MethodSetup& setup, std::string* error) {
    // Table 1's targets: accum (R16G16B16A16_FLOAT) and revealage (R8_UNORM).
    if (!accum_.Create(setup.device, setup.frame, rhi::DXGI_FORMAT_R16G16B16A16_FLOAT) ||
        !revealage_.Create(setup.device, setup.frame, rhi::DXGI_FORMAT_R8_UNORM)) {
      *error = std::string(info.name) + ": creating accum and revealage failed";
      return false;
    }
    effect_ = LoadMethodEffect(setup.device, info, nullptr, {}, error);
    if (!effect_ || !(compose_ = FindPass(effect_.Get(), nullptr, "Compose", error))) return false;
    effect_->GetVariableByName("Accum")->AsShaderResource()->SetResource(accum_.srv.Get());
    effect_->GetVariableByName("Revealage")->AsShaderResource()->SetResource(revealage_.srv.Get());
    return true;
  }

  void Render(const RenderArgs& a) override {
    rhi::DeviceContext* ctx = a.context;
    a.marks->BeginPass(0);
    const float zero[4] = {0, 0, 0, 0}, one[4] = {1, 0, 0, 0};
    ctx->ClearRenderTargetView(accum_.rtv.Get(), zero);
    ctx->ClearRenderTargetView(revealage_.rtv.Get(), one);
    rhi::RenderTargetView* targets[3] = {accum_.rtv.Get(), revealage_.rtv.Get(), a.targets.frame};
    ctx->OMSetRenderTargets(transmission_ ? 3 : 2, targets, a.targets.depth);
    a.geometry->Draw(ctx, "Transparency", DrawOrder::AsSubmitted);

    a.marks->BeginPass(1);
    rhi::RenderTargetView* frame = a.targets.frame;
    ctx->OMSetRenderTargets(1, &frame, nullptr);  // unbinds accum and revealage from output
    ctx->IASetInputLayout(nullptr);
    ctx->IASetPrimitiveTopology(rhi::PRIMITIVE_TOPOLOGY_TRIANGLELIST);
    compose_->Apply(0, ctx);
    ctx->Draw(3, 0);
  }

  uint64_t MemoryBytes() const override { return accum_.bytes + revealage_.bytes; }
  const std::vector<std::string>& PassNames() const override { return kPasses; }

 private:
  inline static const std::vector<std::string> kPasses = {"Transparency", "Compose"};
  bool transmission_;
  AccumulationTarget accum_, revealage_;
  ComPtr<fx::Effect> effect_;
  fx::EffectPass* compose_ = nullptr;
};

std::unique_ptr<Method> CreateWboit(const MethodInfo& info, const MethodSetup& setup, std::string* error) {
  return CreateWeightedBlended(info, setup, false, error);
}

}  // namespace

std::unique_ptr<Method> CreateWeightedBlended(const MethodInfo& info, const MethodSetup& setup, bool transmission,
                                              std::string* error) {
  auto method = std::make_unique<WeightedBlendedMethod>(transmission);
  if (!method->Initialize(info, setup, error)) return nullptr;
  return method;
}

extern const MethodInfo kWboit{"wboit", "oit/wboit.fxh", 0, DrawOrder::AsSubmitted,
                               "weighted blended OIT, Tables 1 + 2 (document 000)", CreateWboit};

}  // namespace renderer::oit
