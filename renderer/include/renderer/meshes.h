// Translucent triangle meshes (the exact-transparency scenes of documents 002 and
// 004) and the geometry the scenes make of them: the Utah teapot tessellated from
// its Bezier patches, and stacks of camera-facing quads of a chosen depth complexity.
// The object that draws them is CreateMeshes (src/objects/meshes.cpp, shaders_hlsl/meshes.fx).
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

namespace renderer {

// The surface of one mesh, the same over all of it. Lit two-sided: the front
// side (triangles wound clockwise on screen, D3D11's front face) shows `front`,
// the other side `back`, with the normal flipped.
struct MeshMaterial {
  glm::vec3 front{1.0f}, back{1.0f};
  float opacity = 0.5f;
  glm::vec3 transmission{1.0f};  // what the surface lets through per channel (colored OIT's t)
};

// A triangle list in world space; normals point to the front side.
struct TriangleMesh {
  std::vector<glm::vec3> positions, normals;
  std::vector<uint32_t> indices;
  MeshMaterial material;
};

// The Utah teapot (Newell's 32 bicubic patches, data in src/objects/utah_teapot_patches.h)
// in its own frame: z up, base at z = 0, 3.15 high, spout towards +x. Each patch is
// evaluated on a (segments+1)^2 grid: patch p's vertices are
// [p * (segments+1)^2, (p+1) * (segments+1)^2), row by row (a row: constant v, the
// patch data's second index). Normals are the analytic ones, dP/du x dP/dv, which
// point out of the teapot; where that vanishes (the lid's knob and the bottom's
// centre, where a whole row of control points is one point) the normal is taken a
// step into the patch. Fronts face outwards: the front colour is the outside.
constexpr int kUtahTeapotPatches = 32;
TriangleMesh UtahTeapot(int segments, const MeshMaterial& material);

// `count` square quads facing the eye, perpendicular to the view axis eye -> target,
// at distinct view depths spread over [depthNear, depthFar] (distances from the eye
// along the axis), in random order, their colours cycling through six hues and
// their opacities in 0.2..0.5, from (seed). Every quad covers the cone of
// half-angle kCentreHalfAngleDegrees around the view axis, so that the depth
// complexity there is exactly `count`.
struct QuadStack {
  glm::vec3 eye, target;
  float depthNear = 0, depthFar = 0;
  uint32_t count = 0;
  uint32_t seed = 0;
};
constexpr float kCentreHalfAngleDegrees = 4.0f;
std::vector<TriangleMesh> CameraFacingQuads(const QuadStack& stack);

// Document 003's scenes (scenes.cpp) are made of these flat-faced meshes.
// A flat quad with corners a, b, c, d in order around it, its front side facing `front`.
TriangleMesh FlatQuad(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c, const glm::vec3& d,
                      const glm::vec3& front, const MeshMaterial& material);
// The axis-aligned box [lo, hi], fronts facing out; openTop leaves its +y face out (a cup).
TriangleMesh Box(const glm::vec3& lo, const glm::vec3& hi, const MeshMaterial& material, bool openTop = false);
// A magic circle in the horizontal plane through `centre`, facing up: two rings (outer
// radius `radius`, widths radius / 12) and a hexagram of bands between them.
TriangleMesh MagicCircle(const glm::vec3& centre, float radius, const MeshMaterial& material);

struct TranslucencySettings;
// The complexity scene's stack (scenes.cpp): settings.depthComplexity quads from
// settings.seed, facing the scripted camera of frame 0, 1.5 before to 1.5 behind its target.
QuadStack ComplexityQuadStack(const TranslucencySettings& settings);

}  // namespace renderer
