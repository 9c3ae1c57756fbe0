// The fixture of every test that runs on a Vulkan device.
//
// It creates a device with the Khronos validation layer on and collects every
// message: a validation-layer message fails the test; refusals
// (the D3D11 debug layer's role) are kept for tests to inspect.
#pragma once

#include <gtest/gtest.h>

#include <cstring>
#include <mutex>
#include <string>
#include <string_view>
#include <vector>

#include "rhi/query_wait.h"
#include "rhi/rhi.h"

namespace rhi_test {

using rhi::ComPtr;
using rhi::UINT;

struct Message {
  rhi::MESSAGE_CATEGORY category;
  rhi::MESSAGE_SEVERITY severity;
  std::string text;
};

// SPIR-V bytes of an HLSL entry point, compiled in-process; fails the test on error.
std::vector<uint32_t> CompileHlsl(std::string_view source, const char* entry, const char* profile);

class GpuTest : public ::testing::Test {
 protected:
  ~GpuTest() override;
  void SetUp() override;

  // Messages that are not validation-layer messages (refusal reasons).
  std::vector<std::string> Refusals() const;
  bool RefusedWith(std::string_view fragment) const;
  void ClearMessages() { messages_.clear(); }

  ComPtr<rhi::VertexShader> VS(std::string_view source, const char* entry = "main");
  ComPtr<rhi::PixelShader> PS(std::string_view source, const char* entry = "main");
  ComPtr<rhi::GeometryShader> GS(std::string_view source, const char* entry = "main");
  ComPtr<rhi::ComputeShader> CS(std::string_view source, const char* entry = "main");

  struct Target {
    ComPtr<rhi::Texture2D> texture;
    ComPtr<rhi::RenderTargetView> rtv;
  };
  Target MakeRenderTarget(UINT width, UINT height, rhi::DXGI_FORMAT format = rhi::DXGI_FORMAT_R8G8B8A8_UNORM,
                          UINT samples = 1);
  ComPtr<rhi::Buffer> MakeBuffer(UINT bindFlags, const void* data, UINT size, rhi::USAGE usage = rhi::USAGE_DEFAULT,
                                 UINT miscFlags = 0, UINT stride = 0);
  // Sets a full-target viewport.
  void SetViewport(UINT width, UINT height);

  // Copies a texture subresource into a staging texture and returns its rows, tightly packed.
  std::vector<uint8_t> ReadTexture(rhi::Texture2D* texture, UINT subresource = 0);
  std::vector<uint8_t> ReadBuffer(rhi::Buffer* buffer);
  template <class T>
  std::vector<T> ReadBufferAs(rhi::Buffer* buffer) {
    std::vector<uint8_t> bytes = ReadBuffer(buffer);
    std::vector<T> values(bytes.size() / sizeof(T));
    std::memcpy(values.data(), bytes.data(), values.size() * sizeof(T));
    return values;
  }
  // One RGBA8 pixel of ReadTexture's result.
  static uint32_t Pixel(const std::vector<uint8_t>& rgba8, UINT width, UINT x, UINT y);

  // Polls a query until its data is ready; a failed GetData fails the test.
  template <class T>
  T WaitForData(rhi::Query* query) {
    T data{};
    EXPECT_EQ(rhi::WaitForData(context.Get(), query, &data), rhi::S_OK);
    return data;
  }

  ComPtr<rhi::Device> device;
  ComPtr<rhi::DeviceContext> context;
  std::vector<Message> messages_;
  std::mutex messagesMutex_;
};

}  // namespace rhi_test
