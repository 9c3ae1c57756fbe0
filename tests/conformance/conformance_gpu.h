// A gtest-free harness for the output-merger conformance matrix: it owns a
// device (validation optional), compiles HLSL in-process, creates targets and
// reads them back. Shared by conformance_tests and conformance_report so both
// run exactly the same code.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "rhi/rhi.h"

namespace conf {

using rhi::ComPtr;
using rhi::UINT;

class Gpu {
 public:
  // adapter: substring of the Vulkan device name, or null (RHI_DEVICE / lavapipe).
  explicit Gpu(const char* adapter = nullptr, bool validation = true);
  ~Gpu();
  bool ok() const { return static_cast<bool>(device_); }

  rhi::Device* device() const { return device_.Get(); }
  rhi::DeviceContext* context() const { return context_.Get(); }
  std::string AdapterName() const;

  // Validation-layer messages and refusals received so far.
  const std::vector<std::string>& validation() const { return validation_; }
  const std::vector<std::string>& refusals() const { return refusals_; }
  void ClearMessages() { validation_.clear(); refusals_.clear(); }

  // Throws std::runtime_error with the compiler's messages on failure.
  static std::vector<uint32_t> Compile(std::string_view source, const char* profile);
  ComPtr<rhi::VertexShader> VS(std::string_view source);
  ComPtr<rhi::PixelShader> PS(std::string_view source);

  ComPtr<rhi::Texture2D> Texture(UINT width, UINT height, rhi::DXGI_FORMAT format, UINT bindFlags,
                                 UINT samples = 1);
  ComPtr<rhi::RenderTargetView> RTV(rhi::Texture2D* texture);
  ComPtr<rhi::ShaderResourceView> SRV(rhi::Resource* resource, const rhi::SHADER_RESOURCE_VIEW_DESC* desc = nullptr);
  // A structured buffer of `count` elements of `stride` bytes with its SRV.
  ComPtr<rhi::ShaderResourceView> StructuredSRV(const void* data, UINT stride, UINT count,
                                                ComPtr<rhi::Buffer>* buffer = nullptr);
  ComPtr<rhi::Buffer> ConstantBuffer(const void* data, UINT size);
  void Viewport(UINT width, UINT height);

  // Subresource 0, rows tightly packed (width * bytesPerPixel).
  std::vector<uint8_t> Read(rhi::Texture2D* texture, UINT bytesPerPixel);

 private:
  ComPtr<rhi::Device> device_;
  ComPtr<rhi::DeviceContext> context_;
  std::vector<std::string> validation_;
  std::vector<std::string> refusals_;
};

}  // namespace conf
