// DDS parsing: the legacy header and the DX10 extension, checked against the file size
// and D3D11's limits before any texel is addressed.
#include <algorithm>
#include <bit>
#include <cstdio>
#include <cstring>
#include <string>

#include "rhi/format_info.h"
#include "rhi/texture_files.h"

namespace rhi {
namespace {

constexpr uint32_t FourCC(char a, char b, char c, char d) {
  return uint32_t(uint8_t(a)) | uint32_t(uint8_t(b)) << 8 | uint32_t(uint8_t(c)) << 16 | uint32_t(uint8_t(d)) << 24;
}

constexpr uint32_t kMagic = FourCC('D', 'D', 'S', ' ');

// DDS_PIXELFORMAT.dwFlags
constexpr uint32_t DDPF_ALPHA = 0x2, DDPF_FOURCC = 0x4, DDPF_RGB = 0x40, DDPF_LUMINANCE = 0x20000,
                   DDPF_BUMPDUDV = 0x80000;
// DDS_HEADER.dwFlags, dwCaps2
constexpr uint32_t DDSD_DEPTH = 0x800000;
constexpr uint32_t DDSCAPS2_CUBEMAP = 0x200, DDSCAPS2_CUBEMAP_ALLFACES = 0xFC00, DDSCAPS2_VOLUME = 0x200000;
// DDS_HEADER_DXT10.miscFlag, miscFlags2
constexpr uint32_t DDS_RESOURCE_MISC_TEXTURECUBE = 0x4, DDS_MISC_FLAGS2_ALPHA_MODE_MASK = 0x7;

struct PixelFormat {
  uint32_t size, flags, fourCC, rgbBitCount, rMask, gMask, bMask, aMask;
};
struct Header {
  uint32_t size, flags, height, width, pitchOrLinearSize, depth, mipMapCount, reserved1[11];
  PixelFormat pixelFormat;
  uint32_t caps, caps2, caps3, caps4, reserved2;
};
struct HeaderDx10 {
  uint32_t dxgiFormat, resourceDimension, miscFlag, arraySize, miscFlags2;
};
static_assert(sizeof(Header) == 124 && sizeof(PixelFormat) == 32 && sizeof(HeaderDx10) == 20);

std::string FourCCText(uint32_t code) {
  std::string text;
  for (int i = 0; i < 4; ++i) {
    const char c = char(code >> (8 * i));
    text += (c >= 32 && c < 127) ? std::string(1, c) : "\\x" + std::to_string(uint8_t(c));
  }
  return "'" + text + "'";
}

std::string Hex(uint32_t value) {
  char text[16];
  std::snprintf(text, sizeof text, "0x%X", value);
  return text;
}

bool Masks(const PixelFormat& f, uint32_t r, uint32_t g, uint32_t b, uint32_t a) {
  return f.rMask == r && f.gMask == g && f.bMask == b && f.aMask == a;
}

// The DXGI format of a legacy pixel format (DirectXTK's GetDXGIFormat, restricted to the
// formats the RHI declares); UNKNOWN with *why set otherwise.
DXGI_FORMAT LegacyFormat(const PixelFormat& f, DDS_ALPHA_MODE* alphaMode, std::string* why) {
  if (f.flags & DDPF_FOURCC) {
    switch (f.fourCC) {
      case FourCC('D', 'X', 'T', '1'): return DXGI_FORMAT_BC1_UNORM;
      case FourCC('D', 'X', 'T', '2'): *alphaMode = DDS_ALPHA_MODE_PREMULTIPLIED; return DXGI_FORMAT_BC2_UNORM;
      case FourCC('D', 'X', 'T', '3'): return DXGI_FORMAT_BC2_UNORM;
      case FourCC('D', 'X', 'T', '4'): *alphaMode = DDS_ALPHA_MODE_PREMULTIPLIED; return DXGI_FORMAT_BC3_UNORM;
      case FourCC('D', 'X', 'T', '5'): return DXGI_FORMAT_BC3_UNORM;
      case FourCC('A', 'T', 'I', '1'):
      case FourCC('B', 'C', '4', 'U'): return DXGI_FORMAT_BC4_UNORM;
      case FourCC('B', 'C', '4', 'S'): return DXGI_FORMAT_BC4_SNORM;
      case FourCC('A', 'T', 'I', '2'):
      case FourCC('B', 'C', '5', 'U'): return DXGI_FORMAT_BC5_UNORM;
      case FourCC('B', 'C', '5', 'S'): return DXGI_FORMAT_BC5_SNORM;
      // D3DFORMAT numbers stored as the FourCC.
      case 36: return DXGI_FORMAT_R16G16B16A16_UNORM;
      case 110: return DXGI_FORMAT_R16G16B16A16_SNORM;
      case 111: return DXGI_FORMAT_R16_FLOAT;
      case 112: return DXGI_FORMAT_R16G16_FLOAT;
      case 113: return DXGI_FORMAT_R16G16B16A16_FLOAT;
      case 114: return DXGI_FORMAT_R32_FLOAT;
      case 115: return DXGI_FORMAT_R32G32_FLOAT;
      case 116: return DXGI_FORMAT_R32G32B32A32_FLOAT;
    }
    *why = "the legacy FourCC " + FourCCText(f.fourCC) + " (" + std::to_string(f.fourCC) + ") is not supported";
    return DXGI_FORMAT_UNKNOWN;
  }
  if (f.flags & DDPF_RGB) {
    if (f.rgbBitCount == 32) {
      if (Masks(f, 0xff, 0xff00, 0xff0000, 0xff000000)) return DXGI_FORMAT_R8G8B8A8_UNORM;
      if (Masks(f, 0xff0000, 0xff00, 0xff, 0xff000000)) return DXGI_FORMAT_B8G8R8A8_UNORM;
      if (Masks(f, 0xff0000, 0xff00, 0xff, 0)) return DXGI_FORMAT_B8G8R8X8_UNORM;
      if (Masks(f, 0x3ff, 0xffc00, 0x3ff00000, 0xc0000000)) return DXGI_FORMAT_R10G10B10A2_UNORM;
      if (Masks(f, 0xffff, 0xffff0000, 0, 0)) return DXGI_FORMAT_R16G16_UNORM;
      if (Masks(f, 0xffffffff, 0, 0, 0)) return DXGI_FORMAT_R32_FLOAT;  // D3DX writes R32F this way
    }
  } else if (f.flags & DDPF_LUMINANCE) {
    if (f.rgbBitCount == 8 && Masks(f, 0xff, 0, 0, 0)) return DXGI_FORMAT_R8_UNORM;
    if (f.rgbBitCount == 16 && Masks(f, 0xffff, 0, 0, 0)) return DXGI_FORMAT_R16_UNORM;
    if (f.rgbBitCount == 16 && Masks(f, 0xff, 0, 0, 0xff00)) return DXGI_FORMAT_R8G8_UNORM;
  } else if (f.flags & DDPF_ALPHA) {
    if (f.rgbBitCount == 8) return DXGI_FORMAT_A8_UNORM;
  } else if (f.flags & DDPF_BUMPDUDV) {
    if (f.rgbBitCount == 16 && Masks(f, 0xff, 0xff00, 0, 0)) return DXGI_FORMAT_R8G8_SNORM;
    if (f.rgbBitCount == 32 && Masks(f, 0xff, 0xff00, 0xff0000, 0xff000000)) return DXGI_FORMAT_R8G8B8A8_SNORM;
    if (f.rgbBitCount == 32 && Masks(f, 0xffff, 0xffff0000, 0, 0)) return DXGI_FORMAT_R16G16_SNORM;
  }
  *why = "the legacy pixel format (flags " + Hex(f.flags) + ", " + std::to_string(f.rgbBitCount) + " bits, masks " +
         Hex(f.rMask) + " " + Hex(f.gMask) + " " + Hex(f.bMask) + " " + Hex(f.aMask) + ") is not supported";
  return DXGI_FORMAT_UNKNOWN;
}

// D3D11's resource limits (D3D11_REQ_TEXTURE*).
constexpr UINT kMax1D = 16384, kMax2D = 16384, kMax3D = 2048, kMaxCube = 16384, kMaxArray = 2048;

class Parser {
 public:
  Parser(const uint8_t* data, size_t size, const char* name) : data_(data), size_(size), name_(name ? name : "<memory>") {}

  HRESULT Parse(DDS_TEXTURE* out, std::string* error) {
    std::string problem = ParseHeader(out);
    if (problem.empty()) problem = Subresources(out);
    if (problem.empty()) return S_OK;
    if (error) *error = name_ + ": " + problem;
    return E_FAIL;
  }

 private:
  std::string ParseHeader(DDS_TEXTURE* t) {
    if (size_ < 4) return "not a DDS file: " + std::to_string(size_) + " bytes, too short for the magic 'DDS '";
    uint32_t magic;
    std::memcpy(&magic, data_, 4);
    if (magic != kMagic) return "not a DDS file: the magic is " + FourCCText(magic) + ", not 'DDS '";
    if (size_ < 4 + sizeof(Header))
      return "truncated: " + std::to_string(size_) + " bytes, the header needs " + std::to_string(4 + sizeof(Header));
    Header h;
    std::memcpy(&h, data_ + 4, sizeof h);
    offset_ = 4 + sizeof h;
    if (h.size != sizeof(Header)) return "the header size is " + std::to_string(h.size) + ", not 124";
    if (h.pixelFormat.size != sizeof(PixelFormat))
      return "the pixel-format size is " + std::to_string(h.pixelFormat.size) + ", not 32";
    t->Width = h.width;
    t->Height = h.height;
    t->Depth = (h.flags & DDSD_DEPTH) ? h.depth : 1;
    t->MipLevels = std::max(1u, h.mipMapCount);
    t->ArraySize = 1;
    if ((h.pixelFormat.flags & DDPF_FOURCC) && h.pixelFormat.fourCC == FourCC('D', 'X', '1', '0')) {
      if (std::string problem = ParseDx10(t); !problem.empty()) return problem;
    } else {
      std::string why;
      t->Format = LegacyFormat(h.pixelFormat, &t->AlphaMode, &why);
      if (t->Format == DXGI_FORMAT_UNKNOWN) return why;
      if (h.caps2 & DDSCAPS2_VOLUME) {
        t->Dimension = RESOURCE_DIMENSION_TEXTURE3D;
      } else if (h.caps2 & DDSCAPS2_CUBEMAP) {
        if ((h.caps2 & DDSCAPS2_CUBEMAP_ALLFACES) != DDSCAPS2_CUBEMAP_ALLFACES)
          return "a cube map with only some faces (caps2 " + Hex(h.caps2) + "); D3D11 needs all six";
        t->Dimension = RESOURCE_DIMENSION_TEXTURE2D;
        t->IsCubeMap = true;
      } else {
        t->Dimension = RESOURCE_DIMENSION_TEXTURE2D;
      }
    }
    return CheckLimits(*t);
  }

  std::string ParseDx10(DDS_TEXTURE* t) {
    if (size_ < offset_ + sizeof(HeaderDx10))
      return "truncated: " + std::to_string(size_) + " bytes, the DX10 header needs " +
             std::to_string(offset_ + sizeof(HeaderDx10));
    HeaderDx10 x;
    std::memcpy(&x, data_ + offset_, sizeof x);
    offset_ += sizeof x;
    t->Format = static_cast<DXGI_FORMAT>(x.dxgiFormat);
    if (BitsPerPixel(t->Format) == 0)
      return "DXGI_FORMAT " + std::to_string(x.dxgiFormat) + " is not supported (not a format the RHI declares)";
    t->ArraySize = x.arraySize;
    if (t->ArraySize == 0) return "the DX10 header's array size is 0";
    t->AlphaMode = static_cast<DDS_ALPHA_MODE>(x.miscFlags2 & DDS_MISC_FLAGS2_ALPHA_MODE_MASK);
    switch (x.resourceDimension) {
      case RESOURCE_DIMENSION_TEXTURE1D:
        if (t->Height != 1 || t->Depth != 1) return "a 1D texture with height " + std::to_string(t->Height);
        break;
      case RESOURCE_DIMENSION_TEXTURE2D: t->IsCubeMap = (x.miscFlag & DDS_RESOURCE_MISC_TEXTURECUBE) != 0; break;
      case RESOURCE_DIMENSION_TEXTURE3D:
        if (t->ArraySize != 1) return "a 3D texture with array size " + std::to_string(t->ArraySize);
        break;
      default: return "the DX10 header's resource dimension " + std::to_string(x.resourceDimension) + " is not 2, 3 or 4";
    }
    t->Dimension = static_cast<RESOURCE_DIMENSION>(x.resourceDimension);
    if (t->Dimension != RESOURCE_DIMENSION_TEXTURE3D) t->Depth = 1;
    return {};
  }

  static std::string CheckLimits(const DDS_TEXTURE& t) {
    const std::string size = std::to_string(t.Width) + "x" + std::to_string(t.Height) +
                             (t.Dimension == RESOURCE_DIMENSION_TEXTURE3D ? "x" + std::to_string(t.Depth) : "");
    UINT maxSize = kMax2D;
    if (t.Dimension == RESOURCE_DIMENSION_TEXTURE1D) maxSize = kMax1D;
    if (t.Dimension == RESOURCE_DIMENSION_TEXTURE3D) maxSize = kMax3D;
    if (t.IsCubeMap) maxSize = kMaxCube;
    if (t.Width == 0 || t.Height == 0 || t.Depth == 0) return "an empty texture (" + size + ")";
    if (t.Width > maxSize || t.Height > maxSize || t.Depth > maxSize)
      return "size " + size + " exceeds D3D11's limit of " + std::to_string(maxSize);
    const UINT faces = t.IsCubeMap ? 6 : 1;
    if (t.ArraySize > kMaxArray / faces)
      return "array size " + std::to_string(t.ArraySize) + (t.IsCubeMap ? " cubes" : "") + " exceeds D3D11's limit of " +
             std::to_string(kMaxArray) + " slices";
    if (t.IsCubeMap && t.Width != t.Height) return "a cube map of non-square faces (" + size + ")";
    const UINT fullChain = std::bit_width(std::max({t.Width, t.Height, t.Depth}));
    if (t.MipLevels > fullChain)
      return std::to_string(t.MipLevels) + " mip levels, more than the full chain of " + std::to_string(fullChain) +
             " for " + size;
    return {};
  }

  // One SUBRESOURCE_DATA per (slice, mip), after checking that the file holds them all.
  std::string Subresources(DDS_TEXTURE* t) {
    const UINT slices = t->ArraySize * (t->IsCubeMap ? 6 : 1);
    uint64_t offset = offset_;
    t->Subresources.clear();
    t->Subresources.reserve(size_t(slices) * t->MipLevels);
    for (UINT slice = 0; slice < slices; ++slice) {
      for (UINT mip = 0; mip < t->MipLevels; ++mip) {
        UINT64 rowPitch = 0, slicePitch = 0;
        ComputePitch(t->Format, std::max(1u, t->Width >> mip), std::max(1u, t->Height >> mip), &rowPitch, &slicePitch);
        if (slicePitch > UINT32_MAX) return "a subresource of " + std::to_string(slicePitch) + " bytes (over 4 GiB)";
        const uint64_t bytes = slicePitch * std::max(1u, t->Depth >> mip);  // < 2^32 * 2^11: no overflow
        if (offset + bytes > size_)
          return "truncated: slice " + std::to_string(slice) + " mip " + std::to_string(mip) + " needs bytes " +
                 std::to_string(offset) + ".." + std::to_string(offset + bytes) + " of a " + std::to_string(size_) +
                 "-byte file (" + std::to_string(t->Width) + "x" + std::to_string(t->Height) +
                 (t->Dimension == RESOURCE_DIMENSION_TEXTURE3D ? "x" + std::to_string(t->Depth) : "") + ", " +
                 std::to_string(t->MipLevels) + " mip levels, " + std::to_string(slices) + " slices)";
        t->Subresources.push_back({data_ + offset, UINT(rowPitch), UINT(slicePitch)});
        offset += bytes;
      }
    }
    return {};
  }

  const uint8_t* data_;
  size_t size_;
  std::string name_;
  size_t offset_ = 0;
};

}  // namespace

HRESULT ParseDDS(const uint8_t* data, size_t size, const char* name, DDS_TEXTURE* texture, std::string* error) {
  if (!texture || (!data && size)) return E_INVALIDARG;
  *texture = DDS_TEXTURE{};
  return Parser(data, size, name).Parse(texture, error);
}

}  // namespace rhi
