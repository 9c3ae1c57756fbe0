// Stream-output declaration strings of ConstructGSWithSO, in FX11's grammar.
//
// A declaration is a list of entries separated by ';' (empty entries are
// ignored):
//     [slot :] SEMANTIC[index][.mask]
//     [slot :] $SKIP[.mask]
// slot is the output buffer (0-3, default 0); index is the trailing digits of
// the semantic (TEXCOORD1 -> TEXCOORD, 1); mask is a contiguous run of xyzw or
// rgba (".yz": StartComponent 1, ComponentCount 2) and defaults to all four
// components. $SKIP writes a gap of mask-length components (FX11 has no
// numeric form such as "$SKIP.3"). Spaces around the parts are allowed.
// fx_5_0 declares up to four streams, one string each.
#pragma once

#include <array>
#include <memory>
#include <string>
#include <variant>
#include <vector>

#include "rhi/d3d11_types.h"

namespace fx {

struct SoDeclError {
  rhi::UINT stream = 0;  // which declaration string
  size_t offset = 0;     // character offset in that string
  std::string message;
};

class StreamOutputDecl {
 public:
  // streams[i] declares stream i; at most SO_STREAM_COUNT strings, empty ones declare nothing.
  static std::variant<StreamOutputDecl, SoDeclError> Parse(const std::vector<std::string>& streams);

  // Ready for CreateGeometryShaderWithStreamOutput. SemanticName points into
  // storage this object shares with its copies; it is nullptr for a $SKIP gap.
  const std::vector<rhi::SO_DECLARATION_ENTRY>& Entries() const { return entries_; }

  // Bytes per vertex each output slot receives (what FX11 uses as buffer strides).
  std::array<rhi::UINT, rhi::SO_BUFFER_SLOT_COUNT> Strides() const;

  bool Empty() const { return entries_.empty(); }

 private:
  // Immutable once built, so the c_str() pointers in entries_ stay valid for
  // every copy that shares it.
  std::shared_ptr<const std::vector<std::string>> names_;
  std::vector<rhi::SO_DECLARATION_ENTRY> entries_;
};

}  // namespace fx
