// Creating RHI textures from DDS and image files through the public API only.
#include "rhi/texture_files.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iterator>

#include "rhi/format_info.h"
#include "rhi/wide_path.h"

namespace rhi {
namespace {

HRESULT Fail(HRESULT hr, const std::string& message, std::string* error) {
  if (error) {
    *error = message;
  } else {
    std::fprintf(stderr, "%s\n", message.c_str());
  }
  return hr;
}

bool ReadFile(const std::filesystem::path& path, std::vector<uint8_t>* bytes, std::string* problem) {
  std::error_code code;
  if (std::filesystem::is_directory(path, code)) return *problem = "is a directory", false;
  std::ifstream file(path, std::ios::binary);
  if (!file) return *problem = "cannot open the file", false;
  bytes->assign(std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>());
  if (file.bad()) return *problem = "cannot read the file", false;
  return true;
}

DXGI_FORMAT SrgbTwin(DXGI_FORMAT format) {
  switch (format) {
    case DXGI_FORMAT_R8G8B8A8_UNORM: return DXGI_FORMAT_R8G8B8A8_UNORM_SRGB;
    case DXGI_FORMAT_B8G8R8A8_UNORM: return DXGI_FORMAT_B8G8R8A8_UNORM_SRGB;
    case DXGI_FORMAT_B8G8R8X8_UNORM: return DXGI_FORMAT_B8G8R8X8_UNORM_SRGB;
    case DXGI_FORMAT_BC1_UNORM: return DXGI_FORMAT_BC1_UNORM_SRGB;
    case DXGI_FORMAT_BC2_UNORM: return DXGI_FORMAT_BC2_UNORM_SRGB;
    case DXGI_FORMAT_BC3_UNORM: return DXGI_FORMAT_BC3_UNORM_SRGB;
    case DXGI_FORMAT_BC7_UNORM: return DXGI_FORMAT_BC7_UNORM_SRGB;
    default: return format;
  }
}

struct CreateFlags {
  USAGE usage = USAGE_DEFAULT;
  UINT bindFlags = BIND_SHADER_RESOURCE;
  UINT cpuAccessFlags = 0;
  UINT miscFlags = 0;
};

std::string SizeText(const DDS_TEXTURE& dds) {
  return std::to_string(dds.Width) + "x" + std::to_string(dds.Height) +
         (dds.Dimension == RESOURCE_DIMENSION_TEXTURE3D ? "x" + std::to_string(dds.Depth) : "");
}

// The texture a DDS_TEXTURE describes (1D, 2D or 3D, arrays, cubes and cube arrays;
// decoded images are described the same way) and, when asked, its whole-resource SRV (a
// TEXTURECUBEARRAY view of every cube for a cube array, a TEXTURE3D view of a volume).
HRESULT CreateTexture(Device* device, const DDS_TEXTURE& dds, const std::string& name, const CreateFlags& flags,
                      Resource** texture, ShaderResourceView** textureView, std::string* error) {
  const UINT slices = dds.ArraySize * (dds.IsCubeMap ? 6 : 1);
  ComPtr<Resource> resource;
  HRESULT hr = S_OK;
  if (dds.Dimension == RESOURCE_DIMENSION_TEXTURE3D) {
    TEXTURE3D_DESC desc{dds.Width, dds.Height, dds.Depth, dds.MipLevels, dds.Format, flags.usage, flags.bindFlags,
                        flags.cpuAccessFlags, flags.miscFlags};
    ComPtr<Texture3D> created;
    hr = device->CreateTexture3D(&desc, dds.Subresources.data(), created.GetAddressOf());
    resource.Attach(created.Detach());
  } else if (dds.Dimension == RESOURCE_DIMENSION_TEXTURE1D) {
    TEXTURE1D_DESC desc{dds.Width, dds.MipLevels, slices, dds.Format, flags.usage, flags.bindFlags,
                        flags.cpuAccessFlags, flags.miscFlags};
    ComPtr<Texture1D> created;
    hr = device->CreateTexture1D(&desc, dds.Subresources.data(), created.GetAddressOf());
    resource.Attach(created.Detach());
  } else {
    TEXTURE2D_DESC desc{dds.Width, dds.Height, dds.MipLevels, slices, dds.Format, {1, 0}, flags.usage,
                        flags.bindFlags, flags.cpuAccessFlags,
                        flags.miscFlags | (dds.IsCubeMap ? UINT(RESOURCE_MISC_TEXTURECUBE) : 0u)};
    ComPtr<Texture2D> created;
    hr = device->CreateTexture2D(&desc, dds.Subresources.data(), created.GetAddressOf());
    resource.Attach(created.Detach());
  }
  if (FAILED(hr))
    return Fail(hr, name + ": the device refused the texture (" + FormatName(dds.Format) + ", " + SizeText(dds) +
                        "; its message says why)",
                error);
  if (textureView) {
    hr = device->CreateShaderResourceView(resource.Get(), nullptr, textureView);
    if (FAILED(hr)) return Fail(hr, name + ": the device refused the shader-resource view", error);
  }
  if (texture) *texture = resource.Detach();
  return S_OK;
}

HRESULT CheckOutputs(Resource** texture, ShaderResourceView** textureView) {
  if (texture) *texture = nullptr;
  if (textureView) *textureView = nullptr;
  return (texture || textureView) ? S_OK : E_INVALIDARG;
}

std::string MaxSizeProblem(UINT width, UINT height, size_t maxsize, UINT depth = 1) {
  if (maxsize == 0 || (width <= maxsize && height <= maxsize && depth <= maxsize)) return {};
  return "size " + std::to_string(width) + "x" + std::to_string(height) +
         (depth > 1 ? "x" + std::to_string(depth) : "") + " exceeds maxsize " + std::to_string(maxsize);
}

HRESULT LoadDds(Device* device, const uint8_t* data, size_t size, const std::string& name, size_t maxsize,
                const CreateFlags& flags, DDS_LOADER_FLAGS loadFlags, Resource** texture,
                ShaderResourceView** textureView, DDS_ALPHA_MODE* alphaMode, std::string* error) {
  if (!device || FAILED(CheckOutputs(texture, textureView)))
    return Fail(E_INVALIDARG, name + ": no device, or neither a texture nor a view to return", error);
  DDS_TEXTURE dds;
  std::string problem;
  if (HRESULT hr = ParseDDS(data, size, name.c_str(), &dds, &problem); FAILED(hr)) return Fail(hr, problem, error);
  if (std::string tooLarge = MaxSizeProblem(dds.Width, dds.Height, maxsize, dds.Depth); !tooLarge.empty())
    return Fail(E_INVALIDARG, name + ": " + tooLarge, error);
  if (loadFlags & DDS_LOADER_FORCE_SRGB) dds.Format = SrgbTwin(dds.Format);
  if (alphaMode) *alphaMode = dds.AlphaMode;
  return CreateTexture(device, dds, name, flags, texture, textureView, error);
}

// sRGB <-> linear light, for filtering _SRGB mip levels as the GPU would.
float ToLinear(uint8_t v) {
  const float c = v / 255.0f;
  return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}
uint8_t FromLinear(float l) {
  const float c = l <= 0.0031308f ? l * 12.92f : 1.055f * std::pow(l, 1.0f / 2.4f) - 0.055f;
  return uint8_t(std::clamp(c, 0.0f, 1.0f) * 255.0f + 0.5f);
}

// The next mip level of an RGBA8 image: each texel the mean of its 2x2 footprint (of a
// single row or column where the level above is 1 texel thick); alpha is always linear.
std::vector<uint8_t> HalfSize(const std::vector<uint8_t>& rgba, UINT width, UINT height, bool srgb) {
  const UINT w = std::max(1u, width / 2), h = std::max(1u, height / 2);
  std::vector<uint8_t> out(size_t(w) * h * 4);
  for (UINT y = 0; y < h; ++y)
    for (UINT x = 0; x < w; ++x)
      for (UINT c = 0; c < 4; ++c) {
        const bool linear = srgb && c < 3;
        float sum = 0;
        UINT count = 0;
        for (UINT dy = 0; dy < (height > 1 ? 2u : 1u); ++dy)
          for (UINT dx = 0; dx < (width > 1 ? 2u : 1u); ++dx) {
            const uint8_t v = rgba[((size_t(std::min(2 * y + dy, height - 1)) * width) + std::min(2 * x + dx, width - 1)) * 4 + c];
            sum += linear ? ToLinear(v) : v / 255.0f;
            ++count;
          }
        const float mean = sum / count;
        out[(size_t(y) * w + x) * 4 + c] = linear ? FromLinear(mean) : uint8_t(mean * 255.0f + 0.5f);
      }
  return out;
}

HRESULT LoadImage(Device* device, DeviceContext* context, const uint8_t* data, size_t size, const std::string& name,
                  size_t maxsize, const CreateFlags& flags, WIC_LOADER_FLAGS loadFlags, Resource** texture,
                  ShaderResourceView** textureView, std::string* error) {
  if (!device || FAILED(CheckOutputs(texture, textureView)))
    return Fail(E_INVALIDARG, name + ": no device, or neither a texture nor a view to return", error);
  DECODED_IMAGE image;
  std::string problem;
  if (HRESULT hr = DecodeImage(data, size, name.c_str(), &image, &problem); FAILED(hr)) return Fail(hr, problem, error);
  if (std::string tooLarge = MaxSizeProblem(image.Width, image.Height, maxsize); !tooLarge.empty())
    return Fail(E_INVALIDARG, name + ": " + tooLarge, error);
  const bool srgb = (loadFlags & WIC_LOADER_FORCE_SRGB) != 0;
  // DirectXTK generates mips when given a context; here the chain is filtered on the CPU.
  std::vector<std::vector<uint8_t>> levels{std::move(image.Rgba)};
  UINT width = image.Width, height = image.Height;
  while (context && (width > 1 || height > 1)) {
    levels.push_back(HalfSize(levels.back(), width, height, srgb));
    width = std::max(1u, width / 2);
    height = std::max(1u, height / 2);
  }
  DDS_TEXTURE texture2d;
  texture2d.Dimension = RESOURCE_DIMENSION_TEXTURE2D;
  texture2d.Width = image.Width;
  texture2d.Height = image.Height;
  texture2d.Depth = texture2d.ArraySize = 1;
  texture2d.MipLevels = UINT(levels.size());
  texture2d.Format = srgb ? DXGI_FORMAT_R8G8B8A8_UNORM_SRGB : DXGI_FORMAT_R8G8B8A8_UNORM;
  for (size_t mip = 0; mip < levels.size(); ++mip) {
    const UINT rowPitch = std::max(1u, image.Width >> mip) * 4;
    texture2d.Subresources.push_back({levels[mip].data(), rowPitch, UINT(levels[mip].size())});
  }
  return CreateTexture(device, texture2d, name, flags, texture, textureView, error);
}

std::string NameOf(const std::filesystem::path& path) { return path.string(); }

}  // namespace

HRESULT CreateDDSTextureFromMemory(Device* device, const uint8_t* ddsData, size_t ddsDataSize, Resource** texture,
                                   ShaderResourceView** textureView, size_t maxsize, DDS_ALPHA_MODE* alphaMode,
                                   std::string* error) {
  return LoadDds(device, ddsData, ddsDataSize, "<memory>", maxsize, {}, DDS_LOADER_DEFAULT, texture, textureView,
                 alphaMode, error);
}

HRESULT CreateDDSTextureFromFileEx(Device* device, const std::filesystem::path& fileName, size_t maxsize, USAGE usage,
                                   UINT bindFlags, UINT cpuAccessFlags, UINT miscFlags, DDS_LOADER_FLAGS loadFlags,
                                   Resource** texture, ShaderResourceView** textureView, DDS_ALPHA_MODE* alphaMode,
                                   std::string* error) {
  std::vector<uint8_t> bytes;
  std::string problem;
  if (!ReadFile(fileName, &bytes, &problem)) return Fail(E_FAIL, NameOf(fileName) + ": " + problem, error);
  return LoadDds(device, bytes.data(), bytes.size(), NameOf(fileName), maxsize,
                 {usage, bindFlags, cpuAccessFlags, miscFlags}, loadFlags, texture, textureView, alphaMode, error);
}

HRESULT CreateDDSTextureFromFile(Device* device, const std::filesystem::path& fileName, Resource** texture,
                                 ShaderResourceView** textureView, size_t maxsize, DDS_ALPHA_MODE* alphaMode,
                                 std::string* error) {
  return CreateDDSTextureFromFileEx(device, fileName, maxsize, USAGE_DEFAULT, BIND_SHADER_RESOURCE, 0, 0,
                                    DDS_LOADER_DEFAULT, texture, textureView, alphaMode, error);
}

HRESULT CreateDDSTextureFromFile(Device* device, const wchar_t* fileName, Resource** texture,
                                 ShaderResourceView** textureView, size_t maxsize, DDS_ALPHA_MODE* alphaMode,
                                 std::string* error) {
  if (!fileName) return E_INVALIDARG;
  return CreateDDSTextureFromFile(device, std::filesystem::path(WidePathToUtf8(fileName)), texture, textureView,
                                  maxsize, alphaMode, error);
}

HRESULT CreateWICTextureFromMemory(Device* device, DeviceContext* context, const uint8_t* data, size_t size,
                                   Resource** texture, ShaderResourceView** textureView, size_t maxsize,
                                   std::string* error) {
  return LoadImage(device, context, data, size, "<memory>", maxsize, {}, WIC_LOADER_DEFAULT, texture, textureView,
                   error);
}

HRESULT CreateWICTextureFromFileEx(Device* device, DeviceContext* context, const std::filesystem::path& fileName,
                                   size_t maxsize, USAGE usage, UINT bindFlags, UINT cpuAccessFlags, UINT miscFlags,
                                   WIC_LOADER_FLAGS loadFlags, Resource** texture, ShaderResourceView** textureView,
                                   std::string* error) {
  std::vector<uint8_t> bytes;
  std::string problem;
  if (!ReadFile(fileName, &bytes, &problem)) return Fail(E_FAIL, NameOf(fileName) + ": " + problem, error);
  return LoadImage(device, context, bytes.data(), bytes.size(), NameOf(fileName), maxsize,
                   {usage, bindFlags, cpuAccessFlags, miscFlags}, loadFlags, texture, textureView, error);
}

HRESULT CreateWICTextureFromFile(Device* device, DeviceContext* context, const std::filesystem::path& fileName,
                                 Resource** texture, ShaderResourceView** textureView, size_t maxsize,
                                 std::string* error) {
  return CreateWICTextureFromFileEx(device, context, fileName, maxsize, USAGE_DEFAULT, BIND_SHADER_RESOURCE, 0, 0,
                                    WIC_LOADER_DEFAULT, texture, textureView, error);
}

HRESULT CreateWICTextureFromFile(Device* device, DeviceContext* context, const wchar_t* fileName, Resource** texture,
                                 ShaderResourceView** textureView, size_t maxsize, std::string* error) {
  if (!fileName) return E_INVALIDARG;
  return CreateWICTextureFromFile(device, context, std::filesystem::path(WidePathToUtf8(fileName)), texture,
                                  textureView, maxsize, error);
}

HRESULT CreateWICTextureFromFile(Device* device, const wchar_t* fileName, Resource** texture,
                                 ShaderResourceView** textureView, size_t maxsize, std::string* error) {
  return CreateWICTextureFromFile(device, nullptr, fileName, texture, textureView, maxsize, error);
}

HRESULT CreateTextureFromFile(Device* device, DeviceContext* context, const std::filesystem::path& fileName,
                              WIC_LOADER_FLAGS loadFlags, Resource** texture, ShaderResourceView** textureView,
                              std::string* error) {
  std::string extension = fileName.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(), [](unsigned char c) { return std::tolower(c); });
  if (extension == ".dds")
    return CreateDDSTextureFromFileEx(device, fileName, 0, USAGE_DEFAULT, BIND_SHADER_RESOURCE, 0, 0,
                                      (loadFlags & WIC_LOADER_FORCE_SRGB) ? DDS_LOADER_FORCE_SRGB : DDS_LOADER_DEFAULT,
                                      texture, textureView, nullptr, error);
  return CreateWICTextureFromFileEx(device, context, fileName, 0, USAGE_DEFAULT, BIND_SHADER_RESOURCE, 0, 0, loadFlags,
                                    texture, textureView, error);
}

}  // namespace rhi
