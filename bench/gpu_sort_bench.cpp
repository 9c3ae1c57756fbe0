// gpu_sort_bench [--sizes 16384,65536,1048576,4194304] [--repeats N] [--key-bits B]
// GPU time of renderer::compute::RadixSort (issue 19's particle sort) for each
// number of (key, value) pairs: random 32-bit keys, the count in a GPU buffer
// (as the particle pass leaves it). Each repeat restores the unsorted pairs,
// then sorts with a TIMESTAMP query at the start of every pass (Sort's PassMarks)
// and one at the end, inside a TIMESTAMP_DISJOINT query; the table gives the
// median of the repeats: all passes, then per kind of pass (the scan is the
// shared PrefixScan's passes over the block histograms). Checks the last result
// is sorted and exits 1 if not. The device is picked as everywhere else
// (RHI_DEVICE, else lavapipe).
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "renderer/compute/radix_sort.h"
#include "rhi/query_wait.h"

namespace {

using namespace rhi;

[[noreturn]] void Fail(const std::string& what) {
  std::fprintf(stderr, "gpu_sort_bench: %s\n", what.c_str());
  std::exit(1);
}

struct RawBuffer {
  ComPtr<Buffer> buffer;
  ComPtr<UnorderedAccessView> uav;
};

RawBuffer MakeRaw(Device* device, const std::vector<uint32_t>& words) {
  RawBuffer b;
  const BUFFER_DESC desc{
      UINT(words.size() * 4), USAGE_DEFAULT, BIND_UNORDERED_ACCESS, 0, RESOURCE_MISC_BUFFER_ALLOW_RAW_VIEWS, 0};
  const SUBRESOURCE_DATA data{words.data(), 0, 0};
  UNORDERED_ACCESS_VIEW_DESC u{};
  u.Format = DXGI_FORMAT_R32_TYPELESS;
  u.ViewDimension = UAV_DIMENSION_BUFFER;
  u.Buffer = {0, UINT(words.size()), BUFFER_UAV_FLAG_RAW};
  if (FAILED(device->CreateBuffer(&desc, &data, b.buffer.GetAddressOf())) ||
      FAILED(device->CreateUnorderedAccessView(b.buffer.Get(), &u, b.uav.GetAddressOf())))
    Fail("creating a buffer of " + std::to_string(words.size()) + " words failed");
  return b;
}

std::vector<uint32_t> ReadWords(Device* device, DeviceContext* context, Buffer* buffer, UINT words) {
  const BUFFER_DESC desc{words * 4, USAGE_STAGING, 0, CPU_ACCESS_READ, 0, 0};
  ComPtr<Buffer> staging;
  if (FAILED(device->CreateBuffer(&desc, nullptr, staging.GetAddressOf()))) Fail("staging buffer");
  context->CopyResource(staging.Get(), buffer);
  MAPPED_SUBRESOURCE mapped{};
  if (FAILED(context->Map(staging.Get(), 0, MAP_READ, 0, &mapped))) Fail("Map");
  std::vector<uint32_t> out(words);
  std::memcpy(out.data(), mapped.pData, words * 4);
  context->Unmap(staging.Get(), 0);
  return out;
}

// A TIMESTAMP query at the start of each pass.
class TimestampMarks final : public renderer::oit::PassMarks {
 public:
  TimestampMarks(Device* device, DeviceContext* context, size_t passes) : context_(context), stamps_(passes + 1) {
    const QUERY_DESC stamp{QUERY_TIMESTAMP, 0};
    for (auto& q : stamps_)
      if (FAILED(device->CreateQuery(&stamp, q.GetAddressOf()))) Fail("CreateQuery");
  }
  void BeginPass(size_t index) override { context_->End(stamps_.at(index).Get()); }
  void End() { context_->End(stamps_.back().Get()); }
  // Milliseconds of each pass.
  std::vector<double> PassMs(double frequency) {
    std::vector<UINT64> t(stamps_.size());
    for (size_t i = 0; i < t.size(); ++i)
      if (FAILED(WaitForData(context_, stamps_[i].Get(), &t[i]))) Fail("GetData (timestamp)");
    std::vector<double> ms;
    for (size_t i = 0; i + 1 < t.size(); ++i) ms.push_back(1e3 * double(t[i + 1] - t[i]) / frequency);
    return ms;
  }

 private:
  DeviceContext* context_;
  std::vector<ComPtr<Query>> stamps_;
};

double Median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0 : v[v.size() / 2];
}

// The kind a pass is reported under: the scan's passes together.
std::string Kind(const std::string& pass) {
  if (pass == "ScanBlocks" || pass == "AddBlockOffsets" || pass == "Total") return "Scan";
  return pass;
}

const char* const kKinds[] = {"SortArgs", "Histogram", "Scan", "Scatter", "CopyBack"};

void Measure(Device* device, DeviceContext* context, uint32_t pairs, uint32_t repeats, uint32_t keyBits) {
  std::string error;
  auto sort = renderer::compute::RadixSort::Create(device, pairs, &error);
  if (!sort) Fail(error);
  std::mt19937 random(pairs);
  std::vector<uint32_t> keys(pairs), values(pairs);
  for (uint32_t i = 0; i < pairs; ++i) keys[i] = random(), values[i] = i;
  RawBuffer unsortedKeys = MakeRaw(device, keys), unsortedValues = MakeRaw(device, values);
  RawBuffer keysBuffer = MakeRaw(device, keys), valuesBuffer = MakeRaw(device, values);
  RawBuffer count = MakeRaw(device, {pairs});

  const std::vector<std::string>& names = sort->PassNames(keyBits);
  TimestampMarks marks(device, context, names.size());
  ComPtr<Query> disjoint;
  const QUERY_DESC disjointDesc{QUERY_TIMESTAMP_DISJOINT, 0};
  if (FAILED(device->CreateQuery(&disjointDesc, disjoint.GetAddressOf()))) Fail("CreateQuery");
  std::vector<double> totals;
  std::map<std::string, std::vector<double>> byKind;
  for (uint32_t r = 0; r < repeats; ++r) {
    context->CopyResource(keysBuffer.buffer.Get(), unsortedKeys.buffer.Get());
    context->CopyResource(valuesBuffer.buffer.Get(), unsortedValues.buffer.Get());
    context->Begin(disjoint.Get());
    size_t pass = 0;
    sort->Sort(context, keysBuffer.uav.Get(), valuesBuffer.uav.Get(), count.uav.Get(), 0, keyBits, &marks, &pass);
    marks.End();
    context->End(disjoint.Get());
    QUERY_DATA_TIMESTAMP_DISJOINT clock{};
    if (FAILED(WaitForData(context, disjoint.Get(), &clock)) || clock.Disjoint) Fail("disjoint timestamps");
    const std::vector<double> ms = marks.PassMs(double(clock.Frequency));
    std::map<std::string, double> sums;
    double total = 0;
    for (size_t i = 0; i < ms.size(); ++i) sums[Kind(names[i])] += ms[i], total += ms[i];
    totals.push_back(total);
    for (const char* kind : kKinds) byKind[kind].push_back(sums[kind]);
  }

  const uint32_t mask = keyBits >= 32 ? ~0u : (1u << keyBits) - 1;
  const std::vector<uint32_t> sorted = ReadWords(device, context, keysBuffer.buffer.Get(), pairs);
  for (uint32_t i = 1; i < pairs; ++i)
    if ((sorted[i - 1] & mask) > (sorted[i] & mask)) Fail("the keys are not sorted at " + std::to_string(i));

  const double total = Median(totals);
  std::printf("| %u | %u | %.3f |", pairs, keyBits, total);
  for (const char* kind : kKinds) std::printf(" %.3f |", Median(byKind[kind]));
  std::printf(" %.1f |\n", pairs / (total * 1e3));  // millions of pairs a second
  std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<uint32_t> sizes = {1u << 14, 1u << 16, 1u << 20, 1u << 22};
  uint32_t repeats = 9, keyBits = 32;
  for (int i = 1; i + 1 < argc; i += 2) {
    if (!std::strcmp(argv[i], "--repeats")) {
      repeats = std::max(1ul, std::strtoul(argv[i + 1], nullptr, 10));
    } else if (!std::strcmp(argv[i], "--key-bits")) {
      keyBits = std::min(32ul, std::strtoul(argv[i + 1], nullptr, 10));
    } else if (!std::strcmp(argv[i], "--sizes")) {
      sizes.clear();
      std::stringstream list(argv[i + 1]);
      for (std::string item; std::getline(list, item, ',');) sizes.push_back(std::stoul(item));
    } else {
      Fail(std::string("unknown option ") + argv[i]);
    }
  }
  ComPtr<Device> device;
  ComPtr<DeviceContext> context;
  DEVICE_OPTIONS options;
  if (FAILED(CreateDevice(&options, device.GetAddressOf(), context.GetAddressOf()))) Fail("no device");
  std::printf("RadixSort on %s, median of %u: GPU ms\n\n", device->GetAdapterName(), repeats);
  std::printf("| pairs | key bits | sort ms | args | histogram | scan | scatter | copy back | M pairs/s |\n");
  std::printf("|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
  for (uint32_t size : sizes) Measure(device.Get(), context.Get(), size, repeats, keyBits);
  return 0;
}
