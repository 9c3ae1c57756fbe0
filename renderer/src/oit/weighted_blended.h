// The weighted blended methods of document 000: WBOIT (Tables 1 and 2) and
// colored blended OIT (Tables 3 and 4), which also multiplies the frame by each
// surface's transmission during accumulation. Passes, in the paper's order:
//   Transparency  accum and revealage cleared (Table 1's clear values), then the
//                 geometry into accum, revealage (and the frame: colored)
//   Compose       a full-screen triangle over the frame (oit/method.fx)
#pragma once

#include "renderer/oit/method.h"

namespace renderer::oit {

// transmission: colored OIT (the frame is RT2 of the accumulation pass).
std::unique_ptr<Method> CreateWeightedBlended(const MethodInfo& info, const MethodSetup& setup, bool transmission,
                                              std::string* error);

}  // namespace renderer::oit
