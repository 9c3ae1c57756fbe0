// Dual depth peeling (Bavoil & Myers 2008; shaders_hlsl/oit/dual_depth_peeling.fxh):
// two layers per geometry pass, the nearest and the farthest not yet peeled.
//   Init                 the depth range of every pixel's fragments (MAX of (-z, z))
//   Peel, BlendBack (x P) peel the range's two ends: the nearest under the front
//                        accumulation, the farthest over the frame (BlendBack)
//   BlendFront           the front accumulation over the frame
// P = ceil(N / 2) peeling passes keep N layers: the N/2 nearest and the N/2
// farthest of each pixel, all of them where it has at most N. The depth ranges
// and the front accumulations ping-pong between two targets each (a pass reads one,
// writes the other); the back layer is read right after its pass.
//
// Coloured transmission (TransmissionFactor per channel) holds throughout: the front
// keeps 1 - T per channel in a target of its own, and the back layers go over the
// frame with dual-source blending (frame = a c + T * frame, T in SV_Target1), where
// B&M's SRC_ALPHA / INV_SRC_ALPHA has one transmission for all channels. The front
// sums in float and meets the RGBA8 frame once, so where a partial composite passes 1
// the frame clamps it at other places than depth peeling's layer-by-layer composite.
#include <string>

#include "oit/peeling_targets.h"
#include "renderer/effect_files.h"

namespace renderer::oit {
namespace {

using rhi::ComPtr;

// One pass's outputs that the next pass reads.
struct DualTargets {
  ColourTarget range, frontColour, frontOpacity;

  bool Create(rhi::Device* device, const FrameDesc& frame) {
    return range.Create(device, frame, rhi::DXGI_FORMAT_R32G32_FLOAT) &&
           frontColour.Create(device, frame, rhi::DXGI_FORMAT_R16G16B16A16_FLOAT) &&
           frontOpacity.Create(device, frame, rhi::DXGI_FORMAT_R16G16B16A16_FLOAT);
  }
  uint64_t bytes() const { return range.bytes + frontColour.bytes + frontOpacity.bytes; }
};

class DualDepthPeelingMethod final : public Method {
 public:
  explicit DualDepthPeelingMethod(uint32_t layers) : peels_((layers + 1) / 2) {
    passes_ = {"Init", "LoadFrame"};
    for (uint32_t i = 0; i < peels_; ++i) passes_.insert(passes_.end(), {"Peel", "BlendBack"});
    passes_.insert(passes_.end(), {"BlendFront", "StoreFrame"});
  }

  bool Initialize(const MethodInfo& info, const MethodSetup& setup, std::string* error) {
    rhi::Device* device = setup.device;
    if (!pair_[0].Create(device, setup.frame) || !pair_[1].Create(device, setup.frame) ||
        !backColour_.Create(device, setup.frame, rhi::DXGI_FORMAT_R16G16B16A16_FLOAT) ||
        !backOpacity_.Create(device, setup.frame, rhi::DXGI_FORMAT_R16G16B16A16_FLOAT))
      return *error = std::string(info.name) + ": creating the targets failed", false;
    effect_ = LoadMethodEffect(device, info, nullptr, {}, error);
    if (!effect_ || !composite_.Create(device, setup.frame, effect_.Get(), error) ||
        !(blendBack_ = FindPass(effect_.Get(), nullptr, "BlendBack", error)) ||
        !(blendFront_ = FindPass(effect_.Get(), nullptr, "BlendFront", error)))
      return false;
    effect_->GetVariableByName("BackColour")->AsShaderResource()->SetResource(backColour_.srv.Get());
    effect_->GetVariableByName("BackOpacity")->AsShaderResource()->SetResource(backOpacity_.srv.Get());
    return true;
  }

  void Render(const RenderArgs& a) override {
    size_t pass = 0;
    a.marks->BeginPass(pass++);
    Init(a);
    a.marks->BeginPass(pass++);
    composite_.Load(a.context, a.targets.frameView);
    for (uint32_t i = 1; i <= peels_; ++i) {
      a.marks->BeginPass(pass++);
      Peel(a, pair_[(i - 1) % 2], pair_[i % 2]);
      a.marks->BeginPass(pass++);
      DrawOverFrame(a.context, composite_.rtv(), blendBack_);
    }
    a.marks->BeginPass(pass++);
    const DualTargets& last = pair_[peels_ % 2];
    effect_->GetVariableByName("FrontColour")->AsShaderResource()->SetResource(last.frontColour.srv.Get());
    effect_->GetVariableByName("FrontOpacity")->AsShaderResource()->SetResource(last.frontOpacity.srv.Get());
    DrawOverFrame(a.context, composite_.rtv(), blendFront_);
    a.marks->BeginPass(pass);
    composite_.Store(a.context, a.targets.frame);
  }

  uint64_t MemoryBytes() const override {
    return pair_[0].bytes() + pair_[1].bytes() + backColour_.bytes + backOpacity_.bytes + composite_.bytes();
  }
  const std::vector<std::string>& PassNames() const override { return passes_; }

 private:
  // The depth range of every pixel into pair_[0], whose front starts empty.
  void Init(const RenderArgs& a) const {
    rhi::DeviceContext* ctx = a.context;
    UnbindPixelShaderResources(ctx);  // the last frame's BlendFront read pair_[0]
    const float noRange[4] = {-1, -1, 0, 0}, empty[4] = {0, 0, 0, 0};
    const DualTargets& first = pair_[0];
    ctx->ClearRenderTargetView(first.range.rtv(), noRange);
    ctx->ClearRenderTargetView(first.frontColour.rtv(), empty);
    ctx->ClearRenderTargetView(first.frontOpacity.rtv(), empty);
    rhi::RenderTargetView* range = first.range.rtv();
    ctx->OMSetRenderTargets(1, &range, a.targets.depth);
    a.geometry->Draw(ctx, "Init", DrawOrder::AsSubmitted);
  }

  // The two ends of `from`'s ranges: the nearest under its front into `to`, the
  // farthest into the back layer; what lies between them into `to`'s ranges.
  void Peel(const RenderArgs& a, const DualTargets& from, const DualTargets& to) const {
    rhi::DeviceContext* ctx = a.context;
    UnbindPixelShaderResources(ctx);  // `to` was the last pass's input, the back layer BlendBack's
    const float noRange[4] = {-1, -1, 0, 0}, empty[4] = {0, 0, 0, 0};
    ctx->ClearRenderTargetView(to.range.rtv(), noRange);
    for (const ColourTarget* t : {&to.frontColour, &to.frontOpacity, &backColour_, &backOpacity_})
      ctx->ClearRenderTargetView(t->rtv(), empty);
    rhi::RenderTargetView* targets[5] = {to.range.rtv(), to.frontColour.rtv(), to.frontOpacity.rtv(),
                                         backColour_.rtv(), backOpacity_.rtv()};
    ctx->OMSetRenderTargets(5, targets, a.targets.depth);
    a.geometry->SetShaderResource("DepthRange", from.range.srv.Get());
    a.geometry->SetShaderResource("FrontColour", from.frontColour.srv.Get());
    a.geometry->SetShaderResource("FrontOpacity", from.frontOpacity.srv.Get());
    a.geometry->Draw(ctx, "Peel", DrawOrder::AsSubmitted);
  }

  const uint32_t peels_;
  std::vector<std::string> passes_;
  DualTargets pair_[2];
  ColourTarget backColour_, backOpacity_;
  FloatComposite composite_;  // the layers over the opaque frame
  ComPtr<fx::Effect> effect_;
  fx::EffectPass *blendBack_ = nullptr, *blendFront_ = nullptr;
};

std::unique_ptr<Method> CreateDualDepthPeeling(const MethodInfo& info, const MethodSetup& setup,
                                               std::string* error) {
  if (setup.peelLayers == 0) return *error = std::string(info.name) + ": peelLayers must be at least 1", nullptr;
  auto method = std::make_unique<DualDepthPeelingMethod>(setup.peelLayers);
  if (!method->Initialize(info, setup, error)) return nullptr;
  return method;
}

}  // namespace

extern const MethodInfo kDualDepthPeeling{
    "dual-depth-peeling", "oit/dual_depth_peeling.fxh", kNeedsFloat32Blend | kNeedsDualSourceBlend,
    DrawOrder::AsSubmitted,
    "dual depth peeling: the N/2 nearest and farthest layers, 2 a pass, coloured transmission through "
    "dual-source blending (Bavoil & Myers 2008)",
    CreateDualDepthPeeling,
    Exactness::kExactWithEnoughLayers};

}  // namespace renderer::oit
