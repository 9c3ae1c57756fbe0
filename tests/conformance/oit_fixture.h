// SPEC.md doc 000 tables 1-4 as a GPU fixture: overlapping translucent layers
// rendered through each table's exact passes, and the same passes on the CPU
// through rhi::reference::BlendResult. The tables and the weight are read from
// the renderer's effect files, never restated.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "conformance_gpu.h"
#include "rhi_reference/formats.h"

namespace conf {

enum class OitMethod { Wboit /*Tables 1+2*/, ColoredLiteral /*3 + 4 as printed*/, ColoredCorrected /*3 + corrected 4*/ };
const char* OitMethodName(OitMethod method);

struct OitLayer {
  std::array<float, 4> color;  // straight rgb + alpha
  std::array<float, 3> transmission;  // t.rgb (coloured OIT)
  float depth;
};

constexpr int kOitLayers = 4;
constexpr int kOitPixels = 16;  // a 4x4 target, one layer stack per pixel

struct OitScene {
  std::array<std::array<OitLayer, kOitLayers>, kOitPixels> layers;  // [pixel][draw order]
  std::array<std::array<float, 4>, kOitPixels> background;          // the opaque frame
};
// Pixel 0: red a=.5 z=.2, green a=.4 z=.5, blue a=.6 z=.8, white a=.3 z=.35 over grey;
// the rest seeded random (a in [0.1, 0.9], z in [0.05, 0.95]).
OitScene MakeOitScene(uint32_t seed);

struct OitPixelResult {
  rhi::reference::StoredColor gpuAccum, gpuRevealage, gpuFrame;     // GPU
  rhi::reference::StoredColor modelAccum, modelRevealage, modelFrame; // CPU model, whole chain
  rhi::reference::StoredColor stageFrame;  // CPU compose fed with the GPU's accum/revealage (and frame)
  rhi::reference::StoredColor over;        // sorted back-to-front OVER (straight alpha)
  std::array<float, 3> intent;             // the method's formula in double precision, linear [0,1]
};

struct OitResult {
  OitMethod method;
  std::array<OitPixelResult, kOitPixels> pixels;
  // Largest distances in steps (max over pixels and channels).
  uint32_t accumSteps = 0, revealageSteps = 0, stageSteps = 0, chainSteps = 0, overSteps = 0, intentSteps = 0;
  std::vector<std::string> validation, refusals;
};

// The method's accumulating and composing blend states, read from its effect
// include's state blocks (shaders_hlsl/oit/*.fxh), where the tables live.
struct OitTables {
  rhi::BLEND_DESC accumulate, compose;
};
OitTables LoadOitTables(Gpu& gpu, OitMethod method);

// Table 1's weight w(a, z) for each (a, z), evaluated on the GPU by a compute
// shader that includes shaders_hlsl/oit/wboit_weight.hlsli, the one definition.
std::vector<float> WboitWeights(Gpu& gpu, const std::vector<std::array<float, 2>>& alphaDepth);

OitResult RunOitFixture(Gpu& gpu, OitMethod method, const OitScene& scene);

// The text of shaders_hlsl/<file>, for test shaders that include the renderer's own code.
std::string ShaderSource(const std::string& file);

// Runs the compute shader `source` (cs_5_0, entry main) once per input, Dispatch(inputCount,
// 1, 1): t0 a StructuredBuffer of the inputs (inputStride bytes each), u0 a
// RWStructuredBuffer<float> of outputCount floats, which it returns.
std::vector<float> RunFloatCompute(Gpu& gpu, const std::string& source, const void* inputs, UINT inputStride,
                                   UINT inputCount, UINT outputCount);

}  // namespace conf
