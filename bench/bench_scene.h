// The scene both halves of rhi_bench record: one D3D11-style command stream,
// described once so the RHI fixture and the raw-Vulkan fixture cannot drift.
//
// Per draw i (kDrawsPerBatch draws per batch, into one 64x64 RGBA8 target):
//   blend variant   i & 1         (opaque / constant-colour blend, with a blend factor)
//   shader pair     (i >> 1) & 1  (VS+PS pair; the RHI also switches depth-stencil state
//                                  and stencil ref with it)
//   vertex buffer   i & 1
//   constant buffer (i >> 1) & 1  (VS b0)
//   Draw(3, 0)
// The (blend, pair) combination cycles 00, 10, 01, 11, so the pipeline changes on
// every draw: the RHI hits its pipeline cache every draw (4 pipelines, built in warm-up).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace bench {

inline constexpr uint32_t kTargetSize = 64;
inline constexpr int kDrawsPerBatch = 1000;

struct DrawChoice {
  int blend;   // 0: opaque, 1: blend by constant colour
  int pair;    // shader pair (and RHI depth-stencil state / stencil ref)
  int vb;      // vertex buffer
  int cb;      // constant buffer bound to VS b0
};
inline constexpr DrawChoice ChoiceFor(int i) { return {i & 1, (i >> 1) & 1, i & 1, (i >> 1) & 1}; }

struct Vertex {
  float x, y;
};
inline constexpr uint32_t kVertexStride = sizeof(Vertex);
// Two triangles in D3D clip space (clockwise on screen: D3D11 front faces).
inline constexpr Vertex kTriangles[2][3] = {
    {{-0.8f, -0.8f}, {-0.8f, 0.8f}, {0.8f, -0.8f}},
    {{-0.5f, -0.5f}, {0.0f, 0.5f}, {0.5f, -0.5f}},
};

struct DrawConstants {
  float offset[4];  // xy: translation, zw: scale (pair 1)
  float color[4];
};
inline constexpr DrawConstants kConstants[2] = {
    {{0.0f, 0.0f, 1.0f, 1.0f}, {1.0f, 0.0f, 0.0f, 1.0f}},
    {{0.1f, -0.1f, 0.5f, 0.5f}, {0.0f, 1.0f, 0.0f, 0.5f}},
};

inline constexpr float kBlendFactors[2][4] = {{1.0f, 1.0f, 1.0f, 1.0f}, {0.5f, 0.25f, 0.75f, 1.0f}};
inline constexpr uint32_t kStencilRefs[2] = {0x00, 0x80};

// SPIR-V of the two shader pairs, as the hlsl_compiler module emits it (HLSL
// semantics still attached as UserSemantic decorations).
struct SceneShaders {
  std::vector<uint32_t> vs[2];
  std::vector<uint32_t> ps[2];
};
// Compiles the scene's HLSL; on a compile error prints it and exits.
SceneShaders CompileSceneShaders();

}  // namespace bench
