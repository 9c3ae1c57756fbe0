// The translucency demos of document 000 (SPEC.md), replayed deterministically.
//
// Frame order of the paper, one function per pass, each driven only through
// effect techniques and passes (shaders_hlsl/*.fx: shaders and the blend,
// depth-stencil and rasterizer state blocks live there; the C++ sets effect
// variables, binds targets and buffers, applies passes and draws):
//   OpaquePass         scene.fx Opaque/Scene: stripes, floor and cubes into frame + depth
//   ParticleUpdatePass smoke.fx Update/StreamOut: stream output into the other
//                      ping-pong buffer, Draw(emitters, 0) on the first frame
//                      (the paper's Draw(1,0) with one emitter), DrawAuto after
//   TransparencyPass   <method>/Transparency of smoke.fx (DrawAuto of the particles)
//                      and/or shards.fx (DrawIndexedInstanced of the shards)
//   ComposePass        <method>/Compose (WBOIT: Table 2; colored: Table 4)
// Methods: Alpha (plain OVER in buffer order; the fire demo: additive), Wboit
// (Tables 1 + 2), Colored (Tables 3 + corrected 4, or the literal Table 4 on
// request), Sorted (the reference: OVER back to front, sorted on the CPU:
// particles read back, shard instances reordered; fire: additive, sorted).
// Everything is seeded and the time step is fixed: frame N is a pure function of
// the settings and N.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "renderer/particle_system.h"
#include "rhi/rhi.h"

namespace renderer {

enum class TranslucencyDemo { Smoke, Shards, Fire };
enum class TranslucencyMethod { Alpha, Wboit, Colored, Sorted };

const char* ToString(TranslucencyDemo demo);
const char* ToString(TranslucencyMethod method);
bool ParseDemo(const std::string& text, TranslucencyDemo* demo);
bool ParseMethod(const std::string& text, TranslucencyMethod* method);

struct TranslucencySettings {
  TranslucencyDemo demo = TranslucencyDemo::Smoke;
  uint32_t width = 640, height = 360;
  uint32_t seed = 1234;
  // Smoke.
  ParticleRule rule{48, 3, 40, 60};
  float particleSize = 0.3f;
  float secondsPerUpdate = 1.0f / 40.0f;
  // Shards.
  uint32_t shardCount = 3000;
  uint32_t extraShards = 0;       // smoke / fire: also draw this many shards (the heavy bench scene)
  float shardSurfaceTint = 0.5f;  // 0: neutral surface colour (tint only in transmission)
  bool shardsAllRed = false;      // every shard transmits (1, 0.15, 0.15)
  // Background.
  bool neutralBackground = false;  // a plain grey wall instead of coloured stripes
  bool literalTable4 = false;      // colored: compose with Table 4 as printed
  bool timestamps = false;         // per-pass TIMESTAMP queries and the 3D pass's statistics (see LastTimes)
  bool countParticles = false;     // SO_STATISTICS around every update (see particleCount)
};

struct PassTimes {
  bool valid = false;  // false when the disjoint query said disjoint
  double opaqueMs = 0, updateMs = 0, transparencyMs = 0, composeMs = 0, totalMs = 0;
  // Pixel-shader invocations of the 3D transparency pass (PIPELINE_STATISTICS): the
  // fragments it shades and blends, what a fill-bound pass's time follows.
  uint64_t transparencyFragments = 0;
};

class Translucency {
 public:
  static std::unique_ptr<Translucency> Create(rhi::Device* device, rhi::DeviceContext* context,
                                              const TranslucencySettings& settings, std::string* error);
  ~Translucency();

  // Renders the next frame (frame index frame(), then advances it).
  void RenderFrame(TranslucencyMethod method);
  // The passes, in the paper's order (RenderFrame calls them).
  void OpaquePass();
  void ParticleUpdatePass();
  void TransparencyPass(TranslucencyMethod method);
  void ComposePass(TranslucencyMethod method);

  // The frame as tightly packed RGBA8 rows.
  std::vector<uint8_t> ReadFrame();
  // The frame target itself (R8G8B8A8_UNORM, bindable as a shader resource), for
  // showing the frame without a read-back; the next RenderFrame overwrites it.
  rhi::Texture2D* FrameTexture() const;
  // Waits for and returns the pass times of the last frame (settings.timestamps).
  PassTimes LastTimes();

  uint32_t frame() const { return frame_; }
  // Live particles (emitters included) after the last update, from SO_STATISTICS;
  // valid with settings.countParticles or the sorted method.
  uint64_t particleCount() const { return particleCount_; }
  const TranslucencySettings& settings() const { return settings_; }

  // The fixed camera of frame n.
  Camera CameraForFrame(uint32_t n) const;
  // A camera used instead of the scripted one from the next RenderFrame on (e.g. an
  // interactive orbit camera); std::nullopt returns to the scripted camera.
  void SetCameraOverride(std::optional<Camera> camera) { cameraOverride_ = camera; }

 private:
  struct Impl;
  Translucency() = default;
  bool Initialize(rhi::Device* device, rhi::DeviceContext* context, const TranslucencySettings& settings,
                  std::string* error);
  void DrawSmoke(TranslucencyMethod method);
  void DrawShards(TranslucencyMethod method);
  void Timestamp(int index);

  TranslucencySettings settings_;
  uint32_t frame_ = 0;
  uint64_t particleCount_ = 0;
  Camera camera_;
  std::optional<Camera> cameraOverride_;
  std::unique_ptr<Impl> impl_;
};

// Image distance of two RGBA8 images over RGB, in 8-bit steps.
double Rmse(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b);
double Psnr(double rmse);  // dB; infinity when rmse == 0

}  // namespace renderer
