#include "shader_cache.h"

#include <glslang/build_info.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>

namespace fx::detail {
namespace {

// Bump when the file format or anything the runtime does to the source before
// compiling or the reflection it stores changes (e.g. the geometry-shader isolation;
// 3: the members of a cbuffer that shares its binding with an unused one).
constexpr char kFormat[] = "fxrt-spirv-cache-3";
#define FXRT_STR2(x) #x
#define FXRT_STR(x) FXRT_STR2(x)
constexpr char kCompilerVersion[] = "glslang " FXRT_STR(GLSLANG_VERSION_MAJOR) "." FXRT_STR(
    GLSLANG_VERSION_MINOR) "." FXRT_STR(GLSLANG_VERSION_PATCH) GLSLANG_VERSION_FLAVOR;

uint64_t Fnv1a(const std::string& s, uint64_t seed) {
  uint64_t h = seed;
  for (unsigned char c : s) {
    h ^= c;
    h *= 0x100000001b3ull;
  }
  // Final avalanche (splitmix64), so both halves of the key differ everywhere.
  h ^= h >> 30, h *= 0xbf58476d1ce4e5b9ull, h ^= h >> 27, h *= 0x94d049bb133111ebull, h ^= h >> 31;
  return h;
}

// Little binary writer/reader for the cache files.
struct Writer {
  std::string bytes;
  void U32(uint32_t v) { bytes.append(reinterpret_cast<const char*>(&v), 4); }
  void Str(const std::string& s) {
    U32(static_cast<uint32_t>(s.size()));
    bytes += s;
  }
};

struct Reader {
  const std::string& bytes;
  size_t at = 0;
  bool ok = true;
  uint32_t U32() {
    uint32_t v = 0;
    if (at + 4 > bytes.size()) return ok = false, 0;
    std::memcpy(&v, bytes.data() + at, 4);
    at += 4;
    return v;
  }
  std::string Str() {
    uint32_t n = U32();
    if (!ok || at + n > bytes.size()) return ok = false, std::string();
    std::string s = bytes.substr(at, n);
    at += n;
    return s;
  }
  // A count that cannot exceed what is left (corrupt files must not allocate gigabytes).
  uint32_t Count() {
    uint32_t n = U32();
    if (n > bytes.size() - at) ok = false;
    return ok ? n : 0;
  }
};

void WriteCode(Writer& w, const CompiledCode& code) {
  w.Str(kFormat);
  w.U32(static_cast<uint32_t>(code.spirv.size()));
  for (uint32_t word : code.spirv) w.U32(word);
  w.U32(static_cast<uint32_t>(code.constantBuffers.size()));
  for (const auto& cb : code.constantBuffers) {
    w.Str(cb.name), w.U32(cb.binding), w.U32(cb.registerSlot), w.U32(cb.size);
    w.U32(static_cast<uint32_t>(cb.members.size()));
    for (const auto& m : cb.members) {
      w.Str(m.name), w.U32(m.offset), w.U32(m.size), w.U32(static_cast<uint32_t>(m.baseType));
      w.U32(m.rows), w.U32(m.columns), w.U32(m.arrayElements);
    }
  }
  w.U32(static_cast<uint32_t>(code.resources.size()));
  for (const auto& r : code.resources) {
    w.Str(r.name), w.U32(r.binding), w.U32(r.registerSlot), w.U32(static_cast<uint32_t>(r.kind));
    w.U32(static_cast<uint32_t>(r.dimension)), w.U32(r.bindCount), w.U32(r.comparisonSampler), w.U32(r.isCounter);
  }
}

std::optional<CompiledCode> ReadCode(Reader& r) {
  if (r.Str() != kFormat) return std::nullopt;
  CompiledCode code;
  code.spirv.resize(r.Count());
  for (uint32_t& word : code.spirv) word = r.U32();
  code.constantBuffers.resize(r.Count());
  for (auto& cb : code.constantBuffers) {
    cb.name = r.Str(), cb.binding = r.U32(), cb.registerSlot = r.U32(), cb.size = r.U32();
    cb.members.resize(r.Count());
    for (auto& m : cb.members) {
      m.name = r.Str(), m.offset = r.U32(), m.size = r.U32(), m.baseType = static_cast<hlsl::BaseType>(r.U32());
      m.rows = r.U32(), m.columns = r.U32(), m.arrayElements = r.U32();
    }
  }
  code.resources.resize(r.Count());
  for (auto& res : code.resources) {
    res.name = r.Str(), res.binding = r.U32(), res.registerSlot = r.U32();
    res.kind = static_cast<hlsl::ResourceInfo::Kind>(r.U32());
    res.dimension = static_cast<hlsl::ResourceInfo::Dimension>(r.U32());
    res.bindCount = r.U32(), res.comparisonSampler = r.U32() != 0, res.isCounter = r.U32() != 0;
  }
  if (!r.ok || r.at != r.bytes.size() || code.spirv.empty()) return std::nullopt;
  return code;
}

}  // namespace

std::string ShaderCacheKey(const std::string& hlsl, const std::string& entryPoint, const std::string& profile,
                           const std::vector<hlsl::Define>& defines) {
  std::string all = hlsl;
  for (const std::string& part : {entryPoint, profile, std::string(kCompilerVersion), std::string(kFormat)})
    all += '\0' + part;
  for (const hlsl::Define& d : defines) all += '\0' + d.name + '=' + d.value;
  char hex[33];
  std::snprintf(hex, sizeof hex, "%016llx%016llx", static_cast<unsigned long long>(Fnv1a(all, 0xcbf29ce484222325ull)),
                static_cast<unsigned long long>(Fnv1a(all, 0x84222325cbf29ce4ull)));
  return hex;
}

std::string ShaderCache::DefaultDirectory() {
  if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg) return std::string(xdg) + "/d3d11-on-vulkan/spirv";
  if (const char* home = std::getenv("HOME"); home && *home) return std::string(home) + "/.cache/d3d11-on-vulkan/spirv";
  return "";
}

std::optional<CompiledCode> ShaderCache::Load(const std::string& key) const {
  if (directory_.empty()) return std::nullopt;
  std::ifstream file(PathOf(key), std::ios::binary);
  if (!file) return std::nullopt;
  std::string bytes((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
  Reader reader{bytes};
  return ReadCode(reader);
}

void ShaderCache::Store(const std::string& key, const CompiledCode& code) const {
  if (directory_.empty()) return;
  std::error_code ec;
  std::filesystem::create_directories(directory_, ec);
  Writer w;
  WriteCode(w, code);
  // Write a private file and rename it, so concurrent loaders never read half a file.
  const std::string tmp = PathOf(key) + ".tmp" + std::to_string(::getpid());
  {
    std::ofstream file(tmp, std::ios::binary | std::ios::trunc);
    if (!file) return;
    file.write(w.bytes.data(), static_cast<std::streamsize>(w.bytes.size()));
    if (!file) return;
  }
  std::filesystem::rename(tmp, PathOf(key), ec);
  if (ec) std::filesystem::remove(tmp, ec);
}

}  // namespace fx::detail
