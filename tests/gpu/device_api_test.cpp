// The device-level methods of ID3D11Device and ID3D11DeviceContext that are
// not about one resource or one pipeline stage: the immediate context, Flush,
// the adapter's name, feature level, format and feature support, creation
// flags, exception mode, removal, and the refusals of what Vulkan lacks
// (class linkage, counters, shared resources).
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

TEST_F(DeviceApiTest, FeatureLevelIs11_0AndTheContextIsImmediate) {
  EXPECT_EQ(device->GetFeatureLevel(), D3D_FEATURE_LEVEL_11_0);
  EXPECT_EQ(context->GetType(), DEVICE_CONTEXT_IMMEDIATE);
  EXPECT_EQ(context->GetContextFlags(), 0u);
}

TEST_F(DeviceApiTest, CreationFlagsSayDebugWhileTheValidationLayerIsOn) {
  // The fixture's device runs with the validation layer (RHI_VALIDATION=1 under ctest).
  EXPECT_EQ(device->GetCreationFlags() & CREATE_DEVICE_DEBUG, CREATE_DEVICE_DEBUG);
}

TEST_F(DeviceApiTest, ExceptionModeIsKeptAndUnknownFlagsAreRefused) {
  EXPECT_EQ(device->GetExceptionMode(), 0u);
  EXPECT_EQ(device->SetExceptionMode(RAISE_FLAG_DRIVER_INTERNAL_ERROR), S_OK);
  EXPECT_EQ(device->GetExceptionMode(), UINT(RAISE_FLAG_DRIVER_INTERNAL_ERROR));
  EXPECT_EQ(device->SetExceptionMode(0x10), E_INVALIDARG);
  EXPECT_TRUE(RefusedWith("RAISE_FLAG_DRIVER_INTERNAL_ERROR"));
  EXPECT_EQ(device->GetExceptionMode(), UINT(RAISE_FLAG_DRIVER_INTERNAL_ERROR));
}

TEST_F(DeviceApiTest, AHealthyDeviceHasNoRemovedReason) { EXPECT_EQ(device->GetDeviceRemovedReason(), S_OK); }

// A format's support bits, as D3D11 names them: those it must have, those it must lack.
struct FormatSupportCase {
  DXGI_FORMAT format;
  UINT has, lacks;
};

class FormatSupportTest : public DeviceApiTest, public ::testing::WithParamInterface<FormatSupportCase> {};

TEST_P(FormatSupportTest, CheckFormatSupportReportsD3D11sUsesOfTheFormat) {
  const FormatSupportCase& c = GetParam();
  UINT support = 0;
  ASSERT_EQ(device->CheckFormatSupport(c.format, &support), S_OK);
  EXPECT_EQ(support & c.has, c.has) << std::hex << "support 0x" << support;
  EXPECT_EQ(support & c.lacks, 0u) << std::hex << "support 0x" << support;
  // FEATURE_FORMAT_SUPPORT answers the same.
  FEATURE_DATA_FORMAT_SUPPORT data{c.format, 0};
  ASSERT_EQ(device->CheckFeatureSupport(FEATURE_FORMAT_SUPPORT, &data, sizeof data), S_OK);
  EXPECT_EQ(data.OutFormatSupport, support);
}

// Feature level 11_0's required support (the D3D11 format support tables) for
// formats of each kind; the backend must have it on every device it accepts.
INSTANTIATE_TEST_SUITE_P(
    Formats, FormatSupportTest,
    ::testing::Values(
        FormatSupportCase{DXGI_FORMAT_R8G8B8A8_UNORM,
                          FORMAT_SUPPORT_TEXTURE2D | FORMAT_SUPPORT_TEXTURECUBE | FORMAT_SUPPORT_SHADER_SAMPLE |
                              FORMAT_SUPPORT_RENDER_TARGET | FORMAT_SUPPORT_BLENDABLE | FORMAT_SUPPORT_MIP_AUTOGEN |
                              FORMAT_SUPPORT_IA_VERTEX_BUFFER | FORMAT_SUPPORT_MULTISAMPLE_RENDERTARGET |
                              FORMAT_SUPPORT_MULTISAMPLE_RESOLVE,
                          FORMAT_SUPPORT_DEPTH_STENCIL | FORMAT_SUPPORT_IA_INDEX_BUFFER},
        FormatSupportCase{DXGI_FORMAT_R32_UINT,
                          FORMAT_SUPPORT_SHADER_LOAD | FORMAT_SUPPORT_RENDER_TARGET | FORMAT_SUPPORT_IA_INDEX_BUFFER |
                              FORMAT_SUPPORT_TYPED_UNORDERED_ACCESS_VIEW,
                          FORMAT_SUPPORT_SHADER_SAMPLE | FORMAT_SUPPORT_MULTISAMPLE_RESOLVE | FORMAT_SUPPORT_BLENDABLE},
        FormatSupportCase{DXGI_FORMAT_R16_UINT, FORMAT_SUPPORT_IA_INDEX_BUFFER, FORMAT_SUPPORT_SHADER_SAMPLE},
        FormatSupportCase{DXGI_FORMAT_D24_UNORM_S8_UINT, FORMAT_SUPPORT_DEPTH_STENCIL | FORMAT_SUPPORT_TEXTURE2D,
                          FORMAT_SUPPORT_RENDER_TARGET | FORMAT_SUPPORT_SHADER_SAMPLE | FORMAT_SUPPORT_TEXTURE3D},
        FormatSupportCase{DXGI_FORMAT_R32G32B32A32_FLOAT,
                          FORMAT_SUPPORT_SHADER_SAMPLE | FORMAT_SUPPORT_RENDER_TARGET | FORMAT_SUPPORT_BLENDABLE |
                              FORMAT_SUPPORT_IA_VERTEX_BUFFER | FORMAT_SUPPORT_BUFFER,
                          FORMAT_SUPPORT_DEPTH_STENCIL},
        FormatSupportCase{DXGI_FORMAT_R32_TYPELESS, FORMAT_SUPPORT_TEXTURE2D | FORMAT_SUPPORT_CAST_WITHIN_BIT_LAYOUT,
                          FORMAT_SUPPORT_RENDER_TARGET | FORMAT_SUPPORT_SHADER_SAMPLE}),
    [](const auto& info) { return std::to_string(info.param.format); });

TEST_F(DeviceApiTest, CheckFormatSupportFailsForAnUnusableFormat) {
  UINT support = 123;
  EXPECT_EQ(device->CheckFormatSupport(DXGI_FORMAT_UNKNOWN, &support), E_FAIL);
  EXPECT_EQ(support, 0u);
}

// The render-target and multisample bits agree with what creation accepts.
TEST_F(DeviceApiTest, FormatSupportAgreesWithTextureCreation) {
  for (DXGI_FORMAT format : {DXGI_FORMAT_R8G8B8A8_UNORM, DXGI_FORMAT_R32_UINT, DXGI_FORMAT_R16G16B16A16_FLOAT,
                             DXGI_FORMAT_R32G32B32A32_FLOAT, DXGI_FORMAT_B8G8R8A8_UNORM, DXGI_FORMAT_R8_UNORM}) {
    SCOPED_TRACE(testing::Message() << "format " << format);
    UINT support = 0;
    ASSERT_EQ(device->CheckFormatSupport(format, &support), S_OK);
    TEXTURE2D_DESC desc{4, 4, 1, 1, format, {1, 0}, USAGE_DEFAULT, BIND_RENDER_TARGET, 0, 0};
    ComPtr<Texture2D> texture;
    EXPECT_EQ(device->CreateTexture2D(&desc, nullptr, texture.GetAddressOf()) == S_OK,
              (support & FORMAT_SUPPORT_RENDER_TARGET) != 0);
    UINT levels = 0;
    ASSERT_EQ(device->CheckMultisampleQualityLevels(format, 4, &levels), S_OK);
    EXPECT_EQ(levels > 0, (support & FORMAT_SUPPORT_MULTISAMPLE_RENDERTARGET) != 0);
  }
}

TEST_F(DeviceApiTest, CheckFeatureSupportAnswersEveryDirect3D11_0Feature) {
  FEATURE_DATA_THREADING threading{TRUE, TRUE};
  ASSERT_EQ(device->CheckFeatureSupport(FEATURE_THREADING, &threading, sizeof threading), S_OK);
  EXPECT_EQ(threading.DriverCommandLists, FALSE) << "command lists are the runtime's, not the driver's";
  FEATURE_DATA_DOUBLES doubles{};
  EXPECT_EQ(device->CheckFeatureSupport(FEATURE_DOUBLES, &doubles, sizeof doubles), S_OK);
  FEATURE_DATA_D3D10_X_HARDWARE_OPTIONS options{};
  ASSERT_EQ(device->CheckFeatureSupport(FEATURE_D3D10_X_HARDWARE_OPTIONS, &options, sizeof options), S_OK);
  EXPECT_EQ(options.ComputeShaders_Plus_RawAndStructuredBuffers_Via_Shader_4_x, TRUE);
  FEATURE_DATA_FORMAT_SUPPORT2 uav{DXGI_FORMAT_R32_UINT, 0};
  ASSERT_EQ(device->CheckFeatureSupport(FEATURE_FORMAT_SUPPORT2, &uav, sizeof uav), S_OK);
  EXPECT_EQ(uav.OutFormatSupport2 & (FORMAT_SUPPORT2_UAV_TYPED_LOAD | FORMAT_SUPPORT2_UAV_TYPED_STORE),
            UINT(FORMAT_SUPPORT2_UAV_TYPED_LOAD | FORMAT_SUPPORT2_UAV_TYPED_STORE));
  EXPECT_NE(uav.OutFormatSupport2 & FORMAT_SUPPORT2_UAV_ATOMIC_ADD, 0u) << "InterlockedAdd on R32_UINT (uav_test)";
  // A wrong size and a feature of a later version are refused.
  EXPECT_EQ(device->CheckFeatureSupport(FEATURE_THREADING, &threading, 4), E_INVALIDARG);
  EXPECT_TRUE(RefusedWith("FEATURE_THREADING needs pFeatureSupportData of 8 bytes"));
  EXPECT_EQ(device->CheckFeatureSupport(FEATURE(6), &threading, sizeof threading), E_INVALIDARG);
  EXPECT_TRUE(RefusedWith("is not a Direct3D 11.0 feature"));
}

TEST_F(DeviceApiTest, ClassLinkageIsNotImplementedWithTheReason) {
  ClassLinkage* linkage = reinterpret_cast<ClassLinkage*>(this);
  EXPECT_EQ(device->CreateClassLinkage(&linkage), E_NOTIMPL);
  EXPECT_EQ(linkage, nullptr);
  EXPECT_TRUE(RefusedWith("no SPIR-V counterpart"));
}

TEST_F(DeviceApiTest, TheDeviceHasNoCountersAndSaysSo) {
  COUNTER_INFO info{COUNTER_DEVICE_DEPENDENT_0, 9, 9};
  device->CheckCounterInfo(&info);
  EXPECT_EQ(info.LastDeviceDependentCounter, COUNTER(0));
  EXPECT_EQ(info.NumSimultaneousCounters, 0u);
  const COUNTER_DESC desc{COUNTER_DEVICE_DEPENDENT_0, 0};
  Counter* counter = reinterpret_cast<Counter*>(this);
  EXPECT_EQ(device->CreateCounter(&desc, &counter), DXGI_ERROR_UNSUPPORTED);
  EXPECT_EQ(counter, nullptr);
  COUNTER_TYPE type;
  UINT active = 0;
  EXPECT_EQ(device->CheckCounter(&desc, &type, &active, nullptr, nullptr, nullptr, nullptr, nullptr, nullptr),
            E_INVALIDARG);
  EXPECT_TRUE(RefusedWith("no device-dependent counters"));
}

TEST_F(DeviceApiTest, NoResourceIsSharedSoOpenSharedResourceAndMiscSharedAreRefused) {
  void* resource = this;
  const GUID anyInterface{};
  EXPECT_EQ(device->OpenSharedResource(reinterpret_cast<HANDLE>(0x1234), anyInterface, &resource), E_INVALIDARG);
  EXPECT_EQ(resource, nullptr);
  EXPECT_TRUE(RefusedWith("shares no resources"));
  TEXTURE2D_DESC desc{4, 4, 1, 1, DXGI_FORMAT_R8G8B8A8_UNORM, {1, 0}, USAGE_DEFAULT, BIND_SHADER_RESOURCE, 0,
                      RESOURCE_MISC_SHARED};
  ComPtr<Texture2D> texture;
  EXPECT_EQ(device->CreateTexture2D(&desc, nullptr, texture.GetAddressOf()), E_INVALIDARG);
  EXPECT_TRUE(RefusedWith("RESOURCE_MISC_SHARED is not supported"));
}

// A GUID of the application's own.
constexpr GUID kAppGuid = {0x12345678, 0x1234, 0x5678, {1, 2, 3, 4, 5, 6, 7, 8}};

TEST_F(DeviceApiTest, PrivateDataFollowsD3D11sSizeAndNotFoundRules) {
  UINT size = 99;
  EXPECT_EQ(device->GetPrivateData(kAppGuid, &size, nullptr), DXGI_ERROR_NOT_FOUND);
  EXPECT_EQ(size, 0u);
  const uint32_t value[2] = {7, 9};
  ASSERT_EQ(device->SetPrivateData(kAppGuid, sizeof value, value), S_OK);
  EXPECT_EQ(device->GetPrivateData(kAppGuid, &size, nullptr), S_OK);
  EXPECT_EQ(size, sizeof value) << "a null pData asks for the size";
  uint32_t small = 0;
  size = sizeof small;
  EXPECT_EQ(device->GetPrivateData(kAppGuid, &size, &small), DXGI_ERROR_MORE_DATA);
  EXPECT_EQ(size, sizeof value);
  uint32_t got[2] = {};
  size = sizeof got;
  ASSERT_EQ(device->GetPrivateData(kAppGuid, &size, got), S_OK);
  EXPECT_EQ(got[0], 7u);
  EXPECT_EQ(got[1], 9u);
  // Null data removes the entry.
  ASSERT_EQ(device->SetPrivateData(kAppGuid, 0, nullptr), S_OK);
  EXPECT_EQ(device->GetPrivateData(kAppGuid, &size, nullptr), DXGI_ERROR_NOT_FOUND);
}

TEST_F(DeviceApiTest, PrivateDataInterfaceHoldsAReferenceAndGetAddRefs) {
  ComPtr<Buffer> buffer = MakeBuffer(BIND_VERTEX_BUFFER, nullptr, 16);
  auto references = [&] {
    buffer->AddRef();
    return buffer->Release();
  };
  const UINT before = references();
  ASSERT_EQ(device->SetPrivateDataInterface(kAppGuid, buffer.Get()), S_OK);
  EXPECT_EQ(references(), before + 1) << "the device holds a reference";
  Unknown* got = nullptr;
  UINT size = sizeof got;
  ASSERT_EQ(device->GetPrivateData(kAppGuid, &size, &got), S_OK);
  EXPECT_EQ(got, static_cast<Unknown*>(buffer.Get()));
  EXPECT_EQ(references(), before + 2) << "GetPrivateData AddRefs the interface";
  got->Release();
  ASSERT_EQ(device->SetPrivateDataInterface(kAppGuid, nullptr), S_OK);
  EXPECT_EQ(references(), before) << "removing the entry releases it";
}

TEST_F(DeviceApiTest, DebugObjectNameIsKeptAndNamesTheVulkanDevice) {
  const std::string name = "port's device";
  // Without the terminating null, as D3D11 samples pass it; the validation layer
  // (on in this fixture) checks the vkSetDebugUtilsObjectNameEXT call.
  ASSERT_EQ(device->SetPrivateData(WKPDID_D3DDebugObjectName, UINT(name.size()), name.data()), S_OK);
  std::string got(name.size(), '\0');
  UINT size = UINT(got.size());
  ASSERT_EQ(device->GetPrivateData(WKPDID_D3DDebugObjectName, &size, got.data()), S_OK);
  EXPECT_EQ(got, name);
}

}  // namespace
}  // namespace rhi_test
