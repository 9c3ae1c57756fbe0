// The scenes of the replays, one registry entry each: document 000's demos, and
// the teapot and the depth-complexity stack of the exact methods (documents 002, 004).
#include "renderer/scenes.h"

#include <cmath>

#include "objects/objects.h"
#include "renderer/translucency.h"

namespace renderer {
namespace {

// The complexity scene's camera; ComplexityQuadStack (below) faces its quads to it.
constexpr glm::vec3 kComplexityTarget{0.0f, 1.5f, 0.0f};
constexpr float kComplexityRadius = 6.0f;

void AddQuad(std::vector<BackdropVertex>* v, glm::vec3 o, glm::vec3 u, glm::vec3 w, glm::vec3 color) {
  glm::vec3 n = glm::normalize(glm::cross(w, u));  // left-handed: u right, w up -> normal towards the viewer
  BackdropVertex a{o, n, color}, b{o + u, n, color}, c{o + u + w, n, color}, d{o + w, n, color};
  v->insert(v->end(), {a, b, c, a, c, d});
}

void AddBox(std::vector<BackdropVertex>* v, glm::vec3 lo, glm::vec3 hi, glm::vec3 color) {
  glm::vec3 s = hi - lo;
  glm::vec3 X{s.x, 0, 0}, Y{0, s.y, 0}, Z{0, 0, s.z};
  AddQuad(v, lo, X, Y, color);                        // -z
  AddQuad(v, lo + X + Z, -X, Y, color);               // +z
  AddQuad(v, lo + Z, -Z, Y, color);                   // -x
  AddQuad(v, lo + X, Z, Y, color);                    // +x
  AddQuad(v, lo + Y, X, Z, color);                    // +y
  AddQuad(v, lo + Z, X, -Z, color);                   // -y
}

// The room of document 000's demos: coloured stripes on the back wall, a checkered
// floor and five cubes (neutral: all grey).
std::vector<BackdropVertex> StripedRoom(const TranslucencySettings& s) {
  const bool neutral = s.neutralBackground;
  std::vector<BackdropVertex> v;
  const glm::vec3 palette[8] = {{0.9f, 0.15f, 0.12f}, {0.95f, 0.55f, 0.1f}, {0.95f, 0.9f, 0.2f}, {0.2f, 0.75f, 0.25f},
                                {0.15f, 0.75f, 0.85f}, {0.15f, 0.3f, 0.9f},  {0.6f, 0.2f, 0.8f},  {0.95f, 0.95f, 0.95f}};
  const glm::vec3 grey{0.6f, 0.6f, 0.6f};
  for (int i = 0; i < 20; ++i)  // the back wall: vertical stripes
    AddQuad(&v, {-10.0f + i, 0, 4.5f}, {1, 0, 0}, {0, 9, 0}, neutral ? grey : palette[i % 8]);
  for (int i = 0; i < 10; ++i)  // the floor: a checker of bands
    for (int j = 0; j < 8; ++j) {
      glm::vec3 c = ((i + j) & 1) ? glm::vec3(0.35f) : glm::vec3(0.55f);
      AddQuad(&v, {-10.0f + 2 * i, 0, 4.5f - 2 * (j + 1)}, {2, 0, 0}, {0, 0, 2}, neutral ? grey : c);
    }
  struct Box {
    glm::vec3 lo, hi;
    int color;
  } boxes[] = {{{-4.0f, 0, 2.0f}, {-2.8f, 1.2f, 3.2f}, 0}, {{2.2f, 0, 2.4f}, {3.8f, 1.6f, 4.0f}, 5},
               {{-0.6f, 0, 3.2f}, {0.6f, 0.8f, 4.2f}, 2},  {{-2.2f, 0, -1.5f}, {-1.4f, 0.6f, -0.7f}, 3},
               {{1.2f, 0, -0.9f}, {1.9f, 2.4f, -0.2f}, 6}};
  for (const Box& b : boxes) AddBox(&v, b.lo, b.hi, neutral ? grey : palette[b.color]);
  return v;
}

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
                       {0.3f, 1.5f, 0.5f}, 7.0f, 120, StripedRoom, BuildSmoke};
const SceneInfo kFire{"fire", "the same particle system as flames; OVER is additive there",
                      {0.3f, 1.5f, 0.5f}, 7.0f, 120, StripedRoom, BuildFire};
const SceneInfo kShards{"shards", "document 000's instanced coloured glass shards (one DrawIndexedInstanced)",
                        {0.0f, 1.9f, 0.0f}, 7.5f, 1, StripedRoom, BuildShards};

// Document 002's Fig. 3: the Utah teapot, outside red and inside green, over a blue
// ground. Its frame (z up) is turned to the world's (y up) and halved: 1.6 high,
// spout towards +x, its bottom 0.02 over the ground (not in it: the two would z-fight).
std::vector<BackdropVertex> BlueGround(const TranslucencySettings&) {
  std::vector<BackdropVertex> v;
  AddQuad(&v, {-20, 0, -20}, {40, 0, 0}, {0, 0, 40}, {0.15f, 0.3f, 0.85f});
  return v;
}

TriangleMesh TeapotInWorld() {
  // Opacity 0.5 (document 002 gives none): a layer and what lies behind it weigh the
  // same, so the red outside and the green inside behind it both show. Transmission 0:
  // colored OIT dims what is behind by 1 - a, as OVER does.
  const MeshMaterial glass{{0.9f, 0.12f, 0.1f}, {0.15f, 0.8f, 0.2f}, 0.5f, glm::vec3(0.0f)};
  TriangleMesh teapot = UtahTeapot(8, glass);
  const auto toWorld = [](const glm::vec3& p) { return glm::vec3(p.x, p.z, -p.y); };  // a rotation: windings keep
  for (glm::vec3& p : teapot.positions) p = 0.5f * toWorld(p) + glm::vec3(0, 0.02f, 0);
  for (glm::vec3& n : teapot.normals) n = toWorld(n);
  return teapot;
}

bool BuildTeapot(rhi::Device* device, const TranslucencySettings& s,
                 std::vector<std::unique_ptr<TranslucentObject>>* objects, std::string* error) {
  auto teapot = CreateMeshes(Setup(device, s), {TeapotInWorld()}, error);
  if (!teapot) return false;
  objects->push_back(std::move(teapot));
  return true;
}

// Document 004's depth complexity: a stack of camera-facing quads, all of them over
// the centre of the frame, before a grey wall facing the camera of frame 0.
constexpr uint32_t kMaxDepthComplexity = 64;

std::vector<BackdropVertex> GreyWall(const TranslucencySettings& s) {
  const QuadStack stack = ComplexityQuadStack(s);
  const glm::vec3 forward = glm::normalize(stack.target - stack.eye);
  const glm::vec3 right = glm::normalize(glm::cross(glm::vec3(0, 1, 0), forward)), up = glm::cross(forward, right);
  const glm::vec3 centre = stack.eye + forward * (stack.depthFar + 1.5f);  // 1.5 behind the farthest quad
  std::vector<BackdropVertex> v;
  AddQuad(&v, centre - 15.0f * (right + up), 30.0f * right, 30.0f * up, glm::vec3(0.5f));  // faces the eye
  return v;
}

bool BuildComplexity(rhi::Device* device, const TranslucencySettings& s,
                     std::vector<std::unique_ptr<TranslucentObject>>* objects, std::string* error) {
  if (s.depthComplexity < 1 || s.depthComplexity > kMaxDepthComplexity) {
    *error = "depthComplexity " + std::to_string(s.depthComplexity) + " is outside 1.." +
             std::to_string(kMaxDepthComplexity);
    return false;
  }
  auto quads = CreateMeshes(Setup(device, s), CameraFacingQuads(ComplexityQuadStack(s)), error);
  if (!quads) return false;
  objects->push_back(std::move(quads));
  return true;
}

// Document 003's scenes (the thesis's near 0.25 and far 5000). Their backdrop: a
// light checkered ground and a two-tone wall behind, detail to see through the glass.
constexpr float kThesisNear = 0.25f, kThesisFar = 5000.0f;

std::vector<BackdropVertex> Studio(const TranslucencySettings&) {
  std::vector<BackdropVertex> v;
  for (int i = 0; i < 12; ++i)
    for (int j = 0; j < 12; ++j) {
      const glm::vec3 c = ((i + j) & 1) ? glm::vec3(0.45f) : glm::vec3(0.7f);
      AddQuad(&v, {-6.0f + i, 0, -6.0f + j}, {1, 0, 0}, {0, 0, 1}, c);
    }
  AddQuad(&v, {-6, 0, 3}, {12, 0, 0}, {0, 1.5f, 0}, {0.75f, 0.55f, 0.35f});
  AddQuad(&v, {-6, 1.5f, 3}, {12, 0, 0}, {0, 6, 0}, {0.8f, 0.8f, 0.75f});
  return v;
}

bool AddMeshes(rhi::Device* device, const TranslucencySettings& s, const std::vector<TriangleMesh>& meshes,
               std::vector<std::unique_ptr<TranslucentObject>>* objects, std::string* error) {
  auto object = CreateMeshes(Setup(device, s), meshes, error);
  if (!object) return false;
  objects->push_back(std::move(object));
  return true;
}

MeshMaterial Glass(const glm::vec3& colour, float opacity) { return {colour, 0.8f * colour, opacity, colour}; }

// Overlapping coloured cubes; the blue one in front, the others seen through it.
bool BuildCubes(rhi::Device* device, const TranslucencySettings& s,
                std::vector<std::unique_ptr<TranslucentObject>>* objects, std::string* error) {
  return AddMeshes(device, s,
                   {Box({-0.9f, 0.05f, 0.1f}, {-0.1f, 0.85f, 0.9f}, Glass({0.95f, 0.2f, 0.15f}, 0.5f)),
                    Box({0.15f, 0.05f, 0.3f}, {0.95f, 0.85f, 1.1f}, Glass({0.2f, 0.85f, 0.3f}, 0.5f)),
                    Box({-0.4f, 0.7f, 0.5f}, {0.4f, 1.5f, 1.3f}, Glass({1.0f, 0.85f, 0.2f}, 0.5f)),
                    Box({-0.35f, 0.3f, -0.5f}, {0.45f, 1.1f, 0.3f}, Glass({0.2f, 0.4f, 1.0f}, 0.5f))},
                   objects, error);
}

// "Ice in a cup": a smoky glass tumbler (open at the top) with two ice cubes, the
// front face of one 0.003 behind the tumbler's front wall (within 1/m = 0.01).
bool BuildIceInCup(rhi::Device* device, const TranslucencySettings& s,
                   std::vector<std::unique_ptr<TranslucentObject>>* objects, std::string* error) {
  const MeshMaterial cup{{0.35f, 0.45f, 0.6f}, {0.3f, 0.38f, 0.5f}, 0.65f, {0.35f, 0.45f, 0.6f}};
  const MeshMaterial ice{{0.85f, 0.95f, 1.0f}, {0.75f, 0.85f, 0.95f}, 0.35f, {0.85f, 0.95f, 1.0f}};
  return AddMeshes(device, s,
                   {Box({-0.45f, 0.02f, -0.45f}, {0.45f, 1.0f, 0.45f}, cup, true),
                    Box({-0.32f, 0.3f, -0.447f}, {0.02f, 0.64f, -0.107f}, ice),
                    Box({0.06f, 0.45f, -0.2f}, {0.38f, 0.77f, 0.12f}, ice)},
                   objects, error);
}

// "A magic circle on a glass floor": a glowing decal 0.001 above a translucent
// floor, which stands over the checkered ground.
bool BuildMagicCircle(rhi::Device* device, const TranslucencySettings& s,
                      std::vector<std::unique_ptr<TranslucentObject>>* objects, std::string* error) {
  const float floor = 0.4f;
  const MeshMaterial glass{{0.6f, 0.85f, 0.9f}, {0.5f, 0.7f, 0.75f}, 0.3f, {0.6f, 0.85f, 0.9f}};
  const MeshMaterial decal{{1.0f, 0.75f, 0.2f}, {1.0f, 0.75f, 0.2f}, 0.8f, {1.0f, 0.75f, 0.2f}};
  return AddMeshes(device, s,
                   {FlatQuad({-1.5f, floor, -1.5f}, {1.5f, floor, -1.5f}, {1.5f, floor, 1.5f}, {-1.5f, floor, 1.5f},
                             {0, 1, 0}, glass),
                    MagicCircle({0, floor + 0.001f, 0}, 1.0f, decal)},
                   objects, error);
}

const SceneInfo kCubes{"cubes", "document 003's overlapping translucent coloured cubes (near 0.25, far 5000)",
                       {0.0f, 0.7f, 0.4f}, 2.6f, 1, Studio, BuildCubes, kThesisNear, kThesisFar};
const SceneInfo kIceInCup{"ice-in-cup", "document 003's ice in a cup: translucent cubes just inside a glass",
                          {0.0f, 0.5f, 0.0f}, 1.6f, 1, Studio, BuildIceInCup, kThesisNear, kThesisFar};
const SceneInfo kMagicCircle{"magic-circle", "document 003's magic circle 0.001 above a translucent glass floor",
                             {0.0f, 0.4f, 0.0f}, 1.8f, 1, Studio, BuildMagicCircle, kThesisNear, kThesisFar};

const SceneInfo kTeapot{"teapot", "document 002's Fig. 3: a two-sided translucent Utah teapot over a blue ground",
                        {0.2f, 0.75f, 0.0f}, 3.2f, 1, BlueGround, BuildTeapot};
const SceneInfo kComplexity{"complexity",
                            "document 004's depth complexity: depthComplexity camera-facing quads over the centre",
                            kComplexityTarget, kComplexityRadius, 1, GreyWall, BuildComplexity};

}  // namespace

QuadStack ComplexityQuadStack(const TranslucencySettings& s) {
  const glm::vec3 eye = ScriptedEye(kComplexityTarget, kComplexityRadius, 0);
  const float distance = glm::length(kComplexityTarget - eye);
  return {eye, kComplexityTarget, distance - 1.5f, distance + 1.5f, s.depthComplexity, s.seed};
}

const std::vector<const SceneInfo*>& Scenes() {
  static const std::vector<const SceneInfo*> scenes = {&kSmoke,  &kFire,  &kShards,    &kTeapot,
                                                       &kComplexity, &kCubes, &kIceInCup, &kMagicCircle};
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

glm::vec3 ScriptedEye(const glm::vec3& cameraTarget, float cameraRadius, uint32_t frame) {
  const float angle = 0.3f * std::sin(frame * 0.01f);  // a slow swing, slightly above the target
  return cameraTarget + glm::vec3(cameraRadius * std::sin(angle), 1.2f, -cameraRadius * std::cos(angle));
}

glm::vec3 SceneLightDirection() { return glm::normalize(glm::vec3(-0.4f, 0.8f, -0.45f)); }

}  // namespace renderer
