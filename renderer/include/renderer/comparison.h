// Every registered transparency method on every registered scene, measured against
// the scene's exact result (issue 16): replay --compare writes its tables and
// pictures, tests/replay/comparison_test.cpp bounds its errors.
//
// The reference of a scene is the first registered method of Exactness::kExact that
// accepts it (prefix-sum), else the first of kExactWithEnoughLayers (depth peeling)
// with the scene's layer count. Exact methods composite each fragment with its
// object's per-surface model (oit/common.fxh TransmissionFactor: coloured
// transmission for the shards), so colored blended OIT is measured against what it
// approximates.
//
// Every method draws the very same frame: the replay runs to the compared frame with
// the first registered method that accepts the scene (the particles do not depend on
// the method), then each method draws that frame again (Translucency::RenderFrameAgain),
// also for its timed frames. The scene's depth layers are counted first by a method
// that keeps layers (Method::LayerSamples), peeled to maxLayers; the comparison then
// gives the peeling methods that many layers (rounded up to even), so that the methods
// exact with enough layers are exact where the scene has at most maxLayers.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "renderer/oit/method.h"
#include "renderer/scenes.h"
#include "renderer/translucency.h"

namespace renderer {

struct ComparisonSettings {
  uint32_t width = 320, height = 180;
  int frames = -1;       // the compared frame is frame frames-1; <= 0: the scene's defaultFrames
  int timedFrames = 5;   // GPU ms: the median over the method drawing the compared frame again this many times
  // Changes a scene's replay settings before it is made (the tests' smaller smoke).
  std::function<void(TranslucencySettings&)> adjust;
  // The scenes compared, by name; empty: every registered scene.
  std::vector<std::string> scenes;
  // The most layers a scene is peeled to when counting its layers.
  uint32_t maxLayers = 64;
};

// One method on one scene.
struct MethodResult {
  const oit::MethodInfo* method = nullptr;
  bool refused = false;
  std::string reason;                 // why it refused the scene
  std::vector<uint8_t> image;         // RGBA8, the compared frame
  double rmse = 0, psnr = 0, ssim = 0;
  double shareOff = 0;                // pixels off by more than kOffSteps in some channel
  double bytesPerPixel = 0;           // Method::MemoryBytes() / pixels
  double gpuMs = 0;                   // the method's passes (not the opaque pass and updates), median
  bool timed = false;                 // false when no timestamp frame came back
  uint64_t lostFragments = 0;         // Method::LostFragments(): storage that overflowed
};

inline constexpr int kOffSteps = 2;  // the share of pixels off by more than 2/255

struct SceneComparison {
  const SceneInfo* scene = nullptr;
  const oit::MethodInfo* reference = nullptr;  // null: no exact method accepts the scene
  uint32_t layers = 0;            // depth layers of the densest pixel (0: no method keeps layers)
  bool layersComplete = true;     // false: more than maxLayers, the peeling methods miss some
  uint64_t fragments = 0;         // translucent fragments past the opaque depth (the reference's first pass)
  int frame = 0;                  // the compared frame's index
  std::vector<MethodResult> methods;  // every registered method, in registry order

  const MethodResult* Find(std::string_view method) const;
};

// Runs the comparison; false (and `error`) when a scene cannot be made at all.
// `progress` (may be empty) is told of each method as it starts.
bool CompareMethods(rhi::Device* device, rhi::DeviceContext* context, const ComparisonSettings& settings,
                    std::vector<SceneComparison>* results, std::string* error,
                    const std::function<void(const SceneInfo&, const oit::MethodInfo&)>& progress = {});

}  // namespace renderer
