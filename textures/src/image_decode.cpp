// PNG / JPEG / TGA / BMP decoding through Debian's stb_image (libstb-dev).
#include <climits>

#include "rhi/texture_files.h"

#define STB_IMAGE_STATIC
#define STB_IMAGE_IMPLEMENTATION
#define STBI_ONLY_PNG
#define STBI_ONLY_JPEG
#define STBI_ONLY_TGA
#define STBI_ONLY_BMP
#define STBI_NO_STDIO
#include <stb_image.h>

namespace rhi {
namespace {

uint32_t Le(const uint8_t* p, int bytes) {
  uint32_t v = 0;
  for (int i = 0; i < bytes; ++i) v |= uint32_t(p[i]) << (8 * i);
  return v;
}

// stb_image reads zeros past the end of a TGA or BMP, so a truncated file would load as a
// partly black image (and a 17-byte TGA claiming 3340x3854 took seconds: the fuzzer's
// first finding). Their headers say how many bytes the pixels take: check it.
std::string Truncation(const uint8_t* data, size_t size, int width, int height) {
  const uint64_t pixels = uint64_t(width) * uint64_t(height);
  stbi__context context;  // stb's own format tests, in its order (each rewinds)
  stbi__start_mem(&context, data, int(size));
  if (stbi__png_test(&context) || stbi__jpeg_test(&context)) return {};
  const bool bmp = stbi__bmp_test(&context);
  if (!bmp && stbi__tga_test(&context)) {
    if (size < 18) return "truncated: " + std::to_string(size) + " bytes, a TGA header needs 18";
    const uint64_t bytesPerPixel = (data[16] + 7) / 8;
    const uint64_t colorMap = data[1] ? uint64_t(Le(data + 5, 2)) * ((data[7] + 7) / 8) : 0;
    const uint64_t header = 18 + data[0] + colorMap;
    const bool rle = data[2] >= 9;
    // An RLE packet is a byte and at least one pixel value for at most 128 pixels.
    const uint64_t needed = header + (rle ? (pixels + 127) / 128 * (1 + bytesPerPixel) : pixels * bytesPerPixel);
    if (size < needed)
      return "truncated: a " + std::to_string(width) + "x" + std::to_string(height) + (rle ? " RLE" : "") +
             " TGA needs " + (rle ? "at least " : "") + std::to_string(needed) + " bytes, the file has " +
             std::to_string(size);
  } else if (bmp && size < 34) {
    return "truncated: " + std::to_string(size) + " bytes, a BMP header needs 34";
  } else if (bmp && (Le(data + 30, 4) == 0 || Le(data + 30, 4) == 3)) {
    const uint64_t rowBytes = (uint64_t(width) * Le(data + 28, 2) + 31) / 32 * 4;
    const uint64_t needed = uint64_t(Le(data + 10, 4)) + rowBytes * uint64_t(height);
    if (size < needed)
      return "truncated: a " + std::to_string(width) + "x" + std::to_string(height) + " BMP needs " +
             std::to_string(needed) + " bytes, the file has " + std::to_string(size);
  }
  return {};
}

// Debian's stb_image (2022-09) writes past its 257-entry Huffman size list when a JPEG's
// DHT table declares more than 256 codes (the fuzzer's third finding; later stb releases
// check it). Every FF C4 (DHT) marker's tables are summed first, reading past the end as
// zeros as stb does. Bytes inside other segments that happen to read FF C4 are checked
// too; a real DHT never exceeds 256 codes, so only a corrupt-looking table is refused.
std::string JpegHuffmanOverflow(const uint8_t* data, size_t size) {
  auto at = [&](size_t i) -> uint32_t { return i < size ? data[i] : 0; };
  for (size_t marker = 0; marker + 1 < size; ++marker) {
    if (data[marker] != 0xFF || data[marker + 1] != 0xC4) continue;
    size_t pos = marker + 2;
    int64_t remaining = int64_t(at(pos) << 8 | at(pos + 1)) - 2;
    pos += 2;
    while (remaining > 0 && pos < size) {
      const uint32_t header = at(pos);
      if ((header >> 4) > 1 || (header & 15) > 3) break;  // stb stops with "bad DHT header"
      uint32_t codes = 0;
      for (int i = 0; i < 16; ++i) codes += at(pos + 1 + i);
      if (codes > 256)
        return "corrupt JPEG: a Huffman table at byte " + std::to_string(marker) + " declares " +
               std::to_string(codes) + " codes (at most 256)";
      pos += 17 + codes;
      remaining -= 17 + codes;
    }
  }
  return {};
}

}  // namespace

HRESULT DecodeImage(const uint8_t* data, size_t size, const char* name, DECODED_IMAGE* image, std::string* error) {
  const std::string where = std::string(name ? name : "<memory>") + ": ";
  if (!image || (!data && size)) return E_INVALIDARG;
  if (size > INT_MAX) return *error = where + "larger than 2 GiB", E_FAIL;
  int width = 0, height = 0, channels = 0;
  stbi__context jpeg;
  stbi__start_mem(&jpeg, data, int(size));
  if (stbi__jpeg_test(&jpeg))
    if (std::string overflow = JpegHuffmanOverflow(data, size); !overflow.empty()) return *error = where + overflow, E_FAIL;
  if (!stbi_info_from_memory(data, int(size), &width, &height, &channels))
    return *error = where + "not a PNG, JPEG, TGA or BMP image (" + stbi_failure_reason() + ")", E_FAIL;
  // stb_image accepts a BMP of height 0 (the fuzzer's second finding); a texture cannot be empty.
  if (width <= 0 || height <= 0)
    return *error = where + "an empty image (" + std::to_string(width) + "x" + std::to_string(height) + ")", E_FAIL;
  // D3D11's 2D limit, checked before stb allocates the pixels.
  if (width > 16384 || height > 16384)
    return *error = where + "size " + std::to_string(width) + "x" + std::to_string(height) +
                    " exceeds D3D11's limit of 16384",
           E_FAIL;
  if (std::string truncated = Truncation(data, size, width, height); !truncated.empty())
    return *error = where + truncated, E_FAIL;
  stbi_uc* pixels = stbi_load_from_memory(data, int(size), &width, &height, &channels, 4);
  if (!pixels) return *error = where + "cannot decode the image (" + stbi_failure_reason() + ")", E_FAIL;
  image->Width = UINT(width);
  image->Height = UINT(height);
  image->Rgba.assign(pixels, pixels + size_t(width) * height * 4);
  stbi_image_free(pixels);
  return S_OK;
}

}  // namespace rhi
