// renderer::compute::PrefixScan (the scan of document 004's fragment buffer and
// of the radix sort's histograms) against a CPU scan, for lengths from 1 to 2^24.
#include "renderer/compute/prefix_scan.h"

#include <algorithm>
#include <random>

#include "compute_fixture.h"

namespace rhi_test {
namespace {

class PrefixScanTest : public ComputeTest, public ::testing::WithParamInterface<uint32_t> {};

TEST_P(PrefixScanTest, EqualsTheCpuScan) {
  const uint32_t length = GetParam();
  std::mt19937 random(length);
  std::vector<uint32_t> input(length);
  for (uint32_t& v : input) v = random() % 16;  // per-pixel counts: the sum stays far below 2^32
  RawBuffer in = MakeRaw(input);
  RawBuffer out = MakeRaw(std::vector<uint32_t>(length, 0xdeadbeef));
  RawBuffer total = MakeRaw({0xdeadbeef});
  std::string error;
  auto scan = renderer::compute::PrefixScan::Create(device.Get(), length, &error);
  ASSERT_NE(scan, nullptr) << error;
  scan->Run(context.Get(), in.uav.Get(), out.uav.Get(), total.uav.Get());
  std::vector<uint32_t> want(length);
  uint32_t sum = 0;
  for (uint32_t i = 0; i < length; ++i) want[i] = sum, sum += input[i];
  const std::vector<uint32_t> got = Read(out);
  ASSERT_EQ(got.size(), want.size());
  EXPECT_TRUE(got == want) << "first difference at "
                           << (std::mismatch(got.begin(), got.end(), want.begin()).first - got.begin());
  EXPECT_EQ(Read(total)[0], sum);
}

// 1, around one group (512), around two levels (512^2 = 262144), a prime, 2^24.
INSTANTIATE_TEST_SUITE_P(Lengths, PrefixScanTest,
                         ::testing::Values(1u, 2u, 511u, 512u, 513u, 262143u, 262145u, 1000003u, 1u << 24));

// A PassMarks that counts the passes it was told of.
class CountedPasses final : public renderer::oit::PassMarks {
 public:
  void BeginPass(size_t index) override { last = index, ++passes; }
  size_t last = 0, passes = 0;
};

TEST_F(ComputeTest, PrefixScanWithoutATotalRunsTheOtherPasses) {
  const uint32_t length = 300000;  // two levels
  std::vector<uint32_t> input(length, 3);
  RawBuffer in = MakeRaw(input), out = MakeRaw(std::vector<uint32_t>(length));
  std::string error;
  auto scan = renderer::compute::PrefixScan::Create(device.Get(), length, &error);
  ASSERT_NE(scan, nullptr) << error;
  CountedPasses marks;
  size_t pass = 0;
  scan->Run(context.Get(), in.uav.Get(), out.uav.Get(), nullptr, &marks, &pass);
  std::vector<std::string> names = scan->PassNames();
  EXPECT_EQ(names.back(), "Total");
  names.pop_back();
  EXPECT_EQ(scan->PassNames(false), names);
  EXPECT_EQ(marks.passes, names.size());
  EXPECT_EQ(pass, names.size());
  const std::vector<uint32_t> got = Read(out);
  EXPECT_EQ(got[1], 3u);
  EXPECT_EQ(got[length - 1], 3 * (length - 1));
}

}  // namespace
}  // namespace rhi_test
