// Small helpers shared by the state modules: a field-by-field FNV-1a hasher and
// the number formatting used in validation messages.
#pragma once

#include <bit>
#include <cstdint>
#include <string>
#include <type_traits>

namespace rhi::states {

// 64-bit FNV-1a fed one field at a time. The D3D11 desc structs mix 4-byte fields
// with UINT8s (RENDER_TARGET_BLEND_DESC has 3 bytes of tail padding,
// DEPTH_STENCIL_DESC 2 in the middle), so hashing their bytes would hash padding.
class Fnv1a {
 public:
  void Add(uint8_t v) { Byte(v); }
  void Add(uint32_t v) {
    for (int i = 0; i < 4; ++i) Byte(static_cast<uint8_t>(v >> (8 * i)));
  }
  void Add(int32_t v) { Add(static_cast<uint32_t>(v)); }
  // Floats hash by bit pattern, consistent with SameBits below.
  void Add(float v) { Add(std::bit_cast<uint32_t>(v)); }
  template <class E>
    requires std::is_enum_v<E>
  void Add(E v) {
    Add(static_cast<std::underlying_type_t<E>>(v));
  }
  uint64_t value() const { return h_; }

 private:
  void Byte(uint8_t b) { h_ = (h_ ^ b) * 0x100000001b3ull; }
  uint64_t h_ = 0xcbf29ce484222325ull;
};

// Raw equality compares floats bitwise, so that it is reflexive for NaN (and
// agrees with Fnv1a::Add(float)).
inline bool SameBits(float a, float b) { return std::bit_cast<uint32_t>(a) == std::bit_cast<uint32_t>(b); }

// D3D11 BOOLs are "any non-zero value"; the canonical form uses TRUE (1).
inline int32_t CanonicalBool(int32_t b) { return b ? 1 : 0; }

// "NaN", "+INF", "-INF" or the shortest %g text of a float.
std::string FloatText(float v);
// "0x1F".
std::string HexText(uint32_t v);

}  // namespace rhi::states
