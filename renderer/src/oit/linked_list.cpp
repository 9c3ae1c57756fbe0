// Exact OIT with per-pixel linked lists (shaders_hlsl/oit/linked_list.fxh),
// beside document 004's prefix-sum buffer: one geometry pass links every
// fragment's (triangle id, depth) into its pixel's list in a node pool of fixed
// capacity (FragmentStorage::nodesPerPixel per pixel), and the same resolve as
// prefix-sum's sorts, shades (deferred) and composites. Fragments past the pool
// are dropped and counted: the pool's node counter (an atomic word) goes on
// counting past the capacity, and its value comes back a frame or two late
// (LateReadback) as LostFragments. On lavapipe the lists come out wrong along
// triangle edges (tests/replay/fragment_buffer_test.cpp).
#include "fx/effect.h"
#include "oit/fragment_buffers.h"
#include "renderer/effect_files.h"

namespace renderer::oit {
namespace {

using rhi::ComPtr;
using rhi::UINT;

constexpr uint32_t kNodeBytes = 12;  // (triangle id, depth, next)

class LinkedListMethod final : public Method {
 public:
  bool Initialize(const MethodInfo& info, const MethodSetup& setup, std::string* error) {
    rhi::Device* device = setup.device;
    width_ = setup.frame.width;
    const uint32_t pixels = setup.frame.width * setup.frame.height;
    capacity_ = pixels * setup.fragmentStorage.nodesPerPixel;
    if (capacity_ == 0 || !nodes_.CreateStructured(device, capacity_, kNodeBytes, false) ||
        !heads_.CreateRaw(device, pixels) || !nodeCounter_.CreateRaw(device, 1) ||
        !readback_.Create(device,
                          [this](uint32_t used, uint64_t) { lost_ = used > capacity_ ? used - capacity_ : 0; })) {
      *error = std::string(info.name) + ": creating the heads and the node pool (" + std::to_string(capacity_) +
               " nodes) failed";
      return false;
    }
    return true;
  }

  void Render(const RenderArgs& a) override {
    rhi::DeviceContext* ctx = a.context;
    readback_.Poll(ctx);
    a.marks->BeginPass(0);
    const UINT endOfList[4] = {0xFFFFFFFFu, 0xFFFFFFFFu, 0xFFFFFFFFu, 0xFFFFFFFFu};
    const UINT zero[4] = {0, 0, 0, 0};
    ctx->ClearUnorderedAccessViewUint(heads_.uav.Get(), endOfList);
    ctx->ClearUnorderedAccessViewUint(nodeCounter_.uav.Get(), zero);
    ctx->OMSetRenderTargets(0, nullptr, a.targets.depth);
    a.geometry->SetEffectVariables([&](fx::Effect& e) {
      e.GetVariableByName("FrameWidth")->AsScalar()->SetInt(int(width_));
      e.GetVariableByName("HeadsOut")->AsUnorderedAccessView()->SetUnorderedAccessView(heads_.uav.Get());
      e.GetVariableByName("NodesOut")->AsUnorderedAccessView()->SetUnorderedAccessView(nodes_.uav.Get());
      e.GetVariableByName("NodeCounter")->AsUnorderedAccessView()->SetUnorderedAccessView(nodeCounter_.uav.Get());
    });
    a.geometry->Draw(ctx, "Link", DrawOrder::AsSubmitted);
    ctx->OMSetRenderTargets(0, nullptr,
                            nullptr);  // the counter leaves the output merger for the copy
    readback_.Issue(ctx, nodeCounter_.buffer.Get(), 0);

    a.marks->BeginPass(1);
    rhi::RenderTargetView* frame = a.targets.frame;
    ctx->OMSetRenderTargets(1, &frame, nullptr);  // unbinds the UAVs: the resolve reads them
    a.geometry->SetEffectVariables([&](fx::Effect& e) {
      e.GetVariableByName("Heads")->AsShaderResource()->SetResource(heads_.srv.Get());
      e.GetVariableByName("Nodes")->AsShaderResource()->SetResource(nodes_.srv.Get());
    });
    a.geometry->DrawFullscreen(ctx, "Resolve");
  }

  // The node pool (12 bytes a node) and the heads (4 bytes a pixel).
  uint64_t MemoryBytes() const override { return nodes_.bytes + heads_.bytes; }
  const std::vector<std::string>& PassNames() const override { return kPasses; }
  uint64_t LostFragments() const override { return lost_; }

 private:
  inline static const std::vector<std::string> kPasses = {"Link", "Resolve"};
  uint32_t width_ = 0, capacity_ = 0;
  uint64_t lost_ = 0;
  ViewedBuffer heads_, nodes_, nodeCounter_;
  LateReadback readback_;
};

std::unique_ptr<Method> CreateLinkedList(const MethodInfo& info, const MethodSetup& setup, std::string* error) {
  if (!AcceptsOnlyOneObject(info, setup, error)) return nullptr;
  auto method = std::make_unique<LinkedListMethod>();
  if (!method->Initialize(info, setup, error)) return nullptr;
  return method;
}

}  // namespace

extern const MethodInfo kLinkedList{"linked-list",
                                    "oit/linked_list.fxh",
                                    kNeedsPixelShaderUavs | kNeedsDualSourceBlend,
                                    DrawOrder::AsSubmitted,
                                    "exact: per-pixel linked lists of (id, depth) in a fixed node pool, lost "
                                    "fragments counted, deferred "
                                    "shading; one object",
                                    CreateLinkedList,
                                    Exactness::kExact};  // while its node pool holds every fragment

}  // namespace renderer::oit
