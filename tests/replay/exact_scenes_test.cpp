// The scenes of the exact-transparency work (documents 002 and 004) checked
// against independent computations, not against their own goldens:
//  - the Utah teapot's tessellation on the CPU: the patch data's symmetries, unit
//    normals that point out of the teapot and agree with the triangles' winding;
//  - the teapot scene on the GPU: its outside red and its inside green (two-sided
//    lighting, SV_IsFrontFace), the ground blue; one DrawIndexed per object pass;
//  - the complexity scene: the quads cover the centre of the frame, and `sorted`
//    there equals OVER composited on the CPU from the quads' colours and opacities
//    over the lit wall, for several depth complexities.
#include <algorithm>
#include <cmath>
#include <numeric>

#include <glm/gtc/matrix_transform.hpp>

#include "gpu_test.h"
#include "renderer/meshes.h"
#include "renderer/translucency.h"
#include "rhi/trace.h"

namespace rhi_test {
namespace {

using renderer::Translucency;
using renderer::TranslucencySettings;
using renderer::TriangleMesh;

constexpr int kSegments = 8;
constexpr int kPatchVertices = (kSegments + 1) * (kSegments + 1);
// The ambient term of the translucent meshes and of the opaque pass (meshes.fx, scene.fx).
constexpr float kAmbient = 0.45f;

glm::vec3 Vertex(const TriangleMesh& m, int patch, int i, int j) {
  return m.positions[size_t(patch * kPatchVertices + j * (kSegments + 1) + i)];
}
glm::vec3 Normal(const TriangleMesh& m, int patch, int i, int j) {
  return m.normals[size_t(patch * kPatchVertices + j * (kSegments + 1) + i)];
}

void ExpectNear(const glm::vec3& a, const glm::vec3& b, const char* what) {
  EXPECT_LT(glm::length(a - b), 1e-4f) << what << ": (" << a.x << ", " << a.y << ", " << a.z << ") vs (" << b.x << ", "
                                       << b.y << ", " << b.z << ")";
}

// Transcription errors in the 306 control points or the patch table break these:
// the rim, body, knob and lid are one quadrant turned by -90 degrees about z (the
// bottom by +90), and the handle's and the spout's patches are pairs mirrored in y
// (the mirror reverses u).
TEST(UtahTeapot, PatchDataHasTheTeapotsSymmetries) {
  const TriangleMesh m = renderer::UtahTeapot(kSegments, {});
  ASSERT_EQ(m.positions.size(), size_t(renderer::kUtahTeapotPatches * kPatchVertices));
  const auto turnedBack = [](glm::vec3 p) { return glm::vec3(p.y, -p.x, p.z); };
  const auto turnedOn = [](glm::vec3 p) { return glm::vec3(-p.y, p.x, p.z); };
  for (int first : {0, 4, 8, 20, 24, 28})
    for (int q = first; q < first + 3; ++q)
      for (int j = 0; j <= kSegments; ++j)
        for (int i = 0; i <= kSegments; ++i) {
          const glm::vec3 p = Vertex(m, q, i, j);
          ExpectNear(first == 28 ? turnedOn(p) : turnedBack(p), Vertex(m, q + 1, i, j), "quadrant");
        }
  for (int half : {12, 14, 16, 18})
    for (int j = 0; j <= kSegments; ++j)
      for (int i = 0; i <= kSegments; ++i) {
        const glm::vec3 p = Vertex(m, half, i, j);
        ExpectNear({p.x, -p.y, p.z}, Vertex(m, half + 1, kSegments - i, j), "mirror");
      }
}

TEST(UtahTeapot, NormalsAreUnitAndFollowTheWinding) {
  const TriangleMesh m = renderer::UtahTeapot(kSegments, {});
  for (const glm::vec3& n : m.normals) ASSERT_NEAR(glm::length(n), 1.0f, 1e-4f);
  ASSERT_EQ(m.indices.size() % 3, 0u);
  ASSERT_GT(m.indices.size(), size_t(3 * 28 * kSegments * kSegments)) << "at most the pole cells are left out";
  for (size_t t = 0; t < m.indices.size(); t += 3) {
    const glm::vec3 a = m.positions[m.indices[t]], b = m.positions[m.indices[t + 1]],
                    c = m.positions[m.indices[t + 2]];
    const glm::vec3 n = m.normals[m.indices[t]] + m.normals[m.indices[t + 1]] + m.normals[m.indices[t + 2]];
    EXPECT_GT(glm::dot(glm::cross(b - a, c - a), n), 0.0f) << "triangle " << t / 3;
  }
}

// Outward at points whose outside is known: the body's patch centres face away from
// the axis (the lower body's also downwards), the bottom down, the knob's apex (a
// pole) up, the handle's and the spout's halves away from their plane of symmetry
// y = 0 (where they leave the body: the spout's tip flares upwards).
TEST(UtahTeapot, NormalsPointOutOfTheTeapot) {
  const TriangleMesh m = renderer::UtahTeapot(kSegments, {});
  const int mid = kSegments / 2;
  for (int body = 4; body < 12; ++body) {
    const glm::vec3 p = Vertex(m, body, mid, mid);
    EXPECT_GT(glm::dot(Normal(m, body, mid, mid), glm::normalize(glm::vec3(p.x, p.y, 0))), 0.5f) << body;
  }
  for (int bottom = 28; bottom < 32; ++bottom) EXPECT_LT(Normal(m, bottom, mid, mid).z, -0.99f) << bottom;
  for (int knob = 20; knob < 24; ++knob) EXPECT_GT(Normal(m, knob, mid, 0).z, 0.99f) << "apex of " << knob;
  for (int half : {12, 14, 16, 18}) {
    EXPECT_LT(Normal(m, half, mid, 0).y, -0.5f) << half;
    EXPECT_GT(Normal(m, half + 1, mid, 0).y, 0.5f) << half + 1;
  }
}

class CameraFacingQuadsTest : public ::testing::TestWithParam<uint32_t> {};

// Each quad is a front-facing square perpendicular to the view axis at its own
// depth, and the rays 4 degrees off the axis (any direction) pass through it.
TEST_P(CameraFacingQuadsTest, EveryQuadCoversTheCentreAtItsOwnDepth) {
  const renderer::QuadStack stack{{0, 2, -6}, {0, 1, 0}, 4, 8, GetParam(), 77};
  const std::vector<TriangleMesh> quads = renderer::CameraFacingQuads(stack);
  ASSERT_EQ(quads.size(), GetParam());
  const glm::vec3 forward = glm::normalize(stack.target - stack.eye);
  const float tanCentre = std::tan(glm::radians(renderer::kCentreHalfAngleDegrees));
  std::vector<float> depths;
  for (const TriangleMesh& q : quads) {
    ASSERT_EQ(q.positions.size(), 4u);
    ASSERT_EQ(q.indices.size(), 6u);
    const float depth = glm::dot(q.positions[0] - stack.eye, forward);
    for (const glm::vec3& p : q.positions) EXPECT_NEAR(glm::dot(p - stack.eye, forward), depth, 1e-4f);
    const glm::vec3 a = q.positions[q.indices[0]], b = q.positions[q.indices[1]], c = q.positions[q.indices[2]];
    EXPECT_GT(glm::dot(glm::cross(b - a, c - a), stack.eye - a), 0.0f) << "wound clockwise as the eye sees it";
    // The quad's extent along its edges, against the centre cone's disc at its depth.
    const glm::vec3 centre = (q.positions[0] + q.positions[2]) * 0.5f;
    const glm::vec3 axisPoint = stack.eye + forward * depth;
    const glm::vec3 edgeU = glm::normalize(q.positions[3] - q.positions[0]),
                    edgeV = glm::normalize(q.positions[1] - q.positions[0]);
    const float half = glm::length(q.positions[3] - q.positions[0]) * 0.5f;
    const glm::vec3 toAxis = axisPoint - centre;
    EXPECT_LE(std::abs(glm::dot(toAxis, edgeU)) + depth * tanCentre, half);
    EXPECT_LE(std::abs(glm::dot(toAxis, edgeV)) + depth * tanCentre, half);
    EXPECT_GT(q.material.opacity, 0.0f);
    EXPECT_LT(q.material.opacity, 1.0f);
    depths.push_back(depth);
  }
  std::vector<float> sorted = depths;
  std::sort(sorted.begin(), sorted.end());
  EXPECT_TRUE(std::adjacent_find(sorted.begin(), sorted.end(), [](float x, float y) { return y - x < 1e-3f; }) ==
              sorted.end())
      << "distinct depths";
  if (GetParam() > 2) {
    EXPECT_NE(depths, sorted) << "submission order is not depth order";
  }
}

INSTANTIATE_TEST_SUITE_P(DepthComplexity, CameraFacingQuadsTest, ::testing::Values(1u, 3u, 8u, 64u));

// ---------------------------------------------------------------------------
// On the GPU (validation layer on).

class ExactScenesTest : public GpuTest {
 protected:
  static TranslucencySettings Settings(const char* scene) {
    TranslucencySettings s;
    s.scene = scene;
    s.width = 96, s.height = 54;
    return s;
  }
  std::unique_ptr<Translucency> Make(const TranslucencySettings& s) {
    std::string error;
    auto t = Translucency::Create(device.Get(), context.Get(), s, &error);
    EXPECT_NE(t, nullptr) << error;
    return t;
  }
  std::vector<uint8_t> Render(Translucency& t, const char* method) {
    EXPECT_TRUE(t.RenderFrame(*renderer::oit::FindMethod(method))) << t.error();
    return t.ReadFrame();
  }
};

struct Rgb {
  int r, g, b;
};
Rgb PixelAt(const std::vector<uint8_t>& image, uint32_t width, glm::ivec2 p) {
  const uint8_t* px = &image[(size_t(p.y) * width + p.x) * 4];
  return {px[0], px[1], px[2]};
}

// The pixel a world point projects to.
glm::ivec2 Project(const renderer::Camera& camera, const glm::vec3& world, uint32_t width, uint32_t height) {
  const glm::vec4 clip = camera.viewProj * glm::vec4(world, 1.0f);
  const glm::vec2 ndc = glm::vec2(clip) / clip.w;
  return {int((ndc.x * 0.5f + 0.5f) * width), int((0.5f - ndc.y * 0.5f) * height)};
}

// Outside red: the body's near wall (world (0.2, 0.6, -1): the teapot is halved and
// turned y-up, its widest ring at about 0.5-0.7 high) is red over what lies behind
// it (the bottom's green inside over the ground: about (97, 74, 69) expected, hence
// the margin of 15). Inside green: from an eye inside the teapot every wall shows its inside,
// green over the sky. The ground, in the frame's bottom corners, is blue.
TEST_F(ExactScenesTest, TheTeapotIsRedOutsideGreenInsideOnABlueGround) {
  const TranslucencySettings s = Settings("teapot");
  auto t = Make(s);
  ASSERT_TRUE(t);
  const std::vector<uint8_t> outside = Render(*t, "sorted");
  const Rgb wall = PixelAt(outside, s.width, Project(t->CameraForFrame(0), {0.2f, 0.6f, -1.0f}, s.width, s.height));
  EXPECT_GT(wall.r, wall.g + 15) << wall.r << " " << wall.g << " " << wall.b;
  EXPECT_GT(wall.r, wall.b + 15) << wall.r << " " << wall.g << " " << wall.b;
  for (glm::ivec2 corner : {glm::ivec2(1, s.height - 2), glm::ivec2(s.width - 2, s.height - 2)}) {
    const Rgb ground = PixelAt(outside, s.width, corner);
    EXPECT_GT(ground.b, 2 * ground.r) << corner.x;
    EXPECT_GT(ground.b, 2 * ground.g) << corner.x;
  }
  renderer::Camera inside;
  inside.eye = {0.2f, 0.8f, 0.0f};
  inside.viewProj = glm::perspectiveLH_ZO(glm::radians(50.0f), float(s.width) / s.height, 0.05f, 40.0f) *
                    glm::lookAtLH(inside.eye, inside.eye + glm::vec3(0, 0.3f, 1), glm::vec3(0, 1, 0));
  t->SetCameraOverride(inside);
  const std::vector<uint8_t> fromInside = Render(*t, "sorted");
  const Rgb inner = PixelAt(fromInside, s.width, {int(s.width / 2), int(s.height / 2)});
  EXPECT_GT(inner.g, inner.r + 30) << inner.r << " " << inner.g << " " << inner.b;
  EXPECT_GT(inner.g, inner.b) << inner.r << " " << inner.g << " " << inner.b;
}

// One vertex and one index buffer: every pass that draws the teapot draws all of it
// with one DrawIndexed, in every method, sorted or not (a method may have several such passes).
TEST_F(ExactScenesTest, EveryObjectPassDrawsTheWholeTeapotWithOneDrawIndexed) {
  const size_t indices = renderer::UtahTeapot(kSegments, {}).indices.size();
  const std::vector<std::string> want = {"DrawIndexed(" + std::to_string(indices) + ", 0, 0)"};
  for (const renderer::oit::MethodInfo* method : renderer::oit::Methods()) {
    rhi::Trace trace;
    ComPtr<rhi::DeviceContext> traced;
    ASSERT_EQ(rhi::CreateTracingContext(context.Get(), &trace, traced.GetAddressOf()), rhi::S_OK);
    std::string error;
    auto t = Translucency::Create(device.Get(), traced.Get(), Settings("teapot"), &error);
    ASSERT_NE(t, nullptr) << error;
    if (!t->Accepts(*method)) continue;  // the compute-tile methods draw particles only
    ASSERT_TRUE(t->RenderFrame(*method)) << t->error();
    // prefix-sum draws the teapot in two passes (count, fill), depth peeling in one a layer: each draws all of it.
    const std::vector<std::string> draws = trace.Filter({"DrawIndexed", "DrawIndexedInstanced", "DrawInstanced"});
    ASSERT_FALSE(draws.empty()) << method->name;
    for (const std::string& draw : draws) EXPECT_EQ(std::vector<std::string>{draw}, want) << method->name;
    t.reset();
    traced.Reset();
  }
}

// OVER of the quads' lit colours, far to near, over the lit wall, in 8-bit steps as
// an RGBA8 target stores each blend's result.
glm::vec3 CpuComposite(const std::vector<TriangleMesh>& quads, const glm::vec3& eye) {
  const glm::vec3 light = renderer::SceneLightDirection();
  const auto lit = [&](const glm::vec3& colour, const glm::vec3& normal) {
    return colour * (kAmbient + (1.0f - kAmbient) * std::max(0.0f, glm::dot(normal, light)));
  };
  const auto store = [](const glm::vec3& c) { return glm::round(glm::clamp(c, 0.0f, 1.0f) * 255.0f) / 255.0f; };
  const glm::vec3 facing = quads.front().normals.front();  // every quad and the wall face the eye
  glm::vec3 frame = store(lit(glm::vec3(0.5f), facing));   // the grey wall (scenes.cpp)
  std::vector<size_t> order(quads.size());
  std::iota(order.begin(), order.end(), size_t(0));
  const auto depth = [&](size_t i) { return glm::dot(quads[i].positions[0] - eye, -facing); };
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return depth(a) > depth(b); });
  for (size_t i : order) {
    const renderer::MeshMaterial& m = quads[i].material;
    frame = store(lit(m.front, facing) * m.opacity + frame * (1.0f - m.opacity));
  }
  return frame * 255.0f;
}

class ComplexityCompositeTest : public ExactScenesTest, public ::testing::WithParamInterface<uint32_t> {};

// The 3x3 pixels at the centre of the frame, inside every quad, against the CPU.
TEST_P(ComplexityCompositeTest, SortedEqualsOverCompositedOnTheCpuAtTheCentre) {
  TranslucencySettings s = Settings("complexity");
  s.depthComplexity = GetParam();
  auto t = Make(s);
  ASSERT_TRUE(t);
  const std::vector<uint8_t> image = Render(*t, "sorted");
  const renderer::QuadStack stack = renderer::ComplexityQuadStack(s);
  const glm::vec3 want = CpuComposite(renderer::CameraFacingQuads(stack), stack.eye);
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) {
      const Rgb got = PixelAt(image, s.width, {int(s.width / 2) + dx, int(s.height / 2) + dy});
      EXPECT_NEAR(got.r, want.r, 2.0) << dx << "," << dy;
      EXPECT_NEAR(got.g, want.g, 2.0) << dx << "," << dy;
      EXPECT_NEAR(got.b, want.b, 2.0) << dx << "," << dy;
    }
}

INSTANTIATE_TEST_SUITE_P(DepthComplexity, ComplexityCompositeTest, ::testing::Values(1u, 2u, 8u, 32u));

// The default stack is submitted out of depth order, so unsorted OVER is wrong where
// `sorted` is exact: the sort is what makes the reference.
TEST_F(ExactScenesTest, UnsortedOverMissesTheComplexityComposite) {
  const TranslucencySettings s = Settings("complexity");
  auto t = Make(s);
  ASSERT_TRUE(t);
  const std::vector<uint8_t> image = Render(*t, "alpha");
  const renderer::QuadStack stack = renderer::ComplexityQuadStack(s);
  const glm::vec3 want = CpuComposite(renderer::CameraFacingQuads(stack), stack.eye);
  const Rgb got = PixelAt(image, s.width, {int(s.width / 2), int(s.height / 2)});
  EXPECT_GT(std::abs(got.r - want.r) + std::abs(got.g - want.g) + std::abs(got.b - want.b), 12.0f);
}

TEST_F(ExactScenesTest, ADepthComplexityOutside1To64IsRefused) {
  for (uint32_t complexity : {0u, 65u}) {
    TranslucencySettings s = Settings("complexity");
    s.depthComplexity = complexity;
    std::string error;
    EXPECT_EQ(Translucency::Create(device.Get(), context.Get(), s, &error), nullptr);
    EXPECT_NE(error.find("depthComplexity " + std::to_string(complexity)), std::string::npos) << error;
  }
}

}  // namespace
}  // namespace rhi_test
