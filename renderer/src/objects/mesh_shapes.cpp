// The geometry of the exact-transparency scenes (renderer/meshes.h): the Utah
// teapot evaluated from its Bezier patches, and stacks of camera-facing quads.
#include <cmath>
#include <numeric>
#include <utility>

#include "objects/utah_teapot_patches.h"
#include "random.h"
#include "renderer/meshes.h"

namespace renderer {
namespace {

using Patch = std::array<glm::vec3, 16>;  // [4 * row + column]

Patch TeapotPatch(int p) {
  Patch patch;
  for (int i = 0; i < 16; ++i) {
    const auto& c = utah_teapot::kControlPoints[utah_teapot::kPatches[p][i] - 1];
    patch[i] = {c[0], c[1], c[2]};
  }
  return patch;
}

// The cubic Bernstein polynomials at t and their derivatives.
void Bernstein(float t, float b[4], float d[4]) {
  const float s = 1.0f - t;
  b[0] = s * s * s, b[1] = 3 * t * s * s, b[2] = 3 * t * t * s, b[3] = t * t * t;
  d[0] = -3 * s * s, d[1] = 3 * s * s - 6 * t * s, d[2] = 6 * t * s - 3 * t * t, d[3] = 3 * t * t;
}

struct SurfacePoint {
  glm::vec3 position, dPdu, dPdv;
};

SurfacePoint Evaluate(const Patch& patch, float u, float v) {
  float bu[4], du[4], bv[4], dv[4];
  Bernstein(u, bu, du);
  Bernstein(v, bv, dv);
  SurfacePoint s{glm::vec3(0), glm::vec3(0), glm::vec3(0)};
  for (int row = 0; row < 4; ++row)
    for (int column = 0; column < 4; ++column) {
      const glm::vec3& c = patch[4 * row + column];
      s.position += bv[row] * bu[column] * c;
      s.dPdu += bv[row] * du[column] * c;
      s.dPdv += dv[row] * bu[column] * c;
    }
  return s;
}

// dP/du x dP/dv; at a pole (a whole row of control points in one point, so that
// dP/du vanishes along that edge) the normal of the surface a step inside, which
// is the limit of the normals approaching the pole.
glm::vec3 PatchNormal(const Patch& patch, float u, float v) {
  constexpr float kStep = 1e-3f;
  SurfacePoint s = Evaluate(patch, u, v);
  glm::vec3 n = glm::cross(s.dPdu, s.dPdv);
  if (glm::length(n) < 1e-6f) {
    s = Evaluate(patch, u, v < 0.5f ? v + kStep : v - kStep);
    n = glm::cross(s.dPdu, s.dPdv);
  }
  return glm::normalize(n);
}

// A cell's triangle at a pole has two corners at the pole: one control point
// evaluated twice, equal up to rounding.
bool Degenerate(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c) {
  constexpr float kSamePoint = 1e-5f;
  return glm::distance(a, b) < kSamePoint || glm::distance(b, c) < kSamePoint || glm::distance(c, a) < kSamePoint;
}

// Two triangles per grid cell, wound so that their geometric normal follows
// dP/du x dP/dv (D3D11's front face, clockwise on screen, in a left-handed world);
// the cells that collapse at a pole are left out.
void AddGridTriangles(uint32_t base, int segments, TriangleMesh* mesh) {
  const auto at = [&](int i, int j) { return base + uint32_t(j * (segments + 1) + i); };
  const auto add = [&](uint32_t a, uint32_t b, uint32_t c) {
    if (Degenerate(mesh->positions[a], mesh->positions[b], mesh->positions[c])) return;
    mesh->indices.insert(mesh->indices.end(), {a, b, c});
  };
  for (int j = 0; j < segments; ++j)
    for (int i = 0; i < segments; ++i) {
      add(at(i, j), at(i + 1, j), at(i, j + 1));
      add(at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
    }
}

// 0..count-1 in a seeded random order (Fisher-Yates): distinct depth slots handed
// out so that submission order is not depth order.
std::vector<uint32_t> ShuffledSlots(uint32_t count, uint32_t seed) {
  std::vector<uint32_t> slot(count);
  std::iota(slot.begin(), slot.end(), 0u);
  for (uint32_t i = count; i > 1; --i) std::swap(slot[i - 1], slot[uint32_t(Random(seed, 300, i) * i)]);
  return slot;
}

// A square of half-size `half` in the plane of right and up, facing an eye that
// looks along right x up: its normal, up x right, points at the eye.
TriangleMesh FacingSquare(const glm::vec3& centre, const glm::vec3& right, const glm::vec3& up, float half,
                          const MeshMaterial& material) {
  TriangleMesh quad;
  const glm::vec3 towardsEye = glm::cross(up, right);
  for (glm::vec2 corner : {glm::vec2(-1, -1), glm::vec2(-1, 1), glm::vec2(1, 1), glm::vec2(1, -1)}) {
    quad.positions.push_back(centre + half * (corner.x * right + corner.y * up));
    quad.normals.push_back(towardsEye);
  }
  quad.indices = {0, 1, 2, 0, 2, 3};  // clockwise as the eye sees them: front faces
  quad.material = material;
  return quad;
}

// The triangle a, b, c wound so that its front (clockwise on screen in a left-handed
// world: cross(b - a, c - a) towards the eye) faces `front`.
void AddFacingTriangle(TriangleMesh* mesh, const glm::vec3& a, glm::vec3 b, glm::vec3 c, const glm::vec3& front) {
  if (glm::dot(glm::cross(b - a, c - a), front) < 0) std::swap(b, c);
  const glm::vec3 normal = glm::normalize(front);
  const uint32_t base = uint32_t(mesh->positions.size());
  mesh->positions.insert(mesh->positions.end(), {a, b, c});
  mesh->normals.insert(mesh->normals.end(), {normal, normal, normal});
  mesh->indices.insert(mesh->indices.end(), {base, base + 1, base + 2});
}

void AddFacingQuad(TriangleMesh* mesh, const glm::vec3& a, const glm::vec3& b, const glm::vec3& c, const glm::vec3& d,
                   const glm::vec3& front) {
  AddFacingTriangle(mesh, a, b, c, front);
  AddFacingTriangle(mesh, a, c, d, front);
}

}  // namespace

TriangleMesh FlatQuad(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c, const glm::vec3& d,
                      const glm::vec3& front, const MeshMaterial& material) {
  TriangleMesh mesh;
  mesh.material = material;
  AddFacingQuad(&mesh, a, b, c, d, front);
  return mesh;
}

TriangleMesh Box(const glm::vec3& lo, const glm::vec3& hi, const MeshMaterial& material, bool openTop) {
  TriangleMesh mesh;
  mesh.material = material;
  const auto corner = [&](int x, int y, int z) { return glm::vec3(x ? hi.x : lo.x, y ? hi.y : lo.y, z ? hi.z : lo.z); };
  for (int axis = 0; axis < 3; ++axis)
    for (int side = 0; side < 2; ++side) {
      if (openTop && axis == 1 && side == 1) continue;
      glm::vec3 out(0);
      out[axis] = side ? 1.0f : -1.0f;
      // The face's four corners in order around it: the other two axes as (0,0) (1,0) (1,1) (0,1).
      const int u = (axis + 1) % 3, v = (axis + 2) % 3;
      glm::vec3 quad[4];
      const int steps[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
      for (int k = 0; k < 4; ++k) {
        int bits[3];
        bits[axis] = side, bits[u] = steps[k][0], bits[v] = steps[k][1];
        quad[k] = corner(bits[0], bits[1], bits[2]);
      }
      AddFacingQuad(&mesh, quad[0], quad[1], quad[2], quad[3], out);
    }
  return mesh;
}

TriangleMesh MagicCircle(const glm::vec3& centre, const float radius, const MeshMaterial& material) {
  TriangleMesh mesh;
  mesh.material = material;
  const glm::vec3 up(0, 1, 0);
  const auto at = [&](float r, float angle) { return centre + r * glm::vec3(std::cos(angle), 0, std::sin(angle)); };
  const float width = radius / 12.0f, inner = 0.62f * radius;
  constexpr int kSegments = 48;
  constexpr float kTau = 6.2831853f;
  for (float r : {radius, inner})
    for (int i = 0; i < kSegments; ++i) {
      const float a0 = kTau * i / kSegments, a1 = kTau * (i + 1) / kSegments;
      AddFacingQuad(&mesh, at(r - width, a0), at(r, a0), at(r, a1), at(r - width, a1), up);
    }
  // The hexagram: the six sides of two triangles inscribed in the inner ring.
  for (int i = 0; i < 6; ++i) {
    const glm::vec3 p = at(inner - width, kTau * i / 6), q = at(inner - width, kTau * (i + 2) / 6);
    const glm::vec3 across = 0.5f * width * glm::normalize(glm::cross(up, q - p));
    AddFacingQuad(&mesh, p - across, q - across, q + across, p + across, up);
  }
  return mesh;
}

TriangleMesh UtahTeapot(int segments, const MeshMaterial& material) {
  TriangleMesh mesh;
  mesh.material = material;
  for (int p = 0; p < kUtahTeapotPatches; ++p) {
    const Patch patch = TeapotPatch(p);
    const uint32_t base = uint32_t(mesh.positions.size());
    for (int j = 0; j <= segments; ++j)
      for (int i = 0; i <= segments; ++i) {
        const float u = float(i) / segments, v = float(j) / segments;
        mesh.positions.push_back(Evaluate(patch, u, v).position);
        mesh.normals.push_back(PatchNormal(patch, u, v));
      }
    AddGridTriangles(base, segments, &mesh);
  }
  return mesh;
}

std::vector<TriangleMesh> CameraFacingQuads(const QuadStack& stack) {
  const glm::vec3 forward = glm::normalize(stack.target - stack.eye);
  const glm::vec3 right = glm::normalize(glm::cross(glm::vec3(0, 1, 0), forward));  // left-handed: x = up x z
  const glm::vec3 up = glm::cross(forward, right);
  const glm::vec3 palette[6] = {{0.95f, 0.2f, 0.15f}, {0.2f, 0.85f, 0.3f}, {0.2f, 0.4f, 1.0f},
                                {1.0f, 0.8f, 0.15f},  {0.2f, 0.9f, 0.95f}, {0.9f, 0.25f, 0.9f}};
  const std::vector<uint32_t> slot = ShuffledSlots(stack.count, stack.seed);
  const float spacing = stack.count > 1 ? (stack.depthFar - stack.depthNear) / float(stack.count - 1) : 0.0f;
  const uint32_t firstColour = uint32_t(Random(stack.seed, 320, 0) * 6);  // then every colour in turn
  std::vector<TriangleMesh> quads;
  for (uint32_t i = 0; i < stack.count; ++i) {
    auto r = [&](uint32_t stream) { return Random(stack.seed, 310 + stream, i); };
    const float depth = stack.depthNear + spacing * float(slot[i]);
    // In angles seen from the eye: a half-size of 8..22 degrees and the centre off
    // the axis by up to the half-size less 5 degrees, so that every quad covers the
    // central 4 degrees and the quads overlap differently around them.
    const float halfAngle = 8.0f + 14.0f * r(0);
    const glm::vec2 offset = depth * std::tan(glm::radians(halfAngle - 5.0f)) *
                             glm::vec2(2 * r(1) - 1, 2 * r(2) - 1) / std::sqrt(2.0f);
    const glm::vec3 colour = palette[(i + firstColour) % 6];
    const MeshMaterial filter{colour, colour, 0.2f + 0.3f * r(4), colour};  // a colour filter: transmits its colour
    quads.push_back(FacingSquare(stack.eye + forward * depth + right * offset.x + up * offset.y, right, up,
                                 depth * std::tan(glm::radians(halfAngle)), filter));
  }
  return quads;
}

}  // namespace renderer
