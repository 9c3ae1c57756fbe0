#include "compute_fixture.h"

namespace rhi_test {

ComputeTest::RawBuffer ComputeTest::MakeRaw(const std::vector<uint32_t>& words, UINT miscFlags) {
  RawBuffer b;
  b.buffer = MakeBuffer(rhi::BIND_UNORDERED_ACCESS, words.data(), UINT(words.size() * 4), rhi::USAGE_DEFAULT,
                        rhi::RESOURCE_MISC_BUFFER_ALLOW_RAW_VIEWS | miscFlags);
  rhi::UNORDERED_ACCESS_VIEW_DESC desc{};
  desc.Format = rhi::DXGI_FORMAT_R32_TYPELESS;
  desc.ViewDimension = rhi::UAV_DIMENSION_BUFFER;
  desc.Buffer = {0, UINT(words.size()), rhi::BUFFER_UAV_FLAG_RAW};
  EXPECT_EQ(device->CreateUnorderedAccessView(b.buffer.Get(), &desc, b.uav.GetAddressOf()), rhi::S_OK);
  return b;
}

}  // namespace rhi_test
