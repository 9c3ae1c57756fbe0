// Particles sorted and blended in compute tiles (issue 19; AMD's D3D11 GPUParticles
// sample): compute-sorted (OVER back to front, `sorted`'s image) and compute-wboit
// (Tables 1-2 per pixel). The passes and why they are so: shaders_hlsl/oit/
// compute_tiles.fxh. The building blocks are the renderer's compute library: the
// prefix scan that document 004's fragment buffer uses, the radix sort, and
// dispatch sizes written by the GPU.
#include <algorithm>

#include "oit/fragment_buffers.h"
#include "renderer/compute/dispatch_args.h"
#include "renderer/compute/prefix_scan.h"
#include "renderer/compute/radix_sort.h"
#include "renderer/effect_files.h"
#include "renderer/oit/method.h"
#include "renderer/output_merger_probe.h"

namespace renderer::oit {
namespace {

using rhi::ComPtr;

constexpr uint32_t kTileSize = 16;  // compute_tiles.fxh: a group's pixels a side
constexpr uint32_t kThreads = 256;  // compute_tiles.fxh: threads of the one-dimensional passes
constexpr uint32_t kMaxGroups = 65535;
constexpr uint32_t kMinPairCapacity = 4096;  // FragmentStorage::tilePairsPerQuad
enum Slot : uint32_t { kDrawnSlot, kPairSlot, kSlots };  // DispatchArgs slots

uint32_t BitsFor(uint32_t values) {  // bits to tell `values` values apart
  uint32_t bits = 1;
  while (bits < 32 && (1ull << bits) < values) ++bits;
  return bits;
}

class ComputeTilesMethod final : public Method {
 public:
  // sortsByDepth: compute-sorted's back-to-front order; compute-wboit keeps buffer order.
  bool Initialize(const MethodInfo& info, const MethodSetup& setup, bool sortsByDepth, std::string* error) {
    info_ = &info;
    device_ = setup.device;
    width_ = setup.frame.width, height_ = setup.frame.height;
    tilesX_ = (width_ + kTileSize - 1) / kTileSize, tilesY_ = (height_ + kTileSize - 1) / kTileSize;
    capacity_ = std::max(setup.quadCapacity, 1u);
    sortsByDepth_ = sortsByDepth;
    passNames_ = sortsByDepth_ ? std::vector<std::string>{"Cull", "Sort", "Bin", "Blend"}
                               : std::vector<std::string>{"Cull", "Bin", "Blend"};
    if (capacity_ > kMaxGroups * kThreads) {
      *error = std::string(info.name) + ": " + std::to_string(capacity_) + " particles are more than one " +
               "dispatch of " + std::to_string(kThreads) + "-thread groups covers";
      return false;
    }
    const uint32_t tiles = tilesX_ * tilesY_;
    if (!visible_.CreateRaw(device_, capacity_) || !visibleOffsets_.CreateRaw(device_, capacity_) ||
        !keys_.CreateRaw(device_, capacity_) || !rects_.CreateRaw(device_, 2 * capacity_) ||
        !drawn_.CreateRaw(device_, 1) || !sortKeys_.CreateRaw(device_, capacity_) ||
        !sortValues_.CreateRaw(device_, capacity_) || !pairCounts_.CreateRaw(device_, capacity_) ||
        !pairOffsets_.CreateRaw(device_, capacity_) || !pairTotal_.CreateRaw(device_, 1) ||
        !tileStart_.CreateRaw(device_, tiles) || !tileEnd_.CreateRaw(device_, tiles) || !CreateComposite() ||
        !readback_.Create(device_, [](uint32_t, uint64_t) {})) {
      *error = std::string(info.name) + ": creating the buffers failed";
      return false;
    }
    visibleScan_ = compute::PrefixScan::Create(device_, capacity_, error);
    pairScan_ = compute::PrefixScan::Create(device_, capacity_, error);
    args_ = compute::DispatchArgs::Create(device_, kSlots, error);
    if (!visibleScan_ || !pairScan_ || !args_) return false;
    if (sortsByDepth_ && !(depthSort_ = compute::RadixSort::Create(device_, capacity_, error))) return false;
    if (!ProbeOutputMergerArithmetic(device_, &arithmetic_, error)) return false;
    effect_ = LoadMethodEffect(device_, info, nullptr, {}, error);
    return effect_ && (compact_ = FindPass(effect_.Get(), nullptr, "Compact", error)) &&
           (countTiles_ = FindPass(effect_.Get(), nullptr, "CountTiles", error)) &&
           (fillPairs_ = FindPass(effect_.Get(), nullptr, "FillPairs", error)) &&
           (tileRanges_ = FindPass(effect_.Get(), nullptr, "TileRanges", error)) &&
           CreatePairs(uint32_t(std::clamp<uint64_t>(uint64_t(capacity_) * setup.fragmentStorage.tilePairsPerQuad,
                                                     kMinPairCapacity, UINT32_MAX / 4)),
                       error);
  }

  void Render(const RenderArgs& a) override {
    rhi::DeviceContext* ctx = a.context;
    size_t pass = 0;
    a.marks->BeginPass(pass++);
    Cull(a);
    if (sortsByDepth_) {
      a.marks->BeginPass(pass++);
      depthSort_->Sort(ctx, sortKeys_.uav.Get(), sortValues_.uav.Get(), drawn_.uav.Get(), 0);
    }
    a.marks->BeginPass(pass++);
    Bin(ctx);
    a.marks->BeginPass(pass++);
    Blend(a);
  }

  // The bytes of every buffer and texture it made, its scans' and sorts' included.
  uint64_t MemoryBytes() const override {
    uint64_t bytes = composite_.bytes + args_->MemoryBytes() + visibleScan_->MemoryBytes() +
                     pairScan_->MemoryBytes() + pairSort_->MemoryBytes() +
                     (depthSort_ ? depthSort_->MemoryBytes() : 0);
    for (const ViewedBuffer* b : {&visible_, &visibleOffsets_, &keys_, &rects_, &drawn_, &sortKeys_, &sortValues_,
                                  &pairCounts_, &pairOffsets_, &pairTotal_, &pairTiles_, &pairParticles_,
                                  &tileStart_, &tileEnd_})
      bytes += b->bytes;
    return bytes;
  }
  const std::vector<std::string>& PassNames() const override { return passNames_; }
  // Blend, which shades the fragments (in compute: the pass rasterizes none).
  size_t FragmentPass() const override { return passNames_.size() - 1; }

  // The frame's pairs, read when its passes are recorded (the CPU waits for them):
  // more than the pair buffers held, they grow to 1.5x the total and the frame is
  // drawn again, so that no frame is ever shown with pairs missing.
  // Pairs that cannot be had (more than a buffer of words holds) are counted as lost.
  bool FrameNeedsRedraw(rhi::DeviceContext* ctx) override {
    const uint32_t total = readback_.ReadNow(ctx, pairTotal_.buffer.Get());
    lostPairs_ = 0;
    if (total <= pairCapacity_) return false;
    std::string error;
    if (CreatePairs(uint32_t(std::min<uint64_t>(uint64_t(total) * 3 / 2, UINT32_MAX / 4)), &error)) return true;
    lostPairs_ = total - pairCapacity_;
    return false;
  }
  // (tile, particle) pairs the last frame could not store: each a particle missing from a tile.
  uint64_t LostFragments() const override { return lostPairs_; }

 private:
  struct Composite {
    ComPtr<rhi::Texture2D> texture;
    ComPtr<rhi::UnorderedAccessView> uav;
    uint64_t bytes = 0;
  };

  bool CreateComposite() {
    const rhi::TEXTURE2D_DESC d{width_, height_, 1, 1, rhi::DXGI_FORMAT_R8G8B8A8_UNORM, {1, 0}, rhi::USAGE_DEFAULT,
                                rhi::BIND_UNORDERED_ACCESS, 0, 0};
    composite_.bytes = uint64_t(width_) * height_ * 4;
    return rhi::SUCCEEDED(device_->CreateTexture2D(&d, nullptr, composite_.texture.GetAddressOf())) &&
           rhi::SUCCEEDED(device_->CreateUnorderedAccessView(composite_.texture.Get(), nullptr,
                                                        composite_.uav.GetAddressOf()));
  }

  // The (tile, particle) pairs for `capacity` pairs, and the sort of them by tile.
  bool CreatePairs(uint32_t capacity, std::string* error) {
    ViewedBuffer tiles, particles;
    auto sort = compute::RadixSort::Create(device_, capacity, error);
    if (!sort) return false;
    if (!tiles.CreateRaw(device_, capacity) || !particles.CreateRaw(device_, capacity)) {
      *error = std::string(info_->name) + ": creating the pair buffers failed";
      return false;
    }
    pairCapacity_ = capacity;
    pairTiles_ = std::move(tiles), pairParticles_ = std::move(particles), pairSort_ = std::move(sort);
    return true;
  }

  void SetParams(fx::Effect& e) const {
    const int frameSize[4] = {int(width_), int(height_), 0, 0};
    e.GetVariableByName("TileFrameSize")->AsVector()->SetIntVector(frameSize);
    e.GetVariableByName("TilesX")->AsScalar()->SetInt(int(tilesX_));
    e.GetVariableByName("PrimitiveCapacity")->AsScalar()->SetInt(int(capacity_));
    e.GetVariableByName("PairCapacity")->AsScalar()->SetInt(int(pairCapacity_));
    e.GetVariableByName("UnormRoundsEachTerm")->AsScalar()->SetInt(arithmetic_.unormRoundsEachTerm);
    e.GetVariableByName("HalfRoundsTowardZero")->AsScalar()->SetInt(arithmetic_.halfRoundsTowardZero);
  }
  static void SetUav(fx::Effect& e, const char* name, rhi::UnorderedAccessView* uav) {
    e.GetVariableByName(name)->AsUnorderedAccessView()->SetUnorderedAccessView(uav);
  }
  static void SetSrv(fx::Effect& e, const char* name, rhi::ShaderResourceView* srv) {
    e.GetVariableByName(name)->AsShaderResource()->SetResource(srv);
  }

  // A pass of the method's own effect over the particles or pairs `slot` counts.
  void DispatchIndirect(rhi::DeviceContext* ctx, fx::EffectPass* pass, Slot slot) {
    args_->Bind(effect_.Get(), slot);
    pass->Apply(0, ctx);
    args_->Dispatch(ctx, slot);
    UnbindCompute(ctx);
  }
  static void UnbindCompute(rhi::DeviceContext* ctx) {
    rhi::ShaderResourceView* none[8] = {};
    ctx->CSSetShaderResources(0, 8, none);
    rhi::UnorderedAccessView* noUavs[rhi::PS_CS_UAV_REGISTER_COUNT] = {};
    ctx->CSSetUnorderedAccessViews(0, rhi::PS_CS_UAV_REGISTER_COUNT, noUavs, nullptr);
  }

  // Footprints, then the drawn particles compacted in buffer order with their count.
  void Cull(const RenderArgs& a) {
    rhi::DeviceContext* ctx = a.context;
    const rhi::UINT zero[4] = {0, 0, 0, 0};
    ctx->ClearUnorderedAccessViewUint(visible_.uav.Get(), zero);
    a.geometry->SetEffectVariables([&](fx::Effect& e) {
      SetParams(e);
      SetUav(e, "VisibleOut", visible_.uav.Get());
      SetUav(e, "KeysOut", keys_.uav.Get());
      SetUav(e, "RectsOut", rects_.uav.Get());
    });
    ctx->OMSetRenderTargets(0, nullptr, a.targets.depth);  // the frame's size for the points; not tested
    a.geometry->Draw(ctx, "Footprints", DrawOrder::AsSubmitted);
    ctx->OMSetRenderTargets(0, nullptr, nullptr);  // the UAVs and the depth are read next
    visibleScan_->Run(ctx, visible_.uav.Get(), visibleOffsets_.uav.Get(), drawn_.uav.Get());
    fx::Effect& e = *effect_.Get();
    SetParams(e);
    SetSrv(e, "Visible", visible_.srv.Get());
    SetSrv(e, "VisibleOffsets", visibleOffsets_.srv.Get());
    SetSrv(e, "Keys", keys_.srv.Get());
    SetUav(e, "SortKeysOut", sortKeys_.uav.Get());
    SetUav(e, "SortValuesOut", sortValues_.uav.Get());
    compact_->Apply(0, ctx);
    ctx->Dispatch((capacity_ + kThreads - 1) / kThreads, 1, 1);
    UnbindCompute(ctx);
  }

  // Every tile's list of particles, in the sorted order.
  void Bin(rhi::DeviceContext* ctx) {
    fx::Effect& e = *effect_.Get();
    const rhi::UINT zero[4] = {0, 0, 0, 0};
    ctx->ClearUnorderedAccessViewUint(pairCounts_.uav.Get(), zero);  // the scan reads past the count
    args_->Write(ctx, drawn_.uav.Get(), 0, kThreads, kDrawnSlot, capacity_);
    SetParams(e);
    SetSrv(e, "SortedValues", sortValues_.srv.Get());
    SetSrv(e, "Rects", rects_.srv.Get());
    SetUav(e, "PairCountsOut", pairCounts_.uav.Get());
    DispatchIndirect(ctx, countTiles_, kDrawnSlot);
    pairScan_->Run(ctx, pairCounts_.uav.Get(), pairOffsets_.uav.Get(), pairTotal_.uav.Get());
    SetSrv(e, "PairOffsets", pairOffsets_.srv.Get());
    SetUav(e, "PairTilesOut", pairTiles_.uav.Get());
    SetUav(e, "PairParticlesOut", pairParticles_.uav.Get());
    DispatchIndirect(ctx, fillPairs_, kDrawnSlot);
    pairSort_->Sort(ctx, pairTiles_.uav.Get(), pairParticles_.uav.Get(), pairTotal_.uav.Get(), 0,
                    BitsFor(tilesX_ * tilesY_));
    ctx->ClearUnorderedAccessViewUint(tileStart_.uav.Get(), zero);
    ctx->ClearUnorderedAccessViewUint(tileEnd_.uav.Get(), zero);
    args_->Write(ctx, pairTotal_.uav.Get(), 0, kThreads, kPairSlot, pairCapacity_);
    SetSrv(e, "PairTiles", pairTiles_.srv.Get());
    SetUav(e, "TileStartOut", tileStart_.uav.Get());
    SetUav(e, "TileEndOut", tileEnd_.uav.Get());
    DispatchIndirect(ctx, tileRanges_, kPairSlot);
  }

  // A group per tile over the opaque frame, into the composite, copied into the frame.
  void Blend(const RenderArgs& a) {
    a.geometry->SetEffectVariables([&](fx::Effect& e) {
      SetParams(e);
      SetSrv(e, "OpaqueColor", a.targets.frameView);
      SetSrv(e, "OpaqueDepth", a.targets.depthView);
      SetSrv(e, "TileStart", tileStart_.srv.Get());
      SetSrv(e, "TileEnd", tileEnd_.srv.Get());
      SetSrv(e, "PairParticles", pairParticles_.srv.Get());
      SetUav(e, "Composite", composite_.uav.Get());
    });
    a.geometry->Dispatch(a.context, "BlendTiles", tilesX_, tilesY_, 1);
    ComPtr<rhi::Resource> frame;
    a.targets.frame->GetResource(frame.GetAddressOf());
    a.context->CopyResource(frame.Get(), composite_.texture.Get());
  }

  const MethodInfo* info_ = nullptr;
  rhi::Device* device_ = nullptr;
  uint32_t width_ = 0, height_ = 0, tilesX_ = 0, tilesY_ = 0, capacity_ = 0, pairCapacity_ = 0;
  uint64_t lostPairs_ = 0;
  bool sortsByDepth_ = false;
  OutputMergerArithmetic arithmetic_;  // the blends the Blend pass replays
  std::vector<std::string> passNames_;
  // Per particle of the buffer (capacity_), then per drawn particle in sorted order.
  ViewedBuffer visible_, visibleOffsets_, keys_, rects_, drawn_, sortKeys_, sortValues_;
  // Per sorted particle, then per (tile, particle) pair, then per tile.
  ViewedBuffer pairCounts_, pairOffsets_, pairTotal_, pairTiles_, pairParticles_, tileStart_, tileEnd_;
  Composite composite_;
  LateReadback readback_;
  std::unique_ptr<compute::PrefixScan> visibleScan_, pairScan_;
  std::unique_ptr<compute::RadixSort> depthSort_, pairSort_;
  std::unique_ptr<compute::DispatchArgs> args_;
  ComPtr<fx::Effect> effect_;
  fx::EffectPass *compact_ = nullptr, *countTiles_ = nullptr, *fillPairs_ = nullptr, *tileRanges_ = nullptr;
};

std::unique_ptr<Method> CreateComputeTiles(const MethodInfo& info, const MethodSetup& setup, bool sortsByDepth,
                                           std::string* error) {
  auto method = std::make_unique<ComputeTilesMethod>();
  if (!method->Initialize(info, setup, sortsByDepth, error)) return nullptr;
  return method;
}
std::unique_ptr<Method> CreateComputeSorted(const MethodInfo& info, const MethodSetup& setup, std::string* error) {
  return CreateComputeTiles(info, setup, true, error);
}
std::unique_ptr<Method> CreateComputeWboit(const MethodInfo& info, const MethodSetup& setup, std::string* error) {
  return CreateComputeTiles(info, setup, false, error);
}

}  // namespace

extern const MethodInfo kComputeSorted{
    "compute-sorted", "oit/compute_sorted.fxh", kNeedsCompute | kNeedsPixelShaderUavs | kNeedsQuadObjects,
    DrawOrder::AsSubmitted,  // the GPU sorts them, not the object
    "particles sorted on the GPU, OVER back to front in compute tiles, no ROP (issue 19; `sorted`'s image)",
    CreateComputeSorted};
extern const MethodInfo kComputeWboit{
    "compute-wboit", "oit/compute_wboit.fxh", kNeedsCompute | kNeedsPixelShaderUavs | kNeedsQuadObjects,
    DrawOrder::AsSubmitted, "WBOIT (Tables 1-2) evaluated per pixel in compute tiles, no ROP (issue 19)",
    CreateComputeWboit};

}  // namespace renderer::oit
