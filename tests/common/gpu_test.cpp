#include "gpu_test.h"

#include <vulkan/vulkan.h>

#include "hlsl/hlsl_compiler.h"
#include "rhi/capture.h"

namespace rhi_test {

namespace {

// Some drivers fail after many instance create/destroy cycles in one process;
// one instance kept alive for the whole test binary keeps the loader and the
// driver loaded.
void KeepVulkanLoaded() {
  static VkInstance instance = [] {
    VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
    app.apiVersion = VK_API_VERSION_1_3;
    VkInstanceCreateInfo info{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
    info.pApplicationInfo = &app;
    VkInstance created = VK_NULL_HANDLE;
    vkCreateInstance(&info, nullptr, &created);
    return created;
  }();
  (void)instance;
}

}  // namespace

std::vector<uint32_t> CompileHlsl(std::string_view source, const char* entry, const char* profile) {
  hlsl::CompileRequest request;
  request.source = std::string(source);
  request.fileName = "test.hlsl";
  request.entryPoint = entry;
  request.profile = profile;
  hlsl::CompileResult result = hlsl::CompileHlsl(request);
  EXPECT_TRUE(result.ok) << result.FormatErrors();
  return result.spirv;
}

void GpuTest::SetUp() {
  KeepVulkanLoaded();
  rhi::DEVICE_OPTIONS options;
  options.EnableValidation = rhi::TRUE;
  options.OnMessage = [this](rhi::MESSAGE_CATEGORY category, rhi::MESSAGE_SEVERITY severity, const char* text) {
    std::lock_guard lock(messagesMutex_);  // the device is free-threaded: messages come from any thread
    messages_.push_back({category, severity, text});
  };
  ASSERT_EQ(rhi::CreateDevice(&options, device.GetAddressOf(), context.GetAddressOf()), rhi::S_OK);
}

// After derived fixtures' members are gone (gtest reports failures raised in
// the fixture's destructor against the test), so the device must go with this
// last reference: one that outlives it leaks its Vulkan device, and work still
// queued then races the process exit.
GpuTest::~GpuTest() {
  if (context) context->Flush();
  context.Reset();
  if (rhi::Device* last = device.Detach()) {
    EXPECT_EQ(last->Release(), 0u) << "the device outlives its last reference (a leaked device child?)";
  }
  for (const Message& m : messages_)
    if (m.category == rhi::MESSAGE_CATEGORY_VULKAN_VALIDATION) ADD_FAILURE() << "validation layer: " << m.text;
}

std::vector<std::string> GpuTest::Refusals() const {
  std::vector<std::string> texts;
  for (const Message& m : messages_)
    if (m.category != rhi::MESSAGE_CATEGORY_VULKAN_VALIDATION) texts.push_back(m.text);
  return texts;
}

bool GpuTest::RefusedWith(std::string_view fragment) const {
  for (const std::string& text : Refusals())
    if (text.find(fragment) != std::string::npos) return true;
  return false;
}

ComPtr<rhi::VertexShader> GpuTest::VS(std::string_view source, const char* entry) {
  auto code = CompileHlsl(source, entry, "vs_5_0");
  ComPtr<rhi::VertexShader> shader;
  EXPECT_EQ(device->CreateVertexShader(code.data(), code.size() * 4, nullptr, shader.GetAddressOf()), rhi::S_OK);
  return shader;
}

ComPtr<rhi::PixelShader> GpuTest::PS(std::string_view source, const char* entry) {
  auto code = CompileHlsl(source, entry, "ps_5_0");
  ComPtr<rhi::PixelShader> shader;
  EXPECT_EQ(device->CreatePixelShader(code.data(), code.size() * 4, nullptr, shader.GetAddressOf()), rhi::S_OK);
  return shader;
}

ComPtr<rhi::GeometryShader> GpuTest::GS(std::string_view source, const char* entry) {
  auto code = CompileHlsl(source, entry, "gs_5_0");
  ComPtr<rhi::GeometryShader> shader;
  EXPECT_EQ(device->CreateGeometryShader(code.data(), code.size() * 4, nullptr, shader.GetAddressOf()), rhi::S_OK);
  return shader;
}

ComPtr<rhi::ComputeShader> GpuTest::CS(std::string_view source, const char* entry) {
  auto code = CompileHlsl(source, entry, "cs_5_0");
  ComPtr<rhi::ComputeShader> shader;
  EXPECT_EQ(device->CreateComputeShader(code.data(), code.size() * 4, nullptr, shader.GetAddressOf()), rhi::S_OK);
  return shader;
}

GpuTest::Target GpuTest::MakeRenderTarget(UINT width, UINT height, rhi::DXGI_FORMAT format, UINT samples) {
  rhi::TEXTURE2D_DESC desc{};
  desc.Width = width;
  desc.Height = height;
  desc.MipLevels = 1;
  desc.ArraySize = 1;
  desc.Format = format;
  desc.SampleDesc.Count = samples;
  desc.Usage = rhi::USAGE_DEFAULT;
  desc.BindFlags = rhi::BIND_RENDER_TARGET | (samples == 1 ? UINT{rhi::BIND_SHADER_RESOURCE} : 0u);
  Target target;
  EXPECT_EQ(device->CreateTexture2D(&desc, nullptr, target.texture.GetAddressOf()), rhi::S_OK);
  EXPECT_EQ(device->CreateRenderTargetView(target.texture.Get(), nullptr, target.rtv.GetAddressOf()), rhi::S_OK);
  return target;
}

ComPtr<rhi::Buffer> GpuTest::MakeBuffer(UINT bindFlags, const void* data, UINT size, rhi::USAGE usage,
                                        UINT miscFlags, UINT stride) {
  rhi::BUFFER_DESC desc{size, usage, bindFlags, usage == rhi::USAGE_DYNAMIC ? rhi::CPU_ACCESS_WRITE : 0u, miscFlags,
                        stride};
  rhi::SUBRESOURCE_DATA init{data, 0, 0};
  ComPtr<rhi::Buffer> buffer;
  EXPECT_EQ(device->CreateBuffer(&desc, data ? &init : nullptr, buffer.GetAddressOf()), rhi::S_OK);
  return buffer;
}

void GpuTest::SetViewport(UINT width, UINT height) {
  rhi::VIEWPORT viewport{0, 0, static_cast<float>(width), static_cast<float>(height), 0, 1};
  context->RSSetViewports(1, &viewport);
}

std::vector<uint8_t> GpuTest::ReadTexture(rhi::Texture2D* texture, UINT subresource) {
  std::vector<uint8_t> texels;
  EXPECT_EQ(rhi::CaptureTexture2D(device.Get(), context.Get(), texture, subresource, &texels), rhi::S_OK);
  return texels;
}

std::vector<uint8_t> GpuTest::ReadBuffer(rhi::Buffer* buffer) {
  rhi::BUFFER_DESC desc;
  buffer->GetDesc(&desc);
  rhi::BUFFER_DESC stagingDesc{desc.ByteWidth, rhi::USAGE_STAGING, 0, rhi::CPU_ACCESS_READ, 0, 0};
  ComPtr<rhi::Buffer> staging;
  EXPECT_EQ(device->CreateBuffer(&stagingDesc, nullptr, staging.GetAddressOf()), rhi::S_OK);
  context->CopyResource(staging.Get(), buffer);
  rhi::MAPPED_SUBRESOURCE mapped{};
  EXPECT_EQ(context->Map(staging.Get(), 0, rhi::MAP_READ, 0, &mapped), rhi::S_OK);
  std::vector<uint8_t> bytes(desc.ByteWidth);
  std::memcpy(bytes.data(), mapped.pData, bytes.size());
  context->Unmap(staging.Get(), 0);
  return bytes;
}

uint32_t GpuTest::Pixel(const std::vector<uint8_t>& rgba8, UINT width, UINT x, UINT y) {
  uint32_t value;
  std::memcpy(&value, rgba8.data() + (static_cast<size_t>(y) * width + x) * 4, 4);
  return value;
}

}  // namespace rhi_test
