// The scenes of the replays: an opaque backdrop (drawn with scene.fx), a list of
// translucent objects and a camera rig. The registry
// (Scenes()) is the one list the apps and the tests iterate.
#pragma once

#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>

#include "renderer/translucent_object.h"
#include "rhi/rhi.h"

namespace renderer {

struct TranslucencySettings;

// A vertex of the opaque backdrop (scene.fx): Lambert-lit, coloured per vertex.
struct BackdropVertex {
  glm::vec3 position, normal, color;
};

struct SceneInfo {
  const char* name;     // command lines and file names: "smoke"
  const char* summary;  // one line for listings
  // The scripted camera orbits `cameraTarget` at `cameraRadius`, slightly above it.
  glm::vec3 cameraTarget;
  float cameraRadius;
  // Frames a replay renders unless told otherwise: enough for its particles to
  // reach their steady state, 1 for a scene that does not change.
  int defaultFrames;
  // The opaque geometry, drawn first, whose depth bounds every translucent surface
  // (a triangle list).
  std::vector<BackdropVertex> (*backdrop)(const TranslucencySettings& settings);
  // Adds the scene's translucent objects (settings.extraShards adds shards to any scene).
  bool (*build)(rhi::Device* device, const TranslucencySettings& settings,
                std::vector<std::unique_ptr<TranslucentObject>>* objects, std::string* error);
  // The camera's near and far planes (view depth, scene units); document 003's scenes
  // use the thesis's 0.25 and 5000.
  float nearPlane = 0.1f, farPlane = 40.0f;
};

// The registry, in the order listings show them.
const std::vector<const SceneInfo*>& Scenes();
// nullptr when no scene has that name.
const SceneInfo* FindScene(std::string_view name);
// "smoke, fire, shards" for usage messages.
std::string SceneNames();

// Where the scripted camera of a scene with that target and radius is at frame n.
glm::vec3 ScriptedEye(const glm::vec3& cameraTarget, float cameraRadius, uint32_t frame);

// The direction towards the scenes' one light.
glm::vec3 SceneLightDirection();

}  // namespace renderer
