// The on-disk cache of compiled shaders: SPIR-V plus the reflection the
// runtime binds by, so that loading an effect a second time runs no glslang.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "hlsl/hlsl_compiler.h"

namespace fx::detail {

struct CompiledCode {
  std::vector<uint32_t> spirv;
  std::vector<hlsl::ConstantBufferInfo> constantBuffers;
  std::vector<hlsl::ResourceInfo> resources;
};

// 32 hex digits naming everything that decides the compiler's output: the
// exact source text, entry point, profile, defines and the compiler version.
std::string ShaderCacheKey(const std::string& hlsl, const std::string& entryPoint, const std::string& profile,
                           const std::vector<hlsl::Define>& defines);

class ShaderCache {
 public:
  // `directory` empty: a cache that never hits and stores nothing.
  explicit ShaderCache(std::string directory) : directory_(std::move(directory)) {}
  // $XDG_CACHE_HOME/d3d11-on-vulkan/spirv, ~/.cache/d3d11-on-vulkan/spirv, or "".
  static std::string DefaultDirectory();

  std::optional<CompiledCode> Load(const std::string& key) const;
  // Best effort: a cache that cannot be written only costs the next load time.
  void Store(const std::string& key, const CompiledCode& code) const;

 private:
  std::string PathOf(const std::string& key) const { return directory_ + "/" + key + ".spv"; }
  std::string directory_;
};

}  // namespace fx::detail
