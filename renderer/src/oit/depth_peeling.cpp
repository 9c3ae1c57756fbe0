// Depth peeling (document 002, Everitt; shaders_hlsl/oit/depth_peeling.fxh):
// exact order-independent transparency, one geometry pass per depth layer.
//   PeelNearest      layer 0: the nearest translucent fragment in front of the opaque
//                    geometry (its depth buffer is a copy of the opaque depth, LESS)
//   Peel (x N-1)     layer k: the same over a fresh copy of the opaque depth, of the
//                    fragments strictly behind layer k-1 (its depth, read as a texture)
//   LoadFrame        the opaque frame into a float32 composite
//   Composite (x N)  the layers over the composite, N-1 first
//   StoreFrame       the composite into the frame, rounded once
//                    (ShowLayer instead of the last three: one layer alone)
// Every layer keeps its colour and opacity in a slice of two texture arrays;
// the two depth buffers ping-pong (one is written while the other is read).
//
// Until a layer is empty: an occlusion query around each layer's Composite counts
// the layer's pixels, and the next frame reads the counts without waiting (GetData;
// the RHI has no predication, D3D11's other way). Once a layer held nothing, the
// layers behind it hold nothing either, so the next frame peels up to that layer and
// skips the rest (as zero-length passes, so that the pass list stays the same). A
// scene whose depth complexity grows gets its new layers one frame late.
#include <string>

#include "oit/peeling_targets.h"
#include "renderer/effect_files.h"
#include "rhi/query_wait.h"

namespace renderer::oit {
namespace {

using rhi::ComPtr;

class DepthPeelingMethod final : public Method {
 public:
  explicit DepthPeelingMethod(uint32_t layers) : maxLayers_(layers), queries_(layers) {
    passes_.assign(layers, "Peel");
    passes_.front() = "PeelNearest";
    passes_.push_back("LoadFrame");
    passes_.insert(passes_.end(), layers, "Composite");
    passes_.push_back("StoreFrame");
  }

  bool Initialize(const MethodInfo& info, const MethodSetup& setup, std::string* error) {
    rhi::Device* device = setup.device;
    const rhi::QUERY_DESC occlusion{rhi::QUERY_OCCLUSION, 0};
    for (ComPtr<rhi::Query>& q : queries_)
      if (rhi::FAILED(device->CreateQuery(&occlusion, q.GetAddressOf())))
        return *error = std::string(info.name) + ": creating the occlusion queries failed", false;
    if (!colour_.CreateArray(device, setup.frame, rhi::DXGI_FORMAT_R16G16B16A16_FLOAT, maxLayers_) ||
        !opacity_.CreateArray(device, setup.frame, rhi::DXGI_FORMAT_R16G16B16A16_FLOAT, maxLayers_) ||
        !depth_[0].Create(device, setup.frame) || !depth_[1].Create(device, setup.frame))
      return *error = std::string(info.name) + ": creating the layers failed", false;
    effect_ = LoadMethodEffect(device, info, nullptr, {}, error);
    if (!effect_ || !composite_.Create(device, setup.frame, effect_.Get(), error) ||
        !(compositeLayer_ = FindPass(effect_.Get(), nullptr, "Composite", error)) ||
        !(showLayer_ = FindPass(effect_.Get(), nullptr, "ShowLayer", error)))
      return false;
    effect_->GetVariableByName("ColourLayers")->AsShaderResource()->SetResource(colour_.srv.Get());
    effect_->GetVariableByName("OpacityLayers")->AsShaderResource()->SetResource(opacity_.srv.Get());
    layer_ = effect_->GetVariableByName("Layer")->AsScalar();
    return true;
  }

  void Render(const RenderArgs& a) override {
    if (shownLayer_ >= 0) return RenderShownLayer(a);
    const uint32_t layers = LayersToPeel(a.context);
    size_t pass = 0;
    for (uint32_t k = 0; k < layers; ++k) {
      a.marks->BeginPass(pass++);
      Peel(a, k);
    }
    // The layers known to be empty: skipped, in the peeling and in the compositing.
    for (uint32_t k = layers; k < maxLayers_; ++k) a.marks->BeginPass(pass++);
    a.marks->BeginPass(pass++);
    composite_.Load(a.context, a.targets.frameView);
    for (uint32_t k = layers; k < maxLayers_; ++k) a.marks->BeginPass(pass++);
    for (uint32_t k = layers; k-- > 0;) {
      a.marks->BeginPass(pass++);
      Composite(a, k);
    }
    a.marks->BeginPass(pass++);
    composite_.Store(a.context, a.targets.frame);
    composited_ = layers;
  }

  uint64_t MemoryBytes() const override {
    return colour_.bytes + opacity_.bytes + composite_.bytes() + depth_[0].bytes + depth_[1].bytes;
  }
  const std::vector<std::string>& PassNames() const override { return passes_; }

  // Layers 0..layer are peeled (the ones behind it would not be shown), then ShowLayer.
  bool ShowLayer(uint32_t layer) override {
    if (layer >= maxLayers_) return false;
    shownLayer_ = int(layer);
    passes_.resize(layer + 1);
    passes_.push_back("ShowLayer");
    return true;
  }

  std::vector<uint64_t> LayerSamples(rhi::DeviceContext* context) const override {
    std::vector<uint64_t> samples(composited_);
    for (uint32_t k = 0; k < composited_; ++k)
      if (rhi::FAILED(rhi::WaitForData(context, queries_[k].Get(), &samples[k]))) return {};
    return samples;
  }

 private:
  // Every layer, unless the last frame's counts, where the GPU has them already,
  // found one empty: then up to that one (it may have filled since).
  uint32_t LayersToPeel(rhi::DeviceContext* context) const {
    for (uint32_t k = 0; k < composited_; ++k) {
      uint64_t samples = 0;
      if (context->GetData(queries_[k].Get(), &samples, sizeof samples, 0) != rhi::S_OK) break;
      if (samples == 0) return k + 1;
    }
    return maxLayers_;
  }

  // Layer k into slice k: the fragments behind layer k-1 (none to be behind for
  // k = 0), the nearest of them in front of the opaque depth.
  void Peel(const RenderArgs& a, uint32_t k) {
    rhi::DeviceContext* ctx = a.context;
    UnbindPixelShaderResources(ctx);  // this pass's depth buffer was the last pass's texture
    ComPtr<rhi::Resource> opaqueDepth;
    a.targets.depth->GetResource(opaqueDepth.GetAddressOf());
    const DepthTexture& depth = depth_[k % 2];
    ctx->CopyResource(depth.texture.Get(), opaqueDepth.Get());
    const float transparent[4] = {0, 0, 0, 0};
    ctx->ClearRenderTargetView(colour_.rtv(k), transparent);
    ctx->ClearRenderTargetView(opacity_.rtv(k), transparent);
    rhi::RenderTargetView* targets[2] = {colour_.rtv(k), opacity_.rtv(k)};
    ctx->OMSetRenderTargets(2, targets, depth.dsv.Get());
    if (k > 0) a.geometry->SetShaderResource("PreviousLayerDepth", depth_[(k - 1) % 2].srv.Get());
    a.geometry->Draw(ctx, k == 0 ? "PeelNearest" : "Peel", DrawOrder::AsSubmitted);
  }

  // Layer k over the composite, its pixels counted.
  void Composite(const RenderArgs& a, uint32_t k) {
    layer_->SetInt(int(k));
    a.context->Begin(queries_[k].Get());
    DrawOverFrame(a.context, composite_.rtv(), compositeLayer_);
    a.context->End(queries_[k].Get());
  }

  void RenderShownLayer(const RenderArgs& a) {
    const uint32_t shown = uint32_t(shownLayer_);
    for (uint32_t k = 0; k <= shown; ++k) {
      a.marks->BeginPass(k);
      Peel(a, k);
    }
    a.marks->BeginPass(shown + 1);
    layer_->SetInt(int(shown));
    DrawOverFrame(a.context, a.targets.frame, showLayer_);
  }

  const uint32_t maxLayers_;
  std::vector<std::string> passes_;
  ColourTarget colour_, opacity_;
  FloatComposite composite_;  // the layers over the opaque frame
  DepthTexture depth_[2];
  std::vector<ComPtr<rhi::Query>> queries_;  // one per layer: its pixels, counted by its Composite
  uint32_t composited_ = 0;                  // the layers the last frame composited
  int shownLayer_ = -1;
  ComPtr<fx::Effect> effect_;
  fx::EffectPass *compositeLayer_ = nullptr, *showLayer_ = nullptr;
  fx::EffectScalarVariable* layer_ = nullptr;
};

std::unique_ptr<Method> CreateDepthPeeling(const MethodInfo& info, const MethodSetup& setup, std::string* error) {
  if (setup.peelLayers == 0) return *error = std::string(info.name) + ": peelLayers must be at least 1", nullptr;
  auto method = std::make_unique<DepthPeelingMethod>(setup.peelLayers);
  if (!method->Initialize(info, setup, error)) return nullptr;
  return method;
}

}  // namespace

extern const MethodInfo kDepthPeeling{"depth-peeling", "oit/depth_peeling.fxh",
                                      kNeedsDualSourceBlend | kNeedsFloat32Blend,
                                      DrawOrder::AsSubmitted,
                                      "depth peeling: N exact layers composited back to front (document 002)",
                                      CreateDepthPeeling, Exactness::kExactWithEnoughLayers};

}  // namespace renderer::oit
