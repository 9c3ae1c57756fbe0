// Exact OIT with a prefix-sum fragment buffer (document 004;
// shaders_hlsl/oit/prefix_sum.fxh): count the translucent fragments per pixel,
// scan the counts, store each fragment's (triangle id, depth) at its pixel's
// offset, and resolve: sort, shade (deferred), composite.
//
// Sizing the fragment buffer. The document sizes it to the frame's total, which
// the CPU only has after reading it back: FragmentSizing::Exact (the
// default) does that each frame (the CPU waits for the count and scan to finish,
// so CPU and GPU work in turn every frame). The other sizing reads the totals
// back without waiting (LateReadback, a frame or so late) and keeps a capacity
// with hysteresis: grown to 1.5x a total that exceeded it, shrunk to 1.5x the
// largest recent total after kShrinkFrames frames under a quarter of it. Its
// first frame, which has no history, is sized exactly. A frame whose total
// exceeds the capacity stores the fragments that fit (which ones is a race); the
// ones past it are counted (LostFragments, when the total comes back) and the
// buffer grows.
#include "renderer/oit/prefix_sum.h"

#include <algorithm>
#include <cstring>

#include "fx/effect.h"
#include "oit/fragment_buffers.h"
#include "renderer/compute/prefix_scan.h"

namespace renderer::oit {
namespace {

using rhi::ComPtr;
using rhi::UINT;

constexpr uint32_t kFragmentBytes = 8;  // (triangle id, depth)
constexpr uint32_t kShrinkFrames = 120;

std::vector<uint32_t> ReadWords(rhi::Device* device, rhi::DeviceContext* context, const ViewedBuffer& b) {
  const rhi::BUFFER_DESC desc{uint32_t(b.bytes), rhi::USAGE_STAGING, 0, rhi::CPU_ACCESS_READ, 0, 0};
  ComPtr<rhi::Buffer> staging;
  std::vector<uint32_t> words(b.bytes / 4);
  if (rhi::FAILED(device->CreateBuffer(&desc, nullptr, staging.GetAddressOf()))) return {};
  context->CopyResource(staging.Get(), b.buffer.Get());
  rhi::MAPPED_SUBRESOURCE mapped{};
  if (rhi::FAILED(context->Map(staging.Get(), 0, rhi::MAP_READ, 0, &mapped))) return {};
  std::memcpy(words.data(), mapped.pData, b.bytes);
  context->Unmap(staging.Get(), 0);
  return words;
}

class PrefixSumMethod final : public Method {
 public:
  bool Initialize(const MethodInfo& info, const MethodSetup& setup, std::string* error) {
    device_ = setup.device;
    sizing_ = setup.fragmentStorage.sizing;
    width_ = setup.frame.width;
    pixels_ = setup.frame.width * setup.frame.height;
    if (!counts_.CreateRaw(device_, pixels_) || !cursors_.CreateRaw(device_, pixels_) ||
        !offsets_.CreateRaw(device_, pixels_) || !total_.CreateRaw(device_, 1) ||
        !readback_.Create(device_, [this](uint32_t total, uint64_t capacity) { Arrived(total, capacity); })) {
      *error = std::string(info.name) + ": creating the per-pixel buffers failed";
      return false;
    }
    scan_ = compute::PrefixScan::Create(device_, pixels_, error);
    if (!scan_) return false;
    passNames_ = {"Count"};
    passNames_.insert(passNames_.end(), scan_->PassNames().begin(), scan_->PassNames().end());
    passNames_.insert(passNames_.end(), {"Fill", "ShadeOpaque", "Resolve"});
    return true;
  }

  void Render(const RenderArgs& a) override {
    rhi::DeviceContext* ctx = a.context;
    readback_.Poll(ctx);
    size_t pass = 0;
    a.marks->BeginPass(pass++);
    const UINT zero[4] = {0, 0, 0, 0};
    ctx->ClearUnorderedAccessViewUint(counts_.uav.Get(), zero);
    ctx->ClearUnorderedAccessViewUint(cursors_.uav.Get(), zero);
    ctx->OMSetRenderTargets(0, nullptr, a.targets.depth);
    a.geometry->SetEffectVariables([&](fx::Effect& e) {
      e.GetVariableByName("FrameWidth")->AsScalar()->SetInt(int(width_));
      e.GetVariableByName("CountsOut")->AsUnorderedAccessView()->SetUnorderedAccessView(counts_.uav.Get());
    });
    a.geometry->Draw(ctx, "Count", DrawOrder::AsSubmitted);
    ctx->OMSetRenderTargets(0, nullptr, nullptr);  // Counts leaves the output merger for the scan

    scan_->Run(ctx, counts_.uav.Get(), offsets_.uav.Get(), total_.uav.Get(), a.marks, &pass);
    SizeFragmentBuffer(ctx);

    a.marks->BeginPass(pass++);
    ctx->OMSetRenderTargets(0, nullptr, a.targets.depth);
    a.geometry->SetEffectVariables([&](fx::Effect& e) {
      e.GetVariableByName("Cursors")->AsUnorderedAccessView()->SetUnorderedAccessView(cursors_.uav.Get());
      e.GetVariableByName("FragmentsOut")->AsUnorderedAccessView()->SetUnorderedAccessView(fragments_.uav.Get());
      e.GetVariableByName("Offsets")->AsShaderResource()->SetResource(offsets_.srv.Get());
    });
    a.geometry->Draw(ctx, "Fill", DrawOrder::AsSubmitted);

    a.marks->BeginPass(pass++);
    ctx->OMSetRenderTargets(0, nullptr, nullptr);  // unbinds the UAVs: the resolve reads them
    a.opaque->ShadeVisibility(ctx);  // step 6's opaque pixels, under the translucent composite

    a.marks->BeginPass(pass++);
    rhi::RenderTargetView* frame = a.targets.frame;
    ctx->OMSetRenderTargets(1, &frame, nullptr);
    a.geometry->SetEffectVariables([&](fx::Effect& e) {
      e.GetVariableByName("Counts")->AsShaderResource()->SetResource(counts_.srv.Get());
      e.GetVariableByName("Fragments")->AsShaderResource()->SetResource(fragments_.srv.Get());
    });
    a.geometry->DrawFullscreen(ctx, "Resolve");
  }

  // Fragments x 8 bytes, plus the per-pixel counts, offsets and cursors (4
  // bytes each), the total and the scan's block sums.
  uint64_t MemoryBytes() const override {
    return fragments_.bytes + counts_.bytes + offsets_.bytes + cursors_.bytes + total_.bytes + scan_->MemoryBytes();
  }

  PrefixSumFrame Read(rhi::DeviceContext* ctx) const {
    PrefixSumFrame f;
    f.counts = ReadWords(device_, ctx, counts_);
    f.offsets = ReadWords(device_, ctx, offsets_);
    f.cursors = ReadWords(device_, ctx, cursors_);
    const std::vector<uint32_t> total = ReadWords(device_, ctx, total_);
    f.total = total.empty() ? 0 : total[0];
    f.capacity = capacity_;
    return f;
  }
  const std::vector<std::string>& PassNames() const override { return passNames_; }
  OpaqueShading Opaque() const override { return OpaqueShading::VisibilityBuffer; }

  // GrowAndRedraw: the frame's total, now that all of its passes are recorded; too
  // large for the buffer it filled, the capacity grows (Arrived) and the frame is
  // drawn again, so nothing is lost.
  bool FrameNeedsRedraw(rhi::DeviceContext* ctx) override {
    if (sizing_ != FragmentSizing::GrowAndRedraw) return false;
    const uint64_t filled = capacity_;
    const uint32_t total = readback_.ReadNow(ctx, total_.buffer.Get());
    Arrived(total, filled);
    lost_ = 0;
    return total > filled;
  }
  uint64_t LostFragments() const override { return lost_; }

 private:
  // Exact: the frame's own total, read back now (a wait). Grown: the capacity
  // the totals read back so far asked for; the first frame, with none, is sized
  // exactly.
  void SizeFragmentBuffer(rhi::DeviceContext* ctx) {
    uint64_t wanted = 0;
    const bool exact = sizing_ == FragmentSizing::Exact;
    if (exact || !seenTotal_) {
      const uint32_t total = readback_.ReadNow(ctx, total_.buffer.Get());
      wanted = exact ? total : total + total / 2;
      demand_ = wanted;
      seenTotal_ = true;
    } else {
      wanted = GrownCapacity();
    }
    if (wanted != capacity_ || !fragments_.buffer) {
      capacity_ = wanted;
      fragments_ = {};
      fragments_.CreateStructured(device_, uint32_t(std::max<uint64_t>(capacity_, 1)), kFragmentBytes, false);
    }
    if (sizing_ == FragmentSizing::Late) readback_.Issue(ctx, total_.buffer.Get(), capacity_);
  }

  // A total read back a frame or more late, with the capacity its frame had.
  void Arrived(uint32_t total, uint64_t capacity) {
    lost_ = total > capacity ? total - capacity : 0;
    if (total > largestRecent_) largestRecent_ = total;
    if (total > demand_) demand_ = total + total / 2;
    framesUnderQuarter_ = total * 4 < capacity_ ? framesUnderQuarter_ + 1 : 0;
  }

  uint64_t GrownCapacity() {
    if (demand_ > capacity_) return demand_;
    if (framesUnderQuarter_ >= kShrinkFrames) {
      framesUnderQuarter_ = 0;
      demand_ = largestRecent_ + largestRecent_ / 2;
      largestRecent_ = 0;
      return std::max<uint64_t>(demand_, 1);
    }
    return capacity_;
  }

  rhi::Device* device_ = nullptr;
  FragmentSizing sizing_ = FragmentSizing::Exact;
  uint32_t width_ = 0, pixels_ = 0;
  ViewedBuffer counts_, cursors_, offsets_, total_, fragments_;
  std::unique_ptr<compute::PrefixScan> scan_;
  LateReadback readback_;
  uint64_t capacity_ = 0, demand_ = 0, largestRecent_ = 0, lost_ = 0;
  uint32_t framesUnderQuarter_ = 0;
  bool seenTotal_ = false;
  std::vector<std::string> passNames_;
};

std::unique_ptr<Method> CreatePrefixSum(const MethodInfo& info, const MethodSetup& setup, std::string* error) {
  if (!AcceptsOnlyOneObject(info, setup, error)) return nullptr;
  auto method = std::make_unique<PrefixSumMethod>();
  if (!method->Initialize(info, setup, error)) return nullptr;
  return method;
}

}  // namespace

std::optional<PrefixSumFrame> ReadPrefixSumFrame(const Method& method, rhi::DeviceContext* context) {
  const auto* prefixSum = dynamic_cast<const PrefixSumMethod*>(&method);
  if (!prefixSum) return std::nullopt;
  return prefixSum->Read(context);
}

extern const MethodInfo kPrefixSum{"prefix-sum",
                                   "oit/prefix_sum.fxh",
                                   kNeedsPixelShaderUavs | kNeedsCompute | kNeedsDualSourceBlend,
                                   DrawOrder::AsSubmitted,
                                   "exact: per-pixel counts, a prefix sum, an 8-byte (id, depth) fragment "
                                   "buffer, deferred shading "
                                   "(document 004); one object; buffer sized to each frame's total",
                                   CreatePrefixSum,
                                   Exactness::kExact};

}  // namespace renderer::oit
