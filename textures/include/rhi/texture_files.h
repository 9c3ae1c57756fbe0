// Texture files into RHI textures, in the shape of DirectXTK's DDSTextureLoader and
// WICTextureLoader (DirectX::CreateDDSTextureFromFile -> rhi::CreateDDSTextureFromFile,
// DirectX::CreateWICTextureFromFile -> rhi::CreateWICTextureFromFile): each returns the
// resource and a shader-resource view of all of it. Built on the public RHI API only
// (library texture_files, in the package's d3d11_on_vulkan::d3d11_on_vulkan target).
//
// DDS: the legacy header (DXT1-5, ATI1/ATI2/BC4U/BC4S/BC5U/BC5S, the D3DFMT numbers of
// float formats, RGB/luminance/alpha masks of the common 8/16/32-bit layouts) and the DX10
// extension (any DXGI_FORMAT the RHI declares, BC1-BC7 included); 1D and 2D textures,
// arrays, cube maps, cube-map arrays (a TEXTURECUBEARRAY view), volume textures (the
// legacy header's DDSCAPS2_VOLUME with its depth, or the DX10 header's TEXTURE3D
// dimension: CreateTexture3D and a TEXTURE3D view) and mip chains (a volume's depth
// halves with each level, as its width and height do).
// PNG, JPEG, TGA, BMP (through stb_image): 8-bit RGBA, UNORM or, with WIC_LOADER_FORCE_SRGB,
// _SRGB; a context argument asks for a full mip chain (as DirectXTK's autogen), computed
// on the CPU with a 2x2 box filter (in linear light for _SRGB).
//
// Differences from DirectXTK: every failure comes with a message naming the file and
// the problem ("bricks.dds: truncated: ..."), in *error when given, else on stderr;
// maxsize refuses a larger texture instead of dropping mip levels or resizing.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "rhi/rhi.h"

namespace rhi {

enum DDS_ALPHA_MODE : UINT {
  DDS_ALPHA_MODE_UNKNOWN = 0,
  DDS_ALPHA_MODE_STRAIGHT = 1,
  DDS_ALPHA_MODE_PREMULTIPLIED = 2,
  DDS_ALPHA_MODE_OPAQUE = 3,
  DDS_ALPHA_MODE_CUSTOM = 4,
};

enum DDS_LOADER_FLAGS : UINT {
  DDS_LOADER_DEFAULT = 0,
  DDS_LOADER_FORCE_SRGB = 0x1,  // load a UNORM format that has an _SRGB twin as the _SRGB one
};

enum WIC_LOADER_FLAGS : UINT {
  WIC_LOADER_DEFAULT = 0,
  WIC_LOADER_FORCE_SRGB = 0x1,  // R8G8B8A8_UNORM_SRGB instead of R8G8B8A8_UNORM
  WIC_LOADER_IGNORE_SRGB = 0x2,  // (the default here: no colour-space metadata is read)
};

// A DDS file's texture as D3D11 creates it: the desc fields and one SUBRESOURCE_DATA per
// subresource in D3D11's order (array slice or cube face major, mip level minor),
// pointing into the bytes that were parsed.
struct DDS_TEXTURE {
  RESOURCE_DIMENSION Dimension = RESOURCE_DIMENSION_UNKNOWN;
  UINT Width = 0, Height = 0, Depth = 0, MipLevels = 0, ArraySize = 0;  // ArraySize counts cubes, not faces
  DXGI_FORMAT Format = DXGI_FORMAT_UNKNOWN;
  bool IsCubeMap = false;
  DDS_ALPHA_MODE AlphaMode = DDS_ALPHA_MODE_UNKNOWN;
  std::vector<SUBRESOURCE_DATA> Subresources;
};

// Parses and checks a DDS file in memory (no device needed): S_OK, or E_FAIL with *error
// "name: problem" for a wrong magic or header size, a truncated file, sizes that
// overflow or exceed D3D11's limits, a format the RHI does not declare, and the like.
HRESULT ParseDDS(const uint8_t* data, size_t size, const char* name, DDS_TEXTURE* texture, std::string* error);

// DirectXTK's CreateDDSTextureFromMemory / CreateDDSTextureFromFile (texture or
// textureView may be null, not both). The wide-character name is UTF-8-converted
// whatever the locale (rhi::WidePathToUtf8).
HRESULT CreateDDSTextureFromMemory(Device* device, const uint8_t* ddsData, size_t ddsDataSize, Resource** texture,
                                   ShaderResourceView** textureView, size_t maxsize = 0,
                                   DDS_ALPHA_MODE* alphaMode = nullptr, std::string* error = nullptr);
HRESULT CreateDDSTextureFromFile(Device* device, const wchar_t* fileName, Resource** texture,
                                 ShaderResourceView** textureView, size_t maxsize = 0,
                                 DDS_ALPHA_MODE* alphaMode = nullptr, std::string* error = nullptr);
HRESULT CreateDDSTextureFromFile(Device* device, const std::filesystem::path& fileName, Resource** texture,
                                 ShaderResourceView** textureView, size_t maxsize = 0,
                                 DDS_ALPHA_MODE* alphaMode = nullptr, std::string* error = nullptr);
// DirectXTK's ...Ex: the texture's usage, bind, CPU-access and misc flags, and loadFlags.
HRESULT CreateDDSTextureFromFileEx(Device* device, const std::filesystem::path& fileName, size_t maxsize, USAGE usage,
                                   UINT bindFlags, UINT cpuAccessFlags, UINT miscFlags, DDS_LOADER_FLAGS loadFlags,
                                   Resource** texture, ShaderResourceView** textureView,
                                   DDS_ALPHA_MODE* alphaMode = nullptr, std::string* error = nullptr);

// An image file decoded to 8-bit RGBA rows (stb_image), for callers that want the pixels.
struct DECODED_IMAGE {
  UINT Width = 0, Height = 0;
  std::vector<uint8_t> Rgba;  // Width * 4 bytes a row
};
HRESULT DecodeImage(const uint8_t* data, size_t size, const char* name, DECODED_IMAGE* image, std::string* error);

// DirectXTK's CreateWICTextureFromMemory / CreateWICTextureFromFile: PNG, JPEG, TGA, BMP.
// With a context, a full mip chain; without, one level.
HRESULT CreateWICTextureFromMemory(Device* device, DeviceContext* context, const uint8_t* data, size_t size,
                                   Resource** texture, ShaderResourceView** textureView, size_t maxsize = 0,
                                   std::string* error = nullptr);
HRESULT CreateWICTextureFromFile(Device* device, const wchar_t* fileName, Resource** texture,
                                 ShaderResourceView** textureView, size_t maxsize = 0, std::string* error = nullptr);
HRESULT CreateWICTextureFromFile(Device* device, DeviceContext* context, const wchar_t* fileName, Resource** texture,
                                 ShaderResourceView** textureView, size_t maxsize = 0, std::string* error = nullptr);
HRESULT CreateWICTextureFromFile(Device* device, DeviceContext* context, const std::filesystem::path& fileName,
                                 Resource** texture, ShaderResourceView** textureView, size_t maxsize = 0,
                                 std::string* error = nullptr);
HRESULT CreateWICTextureFromFileEx(Device* device, DeviceContext* context, const std::filesystem::path& fileName,
                                   size_t maxsize, USAGE usage, UINT bindFlags, UINT cpuAccessFlags, UINT miscFlags,
                                   WIC_LOADER_FLAGS loadFlags, Resource** texture, ShaderResourceView** textureView,
                                   std::string* error = nullptr);

// Either loader by the file's extension (.dds: DDS, else the image decoder), for tools.
HRESULT CreateTextureFromFile(Device* device, DeviceContext* context, const std::filesystem::path& fileName,
                              WIC_LOADER_FLAGS loadFlags, Resource** texture, ShaderResourceView** textureView,
                              std::string* error = nullptr);

}  // namespace rhi
