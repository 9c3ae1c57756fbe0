#pragma once

#include <filesystem>
#include <string>

#include "fx/effect.h"
#include "gpu_test.h"

namespace effects_test {

using rhi::UINT;
using rhi::LPCSTR;
using rhi::TRUE;

inline const std::string kShaderDir = PROJECT_SOURCE_ROOT "/shaders_hlsl";

// One cache shared by the suite's tests (the cache tests use their own folders).
inline std::string SuiteCache() { return (std::filesystem::temp_directory_path() / "fxrt_test_cache").string(); }

class EffectTest : public rhi_test::GpuTest {
 protected:
  rhi::ComPtr<fx::Effect> Load(const std::string& path, std::string cache = SuiteCache()) {
    fx::EFFECT_OPTIONS options;
    options.CacheDirectory = cache;
    options.Errors = &errors;
    rhi::ComPtr<fx::Effect> effect;
    EXPECT_EQ(fx::CreateEffectFromFile(path.c_str(), options, device.Get(), effect.GetAddressOf()), rhi::S_OK)
        << errors;
    return effect;
  }
  rhi::ComPtr<fx::Effect> FromMemory(const std::string& source, std::string cache = SuiteCache()) {
    fx::EFFECT_OPTIONS options;
    options.CacheDirectory = cache;
    options.Errors = &errors;
    rhi::ComPtr<fx::Effect> effect;
    EXPECT_EQ(fx::CreateEffectFromMemory(source.data(), source.size(), "test.fx", options, device.Get(),
                                         effect.GetAddressOf()),
              rhi::S_OK)
        << errors;
    return effect;
  }
  // A RWStructuredBuffer<uint/float> of n elements with its UAV (uavFlags:
  // BUFFER_UAV_FLAG_APPEND / _COUNTER for a hidden counter).
  struct Rw {
    rhi::ComPtr<rhi::Buffer> buffer;
    rhi::ComPtr<rhi::UnorderedAccessView> uav;
  };
  Rw MakeRw(UINT n, UINT uavFlags = 0) {
    Rw rw;
    rw.buffer = MakeBuffer(rhi::BIND_UNORDERED_ACCESS, nullptr, n * 4, rhi::USAGE_DEFAULT,
                           rhi::RESOURCE_MISC_BUFFER_STRUCTURED, 4);
    rhi::UNORDERED_ACCESS_VIEW_DESC desc{};
    desc.Format = rhi::DXGI_FORMAT_UNKNOWN;
    desc.ViewDimension = rhi::UAV_DIMENSION_BUFFER;
    desc.Buffer = {0, n, uavFlags};
    EXPECT_EQ(device->CreateUnorderedAccessView(rw.buffer.Get(), &desc, rw.uav.GetAddressOf()), rhi::S_OK);
    return rw;
  }
  std::string errors;
};

}  // namespace effects_test
