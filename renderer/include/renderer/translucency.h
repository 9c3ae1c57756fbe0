// The translucency replays of the source documents, deterministic: a scene
// (renderer/scenes.h) rendered with a transparency method (renderer/oit/method.h).
//
// Frame order of document 000, each pass driven only through effect techniques
// and passes (shaders_hlsl/*.fx: shaders and the blend, depth-stencil and
// rasterizer state blocks live there; the C++ sets effect variables, binds
// targets and buffers, applies passes and draws):
//   the opaque pass   scene.fx Opaque/Scene: stripes, floor and cubes into frame + depth
//   object updates    particles.fx Update/StreamOut (ParticleSystem): stream output into
//                     the other ping-pong buffer, Draw(emitters, 0) on the first frame
//                     (the paper's Draw(1,0) with one emitter), DrawAuto after
//   the method        its passes over the objects: alpha and sorted one (OVER), WBOIT and
//                     colored two (<technique>/Transparency, then <technique>/Compose)
// Everything is seeded and the time step is fixed: frame N is a pure function of
// the settings and N.
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "renderer/image_metrics.h"  // Rmse, Psnr: the replays' image distances
#include "renderer/oit/method.h"
#include "renderer/particle_system.h"
#include "renderer/scenes.h"
#include "rhi/rhi.h"

namespace renderer {

// The colours the frame is cleared to before the opaque objects.
inline constexpr float kSkyColour[4] = {0.55f, 0.65f, 0.8f, 1.0f};
inline constexpr float kNeutralColour[4] = {0.6f, 0.6f, 0.6f, 1.0f};

struct TranslucencySettings {
  std::string scene = "smoke";  // a name of Scenes()
  uint32_t width = 640, height = 360;
  uint32_t seed = 1234;
  // Particles (smoke, fire).
  ParticleRule rule{48, 3, 40, 60};
  float particleSize = 0.3f;
  float secondsPerUpdate = 1.0f / 40.0f;
  // Shards.
  uint32_t shardCount = 3000;
  uint32_t extraShards = 0;       // the particle scenes: also draw this many shards (the heavy bench scene)
  float shardSurfaceTint = 0.5f;  // 0: neutral surface colour (tint only in transmission)
  bool shardsAllRed = false;      // every shard transmits (1, 0.15, 0.15)
  // The complexity scene: how many translucent quads overlap over the centre of the
  // frame (1..64), the depth complexity that exact methods' per-pixel storage grows with.
  uint32_t depthComplexity = 8;
  // The triangles scene (document 001): the opacity of its front blue triangle and
  // of every other triangle (the article's failure case: 1 in front of 0.5).
  float frontOpacity = 1.0f;
  float triangleOpacity = 0.5f;
  // The peeling methods (document 002): the depth layers they keep, and, for a method
  // that keeps layers, one of them (0: the nearest) shown alone instead of the
  // composite (-1: the composite).
  uint32_t peelLayers = oit::kDefaultPeelLayers;
  int showLayer = -1;
  // The fragment-buffer methods' storage (prefix-sum's sizing, linked-list's pool).
  oit::FragmentStorage fragmentStorage;
  // Document 003's m of moment-transparency-mindepth (per scene unit of view depth).
  float minDepthSlope = oit::kDefaultMinDepthSlope;
  // The camera's near and far planes; 0: the scene's (SceneInfo::nearPlane, farPlane).
  float nearPlane = 0, farPlane = 0;
  // The multisampled methods (wboit-msaa and its variants): samples per pixel.
  uint32_t msaaSamples = oit::kDefaultMsaaSamples;
  // Background: the frame's clear colour (kSkyColour, or kNeutralColour) behind the backdrop.
  bool neutralBackground = false;  // a plain grey wall instead of coloured stripes
  bool timestamps = false;         // per-pass TIMESTAMP queries and the fragment pass's statistics (LastTimes)
  bool countParticles = false;     // SO_STATISTICS around every update (see particleCount)
};

struct PassTimes {
  bool valid = false;  // false when the disjoint query said disjoint
  double opaqueMs = 0, updateMs = 0, totalMs = 0;
  std::vector<double> methodPassMs;  // one per pass of the method, as its PassNames()
  // Pixel-shader invocations of the method's pass that draws the translucent objects
  // (Method::FragmentPass, PIPELINE_STATISTICS): the fragments it shades and blends,
  // what a fill-bound pass's time follows.
  size_t fragmentPass = 0;
  uint64_t fragmentPassInvocations = 0;
};

class Translucency {
 public:
  static std::unique_ptr<Translucency> Create(rhi::Device* device, rhi::DeviceContext* context,
                                              const TranslucencySettings& settings, std::string* error);
  ~Translucency();

  // Renders the next frame (frame index frame(), then advances it) with `method`.
  // False when the method could not be made for this scene (error() says why);
  // the frame index does not advance then.
  bool RenderFrame(const oit::MethodInfo& method);
  // Whether `method` draws this scene's objects by design (the compute-tile methods
  // draw particles only); false with the reason in `why`. RenderFrame refuses the
  // others with that reason.
  bool Accepts(const oit::MethodInfo& method, std::string* why = nullptr) const;
  // Renders the last frame again with `method`: its camera and its objects as the last
  // RenderFrame left them (no update), so that several methods draw the very same
  // frame (the comparison, renderer/comparison.h). A back-to-front method needs that
  // frame's update to have counted the particles (countParticles, or a back-to-front
  // RenderFrame). False (and error()) before the first frame or when the method
  // cannot be made.
  bool RenderFrameAgain(const oit::MethodInfo& method);
  // The frames RenderFrame drew twice because the method's storage was too small the
  // first time (Method::FrameNeedsRedraw).
  uint64_t redrawnFrames() const { return redrawnFrames_; }
  const std::string& error() const { return error_; }

  // The frame as tightly packed RGBA8 rows.
  std::vector<uint8_t> ReadFrame();
  // The frame target itself (R8G8B8A8_UNORM, bindable as a shader resource), for
  // showing the frame without a read-back; the next RenderFrame overwrites it.
  rhi::Texture2D* FrameTexture() const;
  // Waits for and returns the pass times of the last frame (settings.timestamps).
  PassTimes LastTimes();
  // The method made for this replay (after a RenderFrame with it), for its memory and pass names.
  const oit::Method* MethodInstance(const oit::MethodInfo& method) const;

  uint32_t frame() const { return frame_; }
  // Live particles (emitters included) after the last update, from SO_STATISTICS;
  // valid with settings.countParticles or a back-to-front method.
  uint64_t particleCount() const;
  const TranslucencySettings& settings() const { return settings_; }
  const SceneInfo& scene() const { return *scene_; }

  // The fixed camera of frame n.
  Camera CameraForFrame(uint32_t n) const;
  // A camera used instead of the scripted one from the next RenderFrame on (e.g. an
  // interactive orbit camera); std::nullopt returns to the scripted camera.
  void SetCameraOverride(std::optional<Camera> camera) { cameraOverride_ = camera; }

 private:
  struct Impl;
  struct MethodState;
  class FrameGeometry;
  class FrameOpaque;
  Translucency() = default;
  bool Initialize(rhi::Device* device, rhi::DeviceContext* context, const TranslucencySettings& settings);
  MethodState* Prepare(const oit::MethodInfo& method);
  bool Render(const oit::MethodInfo& method, bool advance);
  // Render, then the same frame again where the method's storage proved too small for
  // it and has grown (Method::FrameNeedsRedraw), so that no frame is left incomplete.
  bool RenderComplete(const oit::MethodInfo& method, bool advance);
  bool PrepareVisibilityBuffer();
  void OpaquePass(bool visibilityBuffer);
  void DrawBackdrop(rhi::RenderTargetView* color, rhi::DepthStencilView* depth);
  void DrawOpaqueObjects(rhi::RenderTargetView* target, rhi::DepthStencilView* depth, bool visibilityIds);
  class FrameBackdrop;

  TranslucencySettings settings_;
  const SceneInfo* scene_ = nullptr;
  uint32_t frame_ = 0;
  bool lastUpdateCounted_ = false;
  uint64_t redrawnFrames_ = 0;
  Camera camera_;
  std::optional<Camera> cameraOverride_;
  std::string error_;
  std::unique_ptr<Impl> impl_;
};

}  // namespace renderer
