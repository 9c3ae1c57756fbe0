// Plain alpha blending (OVER) in submission order, and the sorted reference:
// the same pass (shaders_hlsl/oit/alpha.fxh) over geometry drawn back to front.
// Both draw straight into the frame and own no targets.
#include "renderer/oit/method.h"

namespace renderer::oit {
namespace {

class OverMethod final : public Method {
 public:
  explicit OverMethod(DrawOrder order) : order_(order) {}

  void Render(const RenderArgs& a) override {
    a.marks->BeginPass(0);
    rhi::RenderTargetView* frame = a.targets.frame;
    a.context->OMSetRenderTargets(1, &frame, a.targets.depth);
    a.geometry->Draw(a.context, "Transparency", order_);
  }
  uint64_t MemoryBytes() const override { return 0; }
  const std::vector<std::string>& PassNames() const override { return kPasses; }

 private:
  inline static const std::vector<std::string> kPasses = {"Transparency"};
  DrawOrder order_;
};

std::unique_ptr<Method> CreateOver(const MethodInfo& info, const MethodSetup&, std::string*) {
  return std::make_unique<OverMethod>(info.order);
}

}  // namespace

extern const MethodInfo kAlpha{"alpha", "oit/alpha.fxh", 0, DrawOrder::AsSubmitted,
                               "OVER in submission order (document 000's unsorted alpha blending)", CreateOver};
extern const MethodInfo kSorted{"sorted", "oit/alpha.fxh", 0, DrawOrder::BackToFront,
                                "OVER back to front, sorted on the CPU (the reference of document 000)",
                                CreateOver};

}  // namespace renderer::oit
