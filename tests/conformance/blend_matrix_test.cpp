// CI run of the blend matrix on all 13 formats: each format draws every 4th RGB
// triple (a different residue per format, so the 13 formats together cover all
// 1445 RGB triples 3-4 times and all 605 alpha triples), 8 random cases per
// triple. One pipeline per blend state is what costs time on lavapipe; the
// report (conformance_report) runs every triple on every format.
#include <gtest/gtest.h>

#include "blend_matrix.h"

namespace {

using namespace conf;

class BlendMatrix : public ::testing::TestWithParam<rhi::DXGI_FORMAT> {};

TEST_P(BlendMatrix, EveryTripleMatchesReferenceWithinTolerance) {
  Gpu gpu(nullptr, /*validation=*/true);
  ASSERT_TRUE(gpu.ok());
  MatrixOptions options;
  options.casesPerTriple = 8;
  options.tripleStride = 4;
  options.formats = {GetParam()};
  const MatrixResult r = RunBlendMatrix(gpu, options);
  ASSERT_EQ(r.formats.size(), 1u);
  const FormatStats& s = r.formats[0];
  EXPECT_GE(s.tally.cases, 361u * 8u);
  EXPECT_LE(s.tally.cases, 362u * 8u);
  // Every factor and op was exercised on this format.
  EXPECT_EQ(r.perFactor.size(), 17u);
  EXPECT_EQ(r.perOp.size(), 5u);
  EXPECT_EQ(r.failureCount, 0u) << r.failureCount << " of " << s.tally.cases << " cases out of tolerance, max steps "
                                << s.maxSteps[0] << "," << s.maxSteps[1] << "," << s.maxSteps[2] << ","
                                << s.maxSteps[3];
  for (size_t i = 0; i < r.failures.size() && i < 10; ++i) ADD_FAILURE() << r.failures[i].Describe();
  for (const std::string& m : r.validation) ADD_FAILURE() << "validation layer: " << m;
  for (const std::string& m : r.refusals) ADD_FAILURE() << "refusal: " << m;
}

INSTANTIATE_TEST_SUITE_P(AllFormats, BlendMatrix, ::testing::ValuesIn(MatrixFormats()),
                         [](const ::testing::TestParamInfo<rhi::DXGI_FORMAT>& info) {
                           return std::string(FormatName(info.param));
                         });

TEST(BlendStateRules, ColourFactorsAreRefusedForAlpha) {
  Gpu gpu(nullptr, true);
  ASSERT_TRUE(gpu.ok());
  const std::vector<std::string> accepted = CheckAlphaColorFactorsRefused(gpu);
  EXPECT_TRUE(accepted.empty()) << "CreateBlendState accepted " << accepted.size() << ", first: " << accepted[0];
  EXPECT_TRUE(gpu.validation().empty());
}

}  // namespace
