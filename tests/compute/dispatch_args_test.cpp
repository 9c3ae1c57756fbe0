// renderer::compute::DispatchArgs and compute/indirect.hlsli: DispatchIndirect
// arguments written on the GPU from a count on the GPU, against values worked out
// by hand (the split of a group count over 65,535 into x and y included), and a
// dispatch sized by them that visits every item below the count exactly once.
#include "renderer/compute/dispatch_args.h"

#include <string_view>

#include "compute_fixture.h"
#include "renderer/effect_files.h"

namespace rhi_test {
namespace {

using renderer::compute::DispatchArgs;

struct ArgsCase {
  uint32_t count, threadsPerGroup, maxCount;
  uint32_t groupsX, groupsY;  // z is 1; the slot's count word is min(count, maxCount)
};

void PrintTo(const ArgsCase& c, std::ostream* os) {
  *os << "count " << c.count << ", " << c.threadsPerGroup << " a group, max " << c.maxCount;
}

class DispatchArgsTest : public ComputeTest, public ::testing::WithParamInterface<ArgsCase> {};

TEST_P(DispatchArgsTest, WritesTheGroupsAndTheCount) {
  const ArgsCase& c = GetParam();
  std::string error;
  auto args = DispatchArgs::Create(device.Get(), 3, &error);
  ASSERT_NE(args, nullptr) << error;
  // The count in word 5 of a buffer whose other words would give other counts.
  std::vector<uint32_t> words(8, 12345);
  words[5] = c.count;
  RawBuffer count = MakeRaw(words);
  ASSERT_TRUE(args->Write(context.Get(), count.uav.Get(), 5, c.threadsPerGroup, 2, c.maxCount));
  ASSERT_TRUE(args->Write(context.Get(), count.uav.Get(), 0, 1, 0));  // a neighbour: 12345 groups of one
  const std::vector<uint32_t> got = ReadBufferAs<uint32_t>(args->buffer());
  ASSERT_EQ(got.size(), 12u);
  const uint32_t clamped = std::min(c.count, c.maxCount);
  EXPECT_EQ(std::vector<uint32_t>(got.begin() + 8, got.end()),
            (std::vector<uint32_t>{c.groupsX, c.groupsY, 1, clamped}));
  EXPECT_EQ(std::vector<uint32_t>(got.begin(), got.begin() + 4), (std::vector<uint32_t>{12345, 1, 1, 12345}));
  // What the split promises: within D3D11's limit, every item covered, no row wasted.
  const uint64_t groups = (uint64_t(clamped) + c.threadsPerGroup - 1) / c.threadsPerGroup;
  EXPECT_LE(c.groupsX, 65535u);
  EXPECT_GE(uint64_t(c.groupsX) * c.groupsY, groups);
  EXPECT_LT(uint64_t(c.groupsX) * (c.groupsY - 1), std::max<uint64_t>(groups, 1));
}

constexpr uint32_t kNoMax = UINT32_MAX;
INSTANTIATE_TEST_SUITE_P(
    Counts, DispatchArgsTest,
    ::testing::Values(ArgsCase{0, 256, kNoMax, 0, 1}, ArgsCase{1, 256, kNoMax, 1, 1}, ArgsCase{256, 256, kNoMax, 1, 1},
                      ArgsCase{257, 256, kNoMax, 2, 1}, ArgsCase{65535u * 256, 256, kNoMax, 65535, 1},
                      ArgsCase{65535u * 256 + 1, 256, kNoMax, 32768, 2},  // 65,536 groups: two rows
                      ArgsCase{200000, 1, kNoMax, 50000, 4},              // 3 rows hold 196,605
                      ArgsCase{1000, 256, 300, 2, 1},                     // over the maximum: the maximum
                      ArgsCase{kNoMax, 1024, kNoMax, 64528, 65}));        // 4,194,304 groups

TEST_F(ComputeTest, DispatchArgsRefusesABadSlotOrGroupSize) {
  std::string error;
  auto args = DispatchArgs::Create(device.Get(), 2, &error);
  ASSERT_NE(args, nullptr) << error;
  RawBuffer count = MakeRaw({7});
  EXPECT_FALSE(args->Write(context.Get(), count.uav.Get(), 0, 64, 2));
  EXPECT_FALSE(args->Write(context.Get(), count.uav.Get(), 0, 0, 1));
  EXPECT_EQ(DispatchArgs::Create(device.Get(), 0, &error), nullptr);
  EXPECT_NE(error.find("no slots"), std::string::npos) << error;
}

// Two threads a group, so 2 * 65,535 + 1 items take a split grid (32,768 x 2).
constexpr std::string_view kVisitOnce = R"(
#include "compute/indirect.hlsli"
RWByteAddressBuffer Visits : register(u0);
[numthreads(2, 1, 1)]
void CSVisit(uint3 group : SV_GroupID, uint thread : SV_GroupIndex) {
  uint item = IndirectGroupIndex(group) * 2 + thread;
  if (item < IndirectCount()) Visits.InterlockedAdd(item * 4, 1u);
}
technique11 Visit { pass Visit { SetComputeShader(CompileShader(cs_5_0, CSVisit())); } }
)";

TEST_F(ComputeTest, AnIndirectDispatchVisitsEveryItemBelowTheCountOnce) {
  const uint32_t items = 2 * 65535 + 1, tail = 64;
  fx::EFFECT_OPTIONS options;
  options.IncludeDirs = {renderer::ShaderDirectory()};
  std::string errors;
  options.Errors = &errors;
  ComPtr<fx::Effect> effect;
  ASSERT_EQ(fx::CreateEffectFromMemory(kVisitOnce.data(), kVisitOnce.size(), "visit_once.fx", options, device.Get(),
                                       effect.GetAddressOf()),
            rhi::S_OK)
      << errors;
  std::string error;
  auto args = DispatchArgs::Create(device.Get(), 1, &error);
  ASSERT_NE(args, nullptr) << error;
  RawBuffer count = MakeRaw({items});
  RawBuffer visits = MakeRaw(std::vector<uint32_t>(items + tail, 0));
  ASSERT_TRUE(args->Write(context.Get(), count.uav.Get(), 0, 2, 0));
  EXPECT_EQ(ReadBufferAs<uint32_t>(args->buffer()), (std::vector<uint32_t>{32768, 2, 1, items}));
  effect->GetVariableByName("Visits")->AsUnorderedAccessView()->SetUnorderedAccessView(visits.uav.Get());
  args->Bind(effect.Get(), 0);
  effect->GetTechniqueByIndex(0)->GetPassByIndex(0)->Apply(0, context.Get());
  args->Dispatch(context.Get(), 0);
  std::vector<uint32_t> want(items + tail, 1);
  std::fill(want.begin() + items, want.end(), 0);
  EXPECT_TRUE(Read(visits) == want);

  // The arguments are still bound for reading (IndirectArgs): writing them again
  // unbinds them first, so D3D11's "forcing it to NULL" hazard never comes.
  ASSERT_TRUE(args->Write(context.Get(), count.uav.Get(), 0, 64, 0));
  EXPECT_EQ(ReadBufferAs<uint32_t>(args->buffer()), (std::vector<uint32_t>{2048, 1, 1, items}));
  EXPECT_EQ(Refusals(), std::vector<std::string>{});
}

}  // namespace
}  // namespace rhi_test
