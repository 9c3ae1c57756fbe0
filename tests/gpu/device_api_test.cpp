// The device-level methods of ID3D11Device and ID3D11DeviceContext that are
// not about one resource or one pipeline stage: the immediate context, Flush,
// the adapter's name.
#include <chrono>

#include "gpu_helpers.h"

namespace rhi_test {
namespace {

using namespace rhi;

class DeviceApiTest : public RhiGpuTest {};

TEST_F(DeviceApiTest, GetImmediateContextReturnsTheOneContextWithAReference) {
  DeviceContext* immediate = nullptr;
  device->GetImmediateContext(&immediate);
  ASSERT_NE(immediate, nullptr);
  EXPECT_EQ(immediate, context.Get());
  Device* owner = nullptr;
  immediate->GetDevice(&owner);
  EXPECT_EQ(owner, device.Get());
  owner->Release();
  immediate->Release();
}

TEST_F(DeviceApiTest, FlushSubmitsRecordedWorkSoAnEventQueryCompletesWithoutFurtherCalls) {
  Target target = MakeRenderTarget(4, 4);
  Clear(target.rtv.Get(), kRed);
  QUERY_DESC desc{QUERY_EVENT, 0};
  ComPtr<Query> event;
  ASSERT_EQ(device->CreateQuery(&desc, event.GetAddressOf()), S_OK);
  context->End(event.Get());
  context->Flush();
  // DONOTFLUSH: only the Flush above can have submitted the clear and the event.
  // A bounded wait: without the submission the event would never complete.
  BOOL done = FALSE;
  HRESULT hr = S_FALSE;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(20);
  while (hr == S_FALSE && std::chrono::steady_clock::now() < deadline)
    hr = context->GetData(event.Get(), &done, sizeof done, ASYNC_GETDATA_DONOTFLUSH);
  EXPECT_EQ(hr, S_OK);
  EXPECT_EQ(done, TRUE);
}

TEST_F(DeviceApiTest, GetAdapterNameNamesTheVulkanDevice) {
  const std::string name = device->GetAdapterName();
  EXPECT_FALSE(name.empty());
}

}  // namespace
}  // namespace rhi_test
