// Document 001: weighted blended OIT with MSAA and a per-sample resolve, the
// per-pixel resolve it is compared with, and the variants of its discussion
// (shaders_hlsl/oit/wboit_msaa.fxh holds the passes, formulas and state blocks).
//
// The frame driver draws the opaque objects into the single-sampled frame; this
// method needs them multisampled, so it draws them again into its own targets
// through oit::Backdrop (pass Scene), and its resolve overwrites the whole frame.
#include "renderer/oit/wboit_msaa.h"

#include "fx/effect.h"
#include "renderer/effect_files.h"
#include "rhi/format_info.h"

namespace renderer::oit {
namespace {

using rhi::ComPtr;
using rhi::DXGI_FORMAT;

// What distinguishes the registered methods of this file.
struct Variant {
  bool perSample;  // the per-sample composite (false: average the targets, then composite per pixel)
  bool additive;   // C0 + Σ w·c (no product target, no division)
  bool srgbFrame;  // blend in linear colour: the composite target is R8G8B8A8_UNORM_SRGB
};

// A texture with the views the method uses of it.
struct Target {
  ComPtr<rhi::Texture2D> texture;
  ComPtr<rhi::RenderTargetView> rtv;
  ComPtr<rhi::ShaderResourceView> srv;
  ComPtr<rhi::DepthStencilView> dsv;
  uint64_t bytes = 0;

  bool Create(rhi::Device* device, const FrameDesc& frame, uint32_t samples, DXGI_FORMAT format, uint32_t bind) {
    const rhi::TEXTURE2D_DESC d{frame.width, frame.height, 1, 1, format, {samples, 0}, rhi::USAGE_DEFAULT, bind, 0, 0};
    bytes = rhi::TextureBytes(d);
    if (rhi::FAILED(device->CreateTexture2D(&d, nullptr, texture.GetAddressOf()))) return false;
    return (!(bind & rhi::BIND_RENDER_TARGET) ||
            rhi::SUCCEEDED(device->CreateRenderTargetView(texture.Get(), nullptr, rtv.GetAddressOf()))) &&
           (!(bind & rhi::BIND_SHADER_RESOURCE) ||
            rhi::SUCCEEDED(device->CreateShaderResourceView(texture.Get(), nullptr, srv.GetAddressOf()))) &&
           (!(bind & rhi::BIND_DEPTH_STENCIL) ||
            rhi::SUCCEEDED(device->CreateDepthStencilView(texture.Get(), nullptr, dsv.GetAddressOf())));
  }
};

constexpr uint32_t kColorBind = rhi::BIND_RENDER_TARGET | rhi::BIND_SHADER_RESOURCE;

class WboitMsaaMethod final : public Method {
 public:
  explicit WboitMsaaMethod(const Variant& variant) : variant_(variant) {}

  bool Initialize(const MethodInfo& info, const MethodSetup& setup, std::string* error) {
    samples_ = setup.msaaSamples;
    const DXGI_FORMAT composite =
        variant_.srgbFrame ? rhi::DXGI_FORMAT_R8G8B8A8_UNORM_SRGB : rhi::DXGI_FORMAT_R8G8B8A8_UNORM;
    if (!HasSamples(setup.device, info, composite, error)) return false;
    rhi::Device* device = setup.device;
    const FrameDesc& frame = setup.frame;
    bool made = opaque_.Create(device, frame, samples_, rhi::DXGI_FORMAT_R16G16B16A16_FLOAT, kColorBind) &&
                depth_.Create(device, frame, samples_, rhi::DXGI_FORMAT_D32_FLOAT, rhi::BIND_DEPTH_STENCIL) &&
                accum_.Create(device, frame, samples_, rhi::DXGI_FORMAT_R16G16B16A16_FLOAT, kColorBind);
    if (!variant_.additive)
      made = made && product_.Create(device, frame, samples_, rhi::DXGI_FORMAT_R16_FLOAT, kColorBind);
    if (variant_.perSample) {
      made = made && composite_.Create(device, frame, samples_, composite, rhi::BIND_RENDER_TARGET);
      // The frame is R8G8B8A8_UNORM: an sRGB composite resolves (in linear space) into
      // a texture of its own format, copied to the frame (one typeless family).
      if (variant_.srgbFrame) made = made && resolved_.Create(device, frame, 1, composite, rhi::BIND_RENDER_TARGET);
    } else {
      made = made && opaquePixels_.Create(device, frame, 1, rhi::DXGI_FORMAT_R16G16B16A16_FLOAT, kColorBind) &&
             accumPixels_.Create(device, frame, 1, rhi::DXGI_FORMAT_R16G16B16A16_FLOAT, kColorBind) &&
             productPixels_.Create(device, frame, 1, rhi::DXGI_FORMAT_R16_FLOAT, kColorBind);
    }
    if (!made) {
      *error = std::string(info.name) + ": creating its targets failed";
      return false;
    }
    effect_ = LoadMethodEffect(device, info, nullptr, {}, error);
    if (!effect_) return false;
    compose_ = FindPass(effect_.Get(), nullptr, variant_.perSample ? "Compose" : "ComposePerPixel", error);
    if (!compose_) return false;
    if (variant_.perSample) {
      SetTexture("OpaqueSamples", opaque_);
      SetTexture("AccumSamples", accum_);
      if (!variant_.additive) SetTexture("ProductSamples", product_);
    } else {
      SetTexture("OpaquePixels", opaquePixels_);
      SetTexture("AccumPixels", accumPixels_);
      SetTexture("ProductPixels", productPixels_);
    }
    return true;
  }

  void Render(const RenderArgs& a) override {
    rhi::DeviceContext* ctx = a.context;
    a.marks->BeginPass(0);
    a.backdrop->Draw(ctx, opaque_.rtv.Get(), depth_.dsv.Get());

    a.marks->BeginPass(1);
    const float zero[4] = {0, 0, 0, 0}, one[4] = {1, 0, 0, 0};
    ctx->ClearRenderTargetView(accum_.rtv.Get(), zero);
    rhi::RenderTargetView* targets[2] = {accum_.rtv.Get(), product_.rtv.Get()};
    if (!variant_.additive) ctx->ClearRenderTargetView(product_.rtv.Get(), one);
    ctx->OMSetRenderTargets(variant_.additive ? 1 : 2, targets, depth_.dsv.Get());
    a.geometry->Draw(ctx, "Transparency", DrawOrder::AsSubmitted);

    a.marks->BeginPass(2);
    rhi::ComPtr<rhi::Resource> frame;
    a.targets.frame->GetResource(frame.GetAddressOf());
    if (variant_.perSample) {
      rhi::RenderTargetView* composite = composite_.rtv.Get();
      ctx->OMSetRenderTargets(1, &composite, nullptr);  // unbinds accum and product from output
      DrawCompose(ctx);
      const DXGI_FORMAT format =
          variant_.srgbFrame ? rhi::DXGI_FORMAT_R8G8B8A8_UNORM_SRGB : rhi::DXGI_FORMAT_R8G8B8A8_UNORM;
      if (variant_.srgbFrame) {
        ctx->ResolveSubresource(resolved_.texture.Get(), 0, composite_.texture.Get(), 0, format);
        ctx->CopyResource(frame.Get(), resolved_.texture.Get());
      } else {
        ctx->ResolveSubresource(frame.Get(), 0, composite_.texture.Get(), 0, format);
      }
    } else {
      ctx->OMSetRenderTargets(0, nullptr, nullptr);
      ctx->ResolveSubresource(opaquePixels_.texture.Get(), 0, opaque_.texture.Get(), 0,
                              rhi::DXGI_FORMAT_R16G16B16A16_FLOAT);
      ctx->ResolveSubresource(accumPixels_.texture.Get(), 0, accum_.texture.Get(), 0,
                              rhi::DXGI_FORMAT_R16G16B16A16_FLOAT);
      ctx->ResolveSubresource(productPixels_.texture.Get(), 0, product_.texture.Get(), 0, rhi::DXGI_FORMAT_R16_FLOAT);
      rhi::RenderTargetView* target = a.targets.frame;
      ctx->OMSetRenderTargets(1, &target, nullptr);
      DrawCompose(ctx);
    }
  }

  uint64_t MemoryBytes() const override {
    uint64_t bytes = 0;
    for (const Target* t : {&opaque_, &depth_, &accum_, &product_, &composite_, &resolved_, &opaquePixels_,
                            &accumPixels_, &productPixels_})
      bytes += t->bytes;
    return bytes;
  }
  size_t FragmentPass() const override { return 1; }  // after Scene
  const std::vector<std::string>& PassNames() const override {
    return variant_.perSample ? kPerSamplePasses : kPerPixelPasses;
  }

  WboitMsaaTargets Targets() const {
    return {opaque_.srv.Get(), accum_.srv.Get(), product_.srv.Get(), samples_};
  }

 private:
  // The sample count for every format the method renders into, as
  // CheckMultisampleQualityLevels reports it (0 levels: the device has none).
  bool HasSamples(rhi::Device* device, const MethodInfo& info, DXGI_FORMAT composite, std::string* error) const {
    const struct {
      DXGI_FORMAT format;
      const char* name;
    } formats[] = {{rhi::DXGI_FORMAT_R16G16B16A16_FLOAT, "R16G16B16A16_FLOAT"},
                   {rhi::DXGI_FORMAT_R16_FLOAT, "R16_FLOAT"},
                   {rhi::DXGI_FORMAT_D32_FLOAT, "D32_FLOAT"},
                   {composite, variant_.srgbFrame ? "R8G8B8A8_UNORM_SRGB" : "R8G8B8A8_UNORM"}};
    for (const auto& f : formats) {
      rhi::UINT levels = 0;
      if (rhi::FAILED(device->CheckMultisampleQualityLevels(f.format, samples_, &levels)) || levels == 0) {
        *error = std::string(info.name) + ": the device has no " + std::to_string(samples_) + "x multisampled " +
                 f.name + " targets (CheckMultisampleQualityLevels)";
        return false;
      }
    }
    return true;
  }

  void SetTexture(const char* name, const Target& target) {
    effect_->GetVariableByName(name)->AsShaderResource()->SetResource(target.srv.Get());
  }

  void DrawCompose(rhi::DeviceContext* ctx) {
    ctx->IASetInputLayout(nullptr);
    ctx->IASetPrimitiveTopology(rhi::PRIMITIVE_TOPOLOGY_TRIANGLELIST);
    compose_->Apply(0, ctx);
    ctx->Draw(3, 0);
  }

  // "Scene": the opaque objects (scene.fx Opaque/Scene, the effect pass oit::Backdrop applies).
  inline static const std::vector<std::string> kPerSamplePasses = {"Scene", "Transparency", "Compose"};
  inline static const std::vector<std::string> kPerPixelPasses = {"Scene", "Transparency", "ComposePerPixel"};
  Variant variant_;
  uint32_t samples_ = 0;
  Target opaque_, depth_, accum_, product_;   // multisampled
  Target composite_, resolved_;               // per sample: the composite, and its sRGB resolve
  Target opaquePixels_, accumPixels_, productPixels_;  // per pixel: the averaged targets
  ComPtr<fx::Effect> effect_;
  fx::EffectPass* compose_ = nullptr;
};

template <bool perSample, bool additive, bool srgbFrame>
std::unique_ptr<Method> Create(const MethodInfo& info, const MethodSetup& setup, std::string* error) {
  auto method = std::make_unique<WboitMsaaMethod>(Variant{perSample, additive, srgbFrame});
  if (!method->Initialize(info, setup, error)) return nullptr;
  return method;
}

}  // namespace

std::optional<WboitMsaaTargets> GetWboitMsaaTargets(const Method& method) {
  const auto* msaa = dynamic_cast<const WboitMsaaMethod*>(&method);
  if (!msaa) return std::nullopt;
  return msaa->Targets();
}

extern const MethodInfo kWboitMsaa{"wboit-msaa", "oit/wboit_msaa.fxh", kNeedsMsaa, DrawOrder::AsSubmitted,
                                   "WBOIT with MSAA, resolved per sample (document 001); 4x (--msaa 8)",
                                   Create<true, false, false>};
extern const MethodInfo kWboitMsaaPerPixel{
    "wboit-msaa-per-pixel", "oit/wboit_msaa.fxh", kNeedsMsaa, DrawOrder::AsSubmitted,
    "document 001's targets averaged first, then composited per pixel (what per sample fixes)",
    Create<false, false, false>};
extern const MethodInfo kWboitMsaaAdditive{"wboit-msaa-additive", "oit/wboit_msaa_additive.fxh", kNeedsMsaa,
                                           DrawOrder::AsSubmitted,
                                           "document 001's discussion: plain additive, C0 + sum w*c, ONE/ONE",
                                           Create<true, true, false>};
extern const MethodInfo kWboitMsaaLinear{"wboit-msaa-linear", "oit/wboit_msaa_linear.fxh", kNeedsMsaa,
                                         DrawOrder::AsSubmitted,
                                         "document 001's discussion: additive in linear colour, sRGB frame",
                                         Create<true, true, true>};
extern const MethodInfo kWboitMsaaExposure{"wboit-msaa-exposure", "oit/wboit_msaa_exposure.fxh", kNeedsMsaa,
                                           DrawOrder::AsSubmitted,
                                           "document 001's discussion: additive, 1 - exp(-k c) instead of clamping",
                                           Create<true, true, false>};

}  // namespace renderer::oit
