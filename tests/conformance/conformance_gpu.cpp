#include "conformance_gpu.h"

#include <cstring>
#include <stdexcept>

#include "hlsl/hlsl_compiler.h"

namespace conf {

Gpu::Gpu(const char* adapter, bool validation) {
  rhi::DEVICE_OPTIONS options;
  options.AdapterName = adapter;
  options.EnableValidation = validation ? rhi::TRUE : rhi::FALSE;
  options.OnMessage = [this](rhi::MESSAGE_CATEGORY category, rhi::MESSAGE_SEVERITY, const char* text) {
    (category == rhi::MESSAGE_CATEGORY_VULKAN_VALIDATION ? validation_ : refusals_).push_back(text);
  };
  if (rhi::CreateDevice(&options, device_.GetAddressOf(), context_.GetAddressOf()) != rhi::S_OK) {
    context_.Reset();
    device_.Reset();
  }
}

Gpu::~Gpu() {
  if (context_) context_->Flush();
  context_.Reset();
  device_.Reset();
}

std::string Gpu::AdapterName() const { return device_ ? device_->GetAdapterName() : "(no device)"; }

std::vector<uint32_t> Gpu::Compile(std::string_view source, const char* profile) {
  hlsl::CompileRequest request;
  request.source = std::string(source);
  request.fileName = "conformance.hlsl";
  request.entryPoint = "main";
  request.profile = profile;
  request.isolate = false;  // our own sources, known to compile
  hlsl::CompileResult result = hlsl::CompileHlsl(request);
  if (!result.ok) throw std::runtime_error("HLSL compile failed:\n" + result.FormatErrors() + "\n" + request.source);
  return result.spirv;
}

ComPtr<rhi::VertexShader> Gpu::VS(std::string_view source) {
  auto code = Compile(source, "vs_5_0");
  ComPtr<rhi::VertexShader> shader;
  if (device_->CreateVertexShader(code.data(), code.size() * 4, nullptr, shader.GetAddressOf()) != rhi::S_OK)
    throw std::runtime_error("CreateVertexShader failed");
  return shader;
}

ComPtr<rhi::PixelShader> Gpu::PS(std::string_view source) {
  auto code = Compile(source, "ps_5_0");
  ComPtr<rhi::PixelShader> shader;
  if (device_->CreatePixelShader(code.data(), code.size() * 4, nullptr, shader.GetAddressOf()) != rhi::S_OK)
    throw std::runtime_error("CreatePixelShader failed");
  return shader;
}

ComPtr<rhi::Texture2D> Gpu::Texture(UINT width, UINT height, rhi::DXGI_FORMAT format, UINT bindFlags,
                                    UINT samples) {
  rhi::TEXTURE2D_DESC desc{};
  desc.Width = width;
  desc.Height = height;
  desc.MipLevels = 1;
  desc.ArraySize = 1;
  desc.Format = format;
  desc.SampleDesc.Count = samples;
  desc.Usage = rhi::USAGE_DEFAULT;
  desc.BindFlags = bindFlags;
  ComPtr<rhi::Texture2D> texture;
  if (device_->CreateTexture2D(&desc, nullptr, texture.GetAddressOf()) != rhi::S_OK)
    throw std::runtime_error("CreateTexture2D failed for format " + std::to_string(format));
  return texture;
}

ComPtr<rhi::RenderTargetView> Gpu::RTV(rhi::Texture2D* texture) {
  ComPtr<rhi::RenderTargetView> view;
  if (device_->CreateRenderTargetView(texture, nullptr, view.GetAddressOf()) != rhi::S_OK)
    throw std::runtime_error("CreateRenderTargetView failed");
  return view;
}

ComPtr<rhi::ShaderResourceView> Gpu::SRV(rhi::Resource* resource, const rhi::SHADER_RESOURCE_VIEW_DESC* desc) {
  ComPtr<rhi::ShaderResourceView> view;
  if (device_->CreateShaderResourceView(resource, desc, view.GetAddressOf()) != rhi::S_OK)
    throw std::runtime_error("CreateShaderResourceView failed");
  return view;
}

ComPtr<rhi::ShaderResourceView> Gpu::StructuredSRV(const void* data, UINT stride, UINT count,
                                                   ComPtr<rhi::Buffer>* bufferOut) {
  rhi::BUFFER_DESC desc{stride * count, rhi::USAGE_DEFAULT, rhi::BIND_SHADER_RESOURCE, 0,
                        rhi::RESOURCE_MISC_BUFFER_STRUCTURED, stride};
  rhi::SUBRESOURCE_DATA init{data, 0, 0};
  ComPtr<rhi::Buffer> buffer;
  if (device_->CreateBuffer(&desc, &init, buffer.GetAddressOf()) != rhi::S_OK)
    throw std::runtime_error("CreateBuffer (structured) failed");
  rhi::SHADER_RESOURCE_VIEW_DESC srv{};
  srv.Format = rhi::DXGI_FORMAT_UNKNOWN;
  srv.ViewDimension = rhi::SRV_DIMENSION_BUFFER;
  srv.Buffer.FirstElement = 0;
  srv.Buffer.NumElements = count;
  auto view = SRV(buffer.Get(), &srv);
  if (bufferOut) *bufferOut = buffer;
  return view;
}

ComPtr<rhi::Buffer> Gpu::ConstantBuffer(const void* data, UINT size) {
  rhi::BUFFER_DESC desc{(size + 15u) & ~15u, rhi::USAGE_DEFAULT, rhi::BIND_CONSTANT_BUFFER, 0, 0, 0};
  std::vector<uint8_t> padded(desc.ByteWidth, 0);
  std::memcpy(padded.data(), data, size);
  rhi::SUBRESOURCE_DATA init{padded.data(), 0, 0};
  ComPtr<rhi::Buffer> buffer;
  if (device_->CreateBuffer(&desc, &init, buffer.GetAddressOf()) != rhi::S_OK)
    throw std::runtime_error("CreateBuffer (constant) failed");
  return buffer;
}

void Gpu::Viewport(UINT width, UINT height) {
  rhi::VIEWPORT viewport{0, 0, static_cast<float>(width), static_cast<float>(height), 0, 1};
  context_->RSSetViewports(1, &viewport);
}

std::vector<uint8_t> Gpu::Read(rhi::Texture2D* texture, UINT bytesPerPixel) {
  rhi::TEXTURE2D_DESC desc;
  texture->GetDesc(&desc);
  desc.MipLevels = 1;
  desc.ArraySize = 1;
  desc.SampleDesc = {1, 0};
  desc.Usage = rhi::USAGE_STAGING;
  desc.BindFlags = 0;
  desc.CPUAccessFlags = rhi::CPU_ACCESS_READ;
  desc.MiscFlags = 0;
  ComPtr<rhi::Texture2D> staging;
  if (device_->CreateTexture2D(&desc, nullptr, staging.GetAddressOf()) != rhi::S_OK)
    throw std::runtime_error("CreateTexture2D (staging) failed");
  context_->CopySubresourceRegion(staging.Get(), 0, 0, 0, 0, texture, 0, nullptr);
  rhi::MAPPED_SUBRESOURCE mapped{};
  if (context_->Map(staging.Get(), 0, rhi::MAP_READ, 0, &mapped) != rhi::S_OK)
    throw std::runtime_error("Map (staging) failed");
  const size_t row = static_cast<size_t>(desc.Width) * bytesPerPixel;
  std::vector<uint8_t> bytes(row * desc.Height);
  for (UINT y = 0; y < desc.Height; ++y)
    std::memcpy(bytes.data() + y * row, static_cast<const uint8_t*>(mapped.pData) + y * size_t(mapped.RowPitch), row);
  context_->Unmap(staging.Get(), 0);
  return bytes;
}

}  // namespace conf
