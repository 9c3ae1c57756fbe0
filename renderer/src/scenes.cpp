// The scenes of document 000's demos, one registry entry each.
#include "renderer/scenes.h"

#include "objects/objects.h"
#include "renderer/translucency.h"

namespace renderer {
namespace {

ObjectSetup Setup(rhi::Device* device, const TranslucencySettings& s) {
  return {device, s.seed, SceneLightDirection()};
}

// The particle settings both particle scenes share: the rule, the step, the size.
ParticleSettings Particles(const TranslucencySettings& s) {
  ParticleSettings p;
  p.rule = s.rule;
  p.secondsPerUpdate = s.secondsPerUpdate;
  p.size = s.particleSize;
  return p;
}

bool AddExtraShards(rhi::Device* device, const TranslucencySettings& s,
                    std::vector<std::unique_ptr<TranslucentObject>>* objects, std::string* error) {
  if (s.extraShards == 0) return true;
  ShardSettings shards{s.extraShards, s.shardSurfaceTint, s.shardsAllRed};
  auto object = CreateShards(Setup(device, s), shards, error);
  if (!object) return false;
  objects->push_back(std::move(object));
  return true;
}

bool BuildSmoke(rhi::Device* device, const TranslucencySettings& s,
                std::vector<std::unique_ptr<TranslucentObject>>* objects, std::string* error) {
  ParticleSettings p = Particles(s);
  p.emitterCenter = {0, 0.3f, 0.5f};
  // A negative radius mirrors the emitter ring: emitters (and so their particles, in
  // buffer order) run from the front of the ring to its back, so unsorted OVER draws
  // near smoke first and far smoke on top: the failure of the paper's Fig. 1.
  p.emitterRadius = -1.8f;
  p.spread = {0.5f, 0.2f, 0.5f};
  p.speedUp = 1.2f;
  p.acceleration = {0.35f, 0.2f, 0.0f};
  auto smoke = CreateSmoke(Setup(device, s), p, false, error);
  if (!smoke) return false;
  objects->push_back(std::move(smoke));
  return AddExtraShards(device, s, objects, error);
}

bool BuildFire(rhi::Device* device, const TranslucencySettings& s,
               std::vector<std::unique_ptr<TranslucentObject>>* objects, std::string* error) {
  // Flames: a tight ring of emitters near the floor, fast buoyant rise, short lives.
  ParticleSettings p = Particles(s);
  p.emitterCenter = {0, 0.2f, 0.5f};
  p.emitterRadius = -0.45f;
  p.spread = {0.3f, 0.25f, 0.3f};
  p.speedUp = 0.9f;
  p.acceleration = {0.1f, 1.2f, 0.0f};
  auto fire = CreateSmoke(Setup(device, s), p, true, error);
  if (!fire) return false;
  objects->push_back(std::move(fire));
  return AddExtraShards(device, s, objects, error);
}

bool BuildShards(rhi::Device* device, const TranslucencySettings& s,
                 std::vector<std::unique_ptr<TranslucentObject>>* objects, std::string* error) {
  ShardSettings shards{s.shardCount, s.shardSurfaceTint, s.shardsAllRed};  // extraShards: for the other scenes
  auto object = CreateShards(Setup(device, s), shards, error);
  if (!object) return false;
  objects->push_back(std::move(object));
  return true;
}

const SceneInfo kSmoke{"smoke", "document 000's GPU particle smoke over the opaque scene (Fig. 1)",
                       {0.3f, 1.5f, 0.5f}, 7.0f, 120, BuildSmoke};
const SceneInfo kFire{"fire", "the same particle system as flames; OVER is additive there",
                      {0.3f, 1.5f, 0.5f}, 7.0f, 120, BuildFire};
const SceneInfo kShards{"shards", "document 000's instanced coloured glass shards (one DrawIndexedInstanced)",
                        {0.0f, 1.9f, 0.0f}, 7.5f, 1, BuildShards};

}  // namespace

const std::vector<const SceneInfo*>& Scenes() {
  static const std::vector<const SceneInfo*> scenes = {&kSmoke, &kFire, &kShards};
  return scenes;
}

const SceneInfo* FindScene(std::string_view name) {
  for (const SceneInfo* s : Scenes())
    if (name == s->name) return s;
  return nullptr;
}

std::string SceneNames() {
  std::string names;
  for (const SceneInfo* s : Scenes()) names += (names.empty() ? "" : ", ") + std::string(s->name);
  return names;
}

glm::vec3 SceneLightDirection() { return glm::normalize(glm::vec3(-0.4f, 0.8f, -0.45f)); }

}  // namespace renderer
