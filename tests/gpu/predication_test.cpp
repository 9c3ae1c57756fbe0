// Predicated rendering: draws and clears are skipped while the predicate's
// result equals PredicateValue, and only then; D3D11's refusals.
#include "gpu_helpers.h"

namespace rhi_test {
namespace {

using namespace rhi;

class PredicationTest : public RhiGpuTest {
 protected:
  void SetUp() override {
    RhiGpuTest::SetUp();
    if (HasFatalFailure()) return;
    target_ = MakeRenderTarget(4, 4);
    BindTarget(target_.rtv.Get(), 4, 4);
    UseColorPipeline();
  }
  ComPtr<Predicate> MakePredicate(UINT miscFlags = 0) {
    const QUERY_DESC desc{QUERY_OCCLUSION_PREDICATE, miscFlags};
    ComPtr<Predicate> predicate;
    EXPECT_EQ(device->CreatePredicate(&desc, predicate.GetAddressOf()), S_OK);
    return predicate;
  }
  // A predicate whose result is TRUE (a quad drew samples) or FALSE (nothing drawn).
  ComPtr<Predicate> FinishedPredicate(bool visible) {
    ComPtr<Predicate> predicate = MakePredicate();
    context->Begin(predicate.Get());
    if (visible) DrawVertices(Quad(0, 0, 4, 4, kRed, 4, 4));
    context->End(predicate.Get());
    return predicate;
  }
  // Under predication: clear to blue, then draw green over the left half.
  std::vector<std::string> PredicatedFrame(Predicate* predicate, BOOL value) {
    Clear(target_.rtv.Get(), kBlack);
    context->SetPredication(predicate, value);
    Clear(target_.rtv.Get(), kBlue);
    DrawVertices(Quad(0, 0, 2, 4, kGreen, 4, 4));
    context->SetPredication(nullptr, FALSE);  // the read-back copy is predicated too
    return Picture(ReadTexture(target_.texture.Get()), 4, 4, kLegend);
  }
  Target target_;
};

TEST_F(PredicationTest, RenderingIsSkippedExactlyWhenTheResultEqualsPredicateValue) {
  ComPtr<Predicate> visible = FinishedPredicate(true), hidden = FinishedPredicate(false);
  const auto drawn = Rows(4, "GGBB"), skipped = Rows(4, "....");
  EXPECT_EQ(PredicatedFrame(visible.Get(), TRUE), skipped);
  EXPECT_EQ(PredicatedFrame(visible.Get(), FALSE), drawn);
  EXPECT_EQ(PredicatedFrame(hidden.Get(), FALSE), skipped) << "occlusion culling: skip what was not visible";
  EXPECT_EQ(PredicatedFrame(hidden.Get(), TRUE), drawn);
  EXPECT_EQ(PredicatedFrame(nullptr, TRUE), drawn) << "no predicate, no predication";
}

TEST_F(PredicationTest, GetPredicationReturnsThePredicateWithAReferenceAndClearStateResetsIt) {
  ComPtr<Predicate> predicate = FinishedPredicate(false);
  context->SetPredication(predicate.Get(), FALSE);
  Predicate* got = nullptr;
  BOOL value = TRUE;
  context->GetPredication(&got, &value);
  EXPECT_EQ(got, predicate.Get());
  EXPECT_EQ(value, FALSE);
  predicate->AddRef();
  EXPECT_EQ(predicate->Release(), 2u) << "ours and the getter's";
  got->Release();
  context->ClearState();
  context->GetPredication(&got, &value);
  EXPECT_EQ(got, nullptr);
  BindTarget(target_.rtv.Get(), 4, 4);
  UseColorPipeline();
  Clear(target_.rtv.Get(), kBlack);
  DrawVertices(Quad(0, 0, 4, 4, kGreen, 4, 4));
  EXPECT_EQ(Picture(ReadTexture(target_.texture.Get()), 4, 4, kLegend), Rows(4, "GGGG")) << "no longer predicated";
}

TEST_F(PredicationTest, OnlyPredicateKindsAreAcceptedAndAnUnfinishedPredicateDoesNotPredicate) {
  const QUERY_DESC occlusion{QUERY_OCCLUSION, 0};
  ComPtr<Predicate> notPredicate;
  EXPECT_EQ(device->CreatePredicate(&occlusion, notPredicate.GetAddressOf()), E_INVALIDARG);
  EXPECT_TRUE(RefusedWith("is not QUERY_OCCLUSION_PREDICATE"));
  ComPtr<Predicate> unfinished = MakePredicate();
  context->Begin(unfinished.Get());
  ClearMessages();
  EXPECT_EQ(PredicatedFrame(unfinished.Get(), FALSE), Rows(4, "GGBB"));
  EXPECT_TRUE(RefusedWith("SetPredication: the predicate has not been ended"));
  context->End(unfinished.Get());
}

}  // namespace
}  // namespace rhi_test
