// renderer::compute::RadixSort against std::stable_sort by the key's low bits on
// random keys with many ties (values are the pairs' indices, so ties must come
// out in index order), at sizes around its block (1,024 pairs) and up to 2^22,
// with counts on the GPU at, below and above the sort's maximum (the words past
// the count stay as they were), and the passes it reports against those it runs.
#include "renderer/compute/radix_sort.h"

#include <algorithm>
#include <numeric>
#include <random>

#include "compute_fixture.h"

namespace rhi_test {
namespace {

using renderer::compute::RadixSort;

struct SortCase {
  uint32_t count;     // on the GPU
  uint32_t maxCount;  // the sort's
  uint32_t keyBits;
};

void PrintTo(const SortCase& c, std::ostream* os) {
  *os << c.count << " pairs (max " << c.maxCount << "), " << c.keyBits << " key bits";
}

constexpr uint32_t kTail = 16;  // words past max(count, maxCount), which the sort must not touch

// Random 32-bit keys drawn from a pool of about n / 16 values: many ties, and
// high bits that a sort by fewer bits must carry along unsorted.
std::vector<uint32_t> KeysWithTies(uint32_t n, uint32_t seed) {
  std::mt19937 random(seed);
  std::vector<uint32_t> pool(std::max(n / 16, 1u));
  for (uint32_t& k : pool) k = random();
  std::vector<uint32_t> keys(n);
  for (uint32_t& k : keys) k = pool[random() % pool.size()];
  return keys;
}

class RadixSortTest : public ComputeTest, public ::testing::WithParamInterface<SortCase> {
 protected:
  // Sorts `keys` (and their indices as values) on the GPU with `sort` and checks
  // the result against std::stable_sort of the first min(count, maxCount).
  void SortAndCheck(RadixSort& sort, const std::vector<uint32_t>& keys, uint32_t count, uint32_t keyBits) {
    std::vector<uint32_t> values(keys.size());
    std::iota(values.begin(), values.end(), 0u);
    RawBuffer keysBuffer = MakeRaw(keys), valuesBuffer = MakeRaw(values);
    RawBuffer countBuffer = MakeRaw({0xdeadbeef, count, 0xdeadbeef});
    sort.Sort(context.Get(), keysBuffer.uav.Get(), valuesBuffer.uav.Get(), countBuffer.uav.Get(), 1, keyBits);

    const uint32_t sorted = std::min(count, sort.maxCount());
    const uint32_t mask = keyBits >= 32 ? ~0u : (1u << keyBits) - 1;
    std::vector<uint32_t> order(sorted);
    std::iota(order.begin(), order.end(), 0u);
    std::stable_sort(order.begin(), order.end(),
                     [&](uint32_t a, uint32_t b) { return (keys[a] & mask) < (keys[b] & mask); });
    std::vector<uint32_t> wantKeys = keys, wantValues = values;
    for (uint32_t i = 0; i < sorted; ++i) wantKeys[i] = keys[order[i]], wantValues[i] = order[i];

    const std::vector<uint32_t> gotKeys = Read(keysBuffer), gotValues = Read(valuesBuffer);
    ASSERT_EQ(gotKeys.size(), wantKeys.size());
    EXPECT_TRUE(gotKeys == wantKeys) << "first wrong key at "
                                     << std::mismatch(gotKeys.begin(), gotKeys.end(), wantKeys.begin()).first -
                                            gotKeys.begin();
    EXPECT_TRUE(gotValues == wantValues)
        << "first wrong value at "
        << std::mismatch(gotValues.begin(), gotValues.end(), wantValues.begin()).first - gotValues.begin();
    EXPECT_EQ(Refusals(), std::vector<std::string>{});  // no hazard (a resource bound to read and write)
  }

  std::unique_ptr<RadixSort> Create(uint32_t maxCount) {
    std::string error;
    auto sort = RadixSort::Create(device.Get(), maxCount, &error);
    EXPECT_NE(sort, nullptr) << error;
    return sort;
  }
};

TEST_P(RadixSortTest, EqualsStableSortByTheKeyBits) {
  const SortCase& c = GetParam();
  auto sort = Create(c.maxCount);
  ASSERT_NE(sort, nullptr);
  SortAndCheck(*sort, KeysWithTies(std::max(c.count, c.maxCount) + kTail, c.count ^ c.keyBits), c.count, c.keyBits);
}

INSTANTIATE_TEST_SUITE_P(
    Sizes, RadixSortTest,
    ::testing::Values(
        // All 32 bits, count = maximum: empty, one, around a block (1,024) and a scan group, odd, large.
        SortCase{0, 0, 32}, SortCase{1, 1, 32}, SortCase{255, 255, 32}, SortCase{256, 256, 32}, SortCase{257, 257, 32},
        SortCase{4097, 4097, 32}, SortCase{65539, 65539, 32}, SortCase{1u << 20, 1u << 20, 32},
        SortCase{1u << 22, 1u << 22, 32},
        // 13 bits: four passes, the last of one bit.
        SortCase{257, 257, 13}, SortCase{65539, 65539, 13}, SortCase{1u << 20, 1u << 20, 13},
        // An odd number of passes (the result copied back), one pass of one bit, none.
        SortCase{4097, 4097, 4}, SortCase{4097, 4097, 1}, SortCase{4097, 4097, 0},
        // The GPU's count below the maximum, zero, and above it (the maximum is sorted).
        SortCase{1000, 4097, 32}, SortCase{65539, 1u << 20, 13}, SortCase{0, 4097, 32}, SortCase{5000, 4097, 32},
        SortCase{1u << 20, 65539, 32}));

TEST_F(RadixSortTest, SortsAgainWithASmallerCount) {
  auto sort = Create(70000);
  ASSERT_NE(sort, nullptr);
  SortAndCheck(*sort, KeysWithTies(70000, 1), 70000, 32);
  SortAndCheck(*sort, KeysWithTies(3000, 2), 3000, 32);  // the first sort's blocks past 3000 must not count
  SortAndCheck(*sort, KeysWithTies(70000, 3), 65000, 7);
}

// A PassMarks that records the pass indices it was given.
class RecordedPasses final : public renderer::oit::PassMarks {
 public:
  void BeginPass(size_t index) override { indices.push_back(index); }
  std::vector<size_t> indices;
};

TEST_F(RadixSortTest, MarksEveryPassItNames) {
  auto sort = Create(5000);
  ASSERT_NE(sort, nullptr);
  RawBuffer keys = MakeRaw(KeysWithTies(5000, 4)), values = MakeRaw(std::vector<uint32_t>(5000)),
            count = MakeRaw({5000});
  for (uint32_t bits : {32u, 13u, 4u, 0u}) {
    RecordedPasses marks;
    size_t pass = 7;  // passes before the sort's
    sort->Sort(context.Get(), keys.uav.Get(), values.uav.Get(), count.uav.Get(), 0, bits, &marks, &pass);
    const std::vector<std::string>& names = sort->PassNames(bits);
    std::vector<size_t> want(names.size());
    std::iota(want.begin(), want.end(), size_t(7));
    EXPECT_EQ(marks.indices, want) << bits << " bits";
    EXPECT_EQ(pass, 7 + names.size());
    EXPECT_EQ(std::count(names.begin(), names.end(), "Scatter"), (bits + 3) / 4) << bits << " bits";
    EXPECT_EQ(std::count(names.begin(), names.end(), "CopyBack"), ((bits + 3) / 4) % 2) << bits << " bits";
  }
}

TEST_F(RadixSortTest, DoesNothingWithoutAView) {
  auto sort = Create(100);
  ASSERT_NE(sort, nullptr);
  const std::vector<uint32_t> keys = KeysWithTies(100, 5);
  RawBuffer keysBuffer = MakeRaw(keys), values = MakeRaw(std::vector<uint32_t>(100)), count = MakeRaw({100});
  RecordedPasses marks;
  size_t pass = 0;
  sort->Sort(context.Get(), keysBuffer.uav.Get(), values.uav.Get(), nullptr, 0, 32, &marks, &pass);
  sort->Sort(context.Get(), keysBuffer.uav.Get(), nullptr, count.uav.Get(), 0, 32, &marks, &pass);
  sort->Sort(context.Get(), nullptr, values.uav.Get(), count.uav.Get(), 0, 32, &marks, &pass);
  EXPECT_EQ(pass, 0u);
  EXPECT_TRUE(marks.indices.empty());
  EXPECT_EQ(Read(keysBuffer), keys);
}

TEST_F(RadixSortTest, RefusesMoreThanABufferOfWordsHolds) {
  std::string error;
  EXPECT_EQ(RadixSort::Create(device.Get(), 1u << 30, &error), nullptr);
  EXPECT_NE(error.find("1073741824 pairs"), std::string::npos) << error;
}

}  // namespace
}  // namespace rhi_test
