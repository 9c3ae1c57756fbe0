// How a device's output merger rounds its blends. D3D11 leaves blend precision to
// the hardware (at least the render target format's), so two conformant devices
// blend the same fragments into images a step or more apart; a method that replays
// the output merger's blends in a compute shader (the compute-tile methods, issue 19)
// needs this device's arithmetic to give the image its ROP methods give. The probe
// blends known values (shaders_hlsl/oit/blend_probe.fx, with the methods' own blend
// states) and keeps the model that reproduces them.
#pragma once

#include <cstdint>
#include <string>

#include "rhi/rhi.h"

namespace renderer {

struct OutputMergerArithmetic {
  static constexpr uint32_t kProbes = 256;  // pixels probed per target format
  // R8G8B8A8_UNORM: the source's values and factors are converted to 8 bits; true where
  // each product is rounded to 8 bits before the saturated sum (lavapipe), false where
  // the sum is rounded once. An H100 is closest to the second, but not it: 238 of the
  // 256 probed pixels, the others one step apart (its arithmetic is not known here).
  bool unormRoundsEachTerm = false;
  // R16G16B16A16_FLOAT: true where a sum is rounded toward zero (lavapipe), false where
  // to nearest even (an H100); a sum past the largest half is held there on both.
  bool halfRoundsTowardZero = false;
  // Of kProbes pixels each, how many the chosen models reproduce exactly.
  uint32_t unormMatches = 0, halfMatches = 0;
};

// Probes the device with its immediate context: false (and `error`) when the probe
// could not run. A device matching neither model in some pixels gets the closer one
// (unormMatches or halfMatches below kProbes says so).
bool ProbeOutputMergerArithmetic(rhi::Device* device, OutputMergerArithmetic* out, std::string* error);

}  // namespace renderer
