// Colored blended OIT (document 000, Tables 3 and 4; shaders_hlsl/oit/colored.fxh):
// WBOIT whose accumulation pass also multiplies the frame by each surface's
// transmission. Composed with Table 4 corrected, or as printed
// (oit/colored_literal.fxh; docs/blend_tables.md says why it is wrong).
#include "oit/weighted_blended.h"

namespace renderer::oit {
namespace {

std::unique_ptr<Method> CreateColored(const MethodInfo& info, const MethodSetup& setup, std::string* error) {
  return CreateWeightedBlended(info, setup, true, error);
}

}  // namespace

extern const MethodInfo kColored{"colored", "oit/colored.fxh", 0, DrawOrder::AsSubmitted,
                                 "colored blended OIT, Tables 3 + 4 corrected (document 000)", CreateColored};
extern const MethodInfo kColoredLiteral{"colored-literal", "oit/colored_literal.fxh", 0, DrawOrder::AsSubmitted,
                                        "colored blended OIT, Table 4 as printed (adds C * revealage)",
                                        CreateColored};

}  // namespace renderer::oit
