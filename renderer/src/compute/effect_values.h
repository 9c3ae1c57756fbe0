// Setting the compute effects' variables by name (renderer/src/compute/).
#pragma once

#include <cstdint>

#include "fx/effect.h"

namespace renderer::compute {

// A uint variable, all 32 bits (SetInt would go through int and double).
inline void SetUint(fx::Effect* effect, const char* name, uint32_t value) {
  effect->GetVariableByName(name)->AsScalar()->SetRawValue(&value, 0, sizeof value);
}

inline void SetUav(fx::Effect* effect, const char* name, rhi::UnorderedAccessView* view) {
  effect->GetVariableByName(name)->AsUnorderedAccessView()->SetUnorderedAccessView(view);
}

}  // namespace renderer::compute
