// Document 003's moment methods (shaders_hlsl/oit/moment_passes.fxh and the method
// includes): MBOIT, Moment Transparency, and Moment Transparency with the
// minimum-depth correction, its nearest depth in R32_FLOAT or (to show the thesis's
// precision finding) R16_FLOAT. Three passes: the moments (and the nearest depth),
// the weighted accumulation, the composite.
#include <string>

#include "oit/peeling_targets.h"
#include "renderer/effect_files.h"

namespace renderer::oit {
namespace {

using rhi::ComPtr;

struct MomentVariant {
  std::vector<std::string> passes;  // the moment pass, the weighted pass, "Compose"
  rhi::DXGI_FORMAT minDepthFormat;  // DXGI_FORMAT_UNKNOWN: no correction
};

class MomentMethod final : public Method {
 public:
  explicit MomentMethod(const MomentVariant& variant, float minDepthSlope)
      : variant_(variant), minDepthSlope_(minDepthSlope) {}

  bool Initialize(const MethodInfo& info, const MethodSetup& setup, std::string* error) {
    rhi::Device* device = setup.device;
    if (!totalOpticalDepth_.Create(device, setup.frame, rhi::DXGI_FORMAT_R32_FLOAT) ||
        !moments_.Create(device, setup.frame, rhi::DXGI_FORMAT_R32G32B32A32_FLOAT) ||
        !accum_.Create(device, setup.frame, rhi::DXGI_FORMAT_R16G16B16A16_FLOAT) ||
        (CorrectsMinDepth() && !minDepth_.Create(device, setup.frame, variant_.minDepthFormat)))
      return *error = std::string(info.name) + ": creating the moment targets failed", false;
    effect_ = LoadMethodEffect(device, info, nullptr, {}, error);
    if (!effect_ || !(compose_ = FindPass(effect_.Get(), nullptr, "Compose", error))) return false;
    effect_->GetVariableByName("TotalOpticalDepth")->AsShaderResource()->SetResource(totalOpticalDepth_.srv.Get());
    effect_->GetVariableByName("Accum")->AsShaderResource()->SetResource(accum_.srv.Get());
    return true;
  }

  void Render(const RenderArgs& a) override {
    rhi::DeviceContext* ctx = a.context;
    a.geometry->SetEffectVariables([&](fx::Effect& effect) {
      effect.GetVariableByName("NearPlane")->AsScalar()->SetFloat(a.nearPlane);
      effect.GetVariableByName("FarPlane")->AsScalar()->SetFloat(a.farPlane);
      effect.GetVariableByName("MinDepthSlope")->AsScalar()->SetFloat(minDepthSlope_);
    });

    a.marks->BeginPass(0);
    const float zero[4] = {0, 0, 0, 0}, farthest[4] = {a.farPlane, a.farPlane, a.farPlane, a.farPlane};
    ctx->ClearRenderTargetView(totalOpticalDepth_.rtv(), zero);
    ctx->ClearRenderTargetView(moments_.rtv(), zero);
    if (CorrectsMinDepth()) ctx->ClearRenderTargetView(minDepth_.rtv(), farthest);
    rhi::RenderTargetView* targets[3] = {totalOpticalDepth_.rtv(), moments_.rtv(),
                                         CorrectsMinDepth() ? minDepth_.rtv() : nullptr};
    ctx->OMSetRenderTargets(CorrectsMinDepth() ? 3 : 2, targets, a.targets.depth);
    a.geometry->Draw(ctx, variant_.passes[0].c_str(), DrawOrder::AsSubmitted);

    a.marks->BeginPass(1);
    ctx->ClearRenderTargetView(accum_.rtv(), zero);
    rhi::RenderTargetView* accum = accum_.rtv();
    ctx->OMSetRenderTargets(1, &accum, a.targets.depth);  // unbinds the moments from output
    a.geometry->SetShaderResource("TotalOpticalDepth", totalOpticalDepth_.srv.Get());
    a.geometry->SetShaderResource("Moments", moments_.srv.Get());
    if (CorrectsMinDepth()) a.geometry->SetShaderResource("MinDepth", minDepth_.srv.Get());
    a.geometry->Draw(ctx, variant_.passes[1].c_str(), DrawOrder::AsSubmitted);

    a.marks->BeginPass(2);
    DrawOverFrame(ctx, a.targets.frame, compose_);  // unbinds accum from output first
  }

  uint64_t MemoryBytes() const override {
    return totalOpticalDepth_.bytes + moments_.bytes + accum_.bytes + minDepth_.bytes;
  }
  const std::vector<std::string>& PassNames() const override { return variant_.passes; }

 private:
  bool CorrectsMinDepth() const { return variant_.minDepthFormat != rhi::DXGI_FORMAT_UNKNOWN; }

  const MomentVariant& variant_;
  const float minDepthSlope_;
  ColourTarget totalOpticalDepth_, moments_, accum_, minDepth_;
  ComPtr<fx::Effect> effect_;
  fx::EffectPass* compose_ = nullptr;
};

const MomentVariant kMboitVariant{{"GenerateMoments", "ResolveMoments", "Compose"}, rhi::DXGI_FORMAT_UNKNOWN};
const MomentVariant kTransparencyVariant{{"Moments", "Weights", "Compose"}, rhi::DXGI_FORMAT_UNKNOWN};
const MomentVariant kMinDepthVariant{{"Moments", "Weights", "Compose"}, rhi::DXGI_FORMAT_R32_FLOAT};
const MomentVariant kMinDepth16Variant{{"Moments", "Weights", "Compose"}, rhi::DXGI_FORMAT_R16_FLOAT};

std::unique_ptr<Method> Create(const MomentVariant& variant, const MethodInfo& info, const MethodSetup& setup,
                               std::string* error) {
  auto method = std::make_unique<MomentMethod>(variant, setup.minDepthSlope);
  if (!method->Initialize(info, setup, error)) return nullptr;
  return method;
}

std::unique_ptr<Method> CreateMboit(const MethodInfo& info, const MethodSetup& setup, std::string* error) {
  return Create(kMboitVariant, info, setup, error);
}
std::unique_ptr<Method> CreateMomentTransparency(const MethodInfo& info, const MethodSetup& setup,
                                                 std::string* error) {
  return Create(kTransparencyVariant, info, setup, error);
}
std::unique_ptr<Method> CreateMinDepth(const MethodInfo& info, const MethodSetup& setup, std::string* error) {
  return Create(kMinDepthVariant, info, setup, error);
}
std::unique_ptr<Method> CreateMinDepth16(const MethodInfo& info, const MethodSetup& setup, std::string* error) {
  return Create(kMinDepth16Variant, info, setup, error);
}

}  // namespace

extern const MethodInfo kMboit{"mboit", "oit/mboit.fxh", kNeedsFloat32Blend, DrawOrder::AsSubmitted,
                               "moment-based OIT, 4 power moments in float32 (document 003's base, I3D 2018)",
                               CreateMboit};
extern const MethodInfo kMomentTransparency{
    "moment-transparency", "oit/moment_transparency.fxh", kNeedsFloat32Blend, DrawOrder::AsSubmitted,
    "Moment Transparency: moments of optical depth, WBOIT-style weights (document 003)", CreateMomentTransparency};
extern const MethodInfo kMomentTransparencyMinDepth{
    "moment-transparency-mindepth", "oit/moment_transparency_mindepth.fxh", kNeedsFloat32Blend,
    DrawOrder::AsSubmitted, "Moment Transparency with document 003's minimum-depth correction (R32_FLOAT)",
    CreateMinDepth};
extern const MethodInfo kMomentTransparencyMinDepth16{
    "moment-transparency-mindepth-r16", "oit/moment_transparency_mindepth.fxh", kNeedsFloat32Blend,
    DrawOrder::AsSubmitted, "the same with the nearest depth in R16_FLOAT (document 003: too imprecise)",
    CreateMinDepth16};

}  // namespace renderer::oit
