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

HRESULT DecodeImage(const uint8_t* data, size_t size, const char* name, DECODED_IMAGE* image, std::string* error) {
  const std::string where = std::string(name ? name : "<memory>") + ": ";
  if (!image || (!data && size)) return E_INVALIDARG;
  if (size > INT_MAX) return *error = where + "larger than 2 GiB", E_FAIL;
  int width = 0, height = 0, channels = 0;
  if (!stbi_info_from_memory(data, int(size), &width, &height, &channels))
    return *error = where + "not a PNG, JPEG, TGA or BMP image (" + stbi_failure_reason() + ")", E_FAIL;
  // D3D11's 2D limit, checked before stb allocates the pixels.
  if (width > 16384 || height > 16384)
    return *error = where + "size " + std::to_string(width) + "x" + std::to_string(height) +
                    " exceeds D3D11's limit of 16384",
           E_FAIL;
  stbi_uc* pixels = stbi_load_from_memory(data, int(size), &width, &height, &channels, 4);
  if (!pixels) return *error = where + "cannot decode the image (" + stbi_failure_reason() + ")", E_FAIL;
  image->Width = UINT(width);
  image->Height = UINT(height);
  image->Rgba.assign(pixels, pixels + size_t(width) * height * 4);
  stbi_image_free(pixels);
  return S_OK;
}

}  // namespace rhi
