// Shared by the libFuzzer target (texture_fuzz.cpp) and the deterministic corpus replay
// (texture_corpus_replay.cpp): one input = the bytes of a texture file, given both to
// rhi::ParseDDS (the DDS loader's parsing and size checks) and to rhi::DecodeImage
// (stb_image: PNG, JPEG, TGA, BMP). No device is involved: creating the texture from a
// parsed file is the RHI's CreateTexture*, which validates its descs itself.
//
// The outcome must be "clean": a success whose subresources all lie inside the input
// with consistent pitches, or an error "fuzz.dds: <problem>" / "fuzz.img: <problem>".
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "rhi/format_info.h"
#include "rhi/texture_files.h"

namespace texfuzz {

// Larger inputs only slow the fuzzer down; the parser's limits are reached by header values.
inline constexpr size_t kMaxInputBytes = 64 * 1024;

struct Outcome {
  bool parsedDds = false;
  bool decodedImage = false;
  std::vector<std::string> problems;  // empty: clean
};

inline void CheckError(const std::string& error, const std::string& name, Outcome* o) {
  if (error.rfind(name + ": ", 0) != 0 || error.size() <= name.size() + 2)
    o->problems.push_back("an error without \"" + name + ": <problem>\": \"" + error + "\"");
}

inline void CheckDds(const uint8_t* data, size_t size, const rhi::DDS_TEXTURE& t, Outcome* o) {
  const size_t faces = t.IsCubeMap ? 6 : 1;
  if (t.Subresources.size() != size_t(t.ArraySize) * faces * t.MipLevels)
    o->problems.push_back("subresource count does not match ArraySize x faces x MipLevels");
  for (size_t i = 0; i < t.Subresources.size(); ++i) {
    const rhi::SUBRESOURCE_DATA& s = t.Subresources[i];
    const rhi::UINT mip = rhi::UINT(i % t.MipLevels);
    rhi::UINT64 rowPitch = 0, slicePitch = 0;
    rhi::ComputePitch(t.Format, std::max(1u, t.Width >> mip), std::max(1u, t.Height >> mip), &rowPitch, &slicePitch);
    const auto* begin = static_cast<const uint8_t*>(s.pSysMem);
    const size_t bytes = size_t(slicePitch) * std::max(1u, t.Depth >> mip);
    if (s.SysMemPitch != rowPitch || s.SysMemSlicePitch != slicePitch)
      o->problems.push_back("subresource " + std::to_string(i) + " has inconsistent pitches");
    if (begin < data || begin + bytes > data + size)
      o->problems.push_back("subresource " + std::to_string(i) + " lies outside the input");
  }
}

inline Outcome RunOne(const uint8_t* data, size_t size) {
  Outcome o;
  rhi::DDS_TEXTURE dds;
  std::string error;
  if (rhi::SUCCEEDED(rhi::ParseDDS(data, size, "fuzz.dds", &dds, &error))) {
    o.parsedDds = true;
    CheckDds(data, size, dds, &o);
  } else {
    CheckError(error, "fuzz.dds", &o);
  }
  rhi::DECODED_IMAGE image;
  error.clear();
  if (rhi::SUCCEEDED(rhi::DecodeImage(data, size, "fuzz.img", &image, &error))) {
    o.decodedImage = true;
    if (image.Width == 0 || image.Height == 0 || image.Rgba.size() != size_t(image.Width) * image.Height * 4)
      o.problems.push_back("a decoded image whose pixels do not match its size");
  } else {
    CheckError(error, "fuzz.img", &o);
  }
  return o;
}

}  // namespace texfuzz
