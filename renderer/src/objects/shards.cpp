// The instanced glass shards of document 000: one irregular shard mesh and
// per-instance world matrices and tints, drawn with one DrawIndexedInstanced
// through shaders_hlsl/shards.fx, built once per transparency method.
#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "fx/effect.h"
#include "objects/effect_object.h"
#include "random.h"
#include "renderer/effect_files.h"

namespace renderer {
namespace {

using namespace rhi;

struct ShardVertex {
  glm::vec3 position, normal;
};

struct ShardInstance {
  glm::vec4 world[4];  // columns
  glm::vec4 tint;      // rgb transmission, a alpha
};
static_assert(sizeof(ShardInstance) == 80);

// An irregular shard: a jittered hexagon pushed into a thin double pyramid, flat-shaded.
std::vector<ShardVertex> ShardMesh(uint32_t seed) {
  constexpr int kSides = 6;
  glm::vec3 rim[kSides];
  for (int i = 0; i < kSides; ++i) {
    float angle = 6.2831853f * (i + 0.6f * (Random(seed, 10, i) - 0.5f)) / kSides;
    float radius = 0.5f + 0.5f * Random(seed, 11, i);
    rim[i] = {radius * std::cos(angle), radius * std::sin(angle) * 1.4f, 0.05f * (Random(seed, 12, i) - 0.5f)};
  }
  const glm::vec3 front{0.1f, 0.05f, 0.12f}, back{-0.05f, 0.1f, -0.08f};
  std::vector<ShardVertex> v;
  for (int i = 0; i < kSides; ++i) {
    glm::vec3 a = rim[i], b = rim[(i + 1) % kSides];
    for (glm::vec3 apex : {front, back}) {
      glm::vec3 n = glm::normalize(glm::cross(b - a, apex - a));
      v.push_back({a, n});
      v.push_back({b, n});
      v.push_back({apex, n});
    }
  }
  return v;
}

std::vector<ShardInstance> ShardInstances(uint32_t seed, const ShardSettings& s) {
  const glm::vec3 tints[6] = {{1.0f, 0.2f, 0.15f}, {0.2f, 0.95f, 0.3f}, {0.2f, 0.4f, 1.0f},
                              {1.0f, 0.75f, 0.15f}, {0.2f, 0.9f, 0.95f}, {0.95f, 0.25f, 0.9f}};
  std::vector<ShardInstance> out(s.count);
  for (uint32_t i = 0; i < s.count; ++i) {
    auto r = [&](uint32_t stream) { return Random(seed, 100 + stream, i); };
    glm::vec3 position{-3.5f + 7.0f * r(0), 0.2f + 3.6f * r(1), -2.5f + 5.0f * r(2)};
    glm::vec3 axis = glm::normalize(glm::vec3(r(3) - 0.5f, r(4) - 0.5f, r(5) - 0.5f) + glm::vec3(1e-3f));
    float angle = 6.2831853f * r(6);
    float scale = 0.12f + 0.18f * r(7);
    glm::mat4 world = glm::translate(glm::mat4(1.0f), position) * glm::rotate(glm::mat4(1.0f), angle, axis) *
                      glm::scale(glm::mat4(1.0f), glm::vec3(scale));
    for (int c = 0; c < 4; ++c) out[i].world[c] = world[c];
    glm::vec3 tint = s.allRed ? glm::vec3(1.0f, 0.15f, 0.15f) : tints[std::min(5u, uint32_t(r(8) * 6))];
    out[i].tint = glm::vec4(tint, 0.2f + 0.2f * r(9));
  }
  return out;
}

class Shards final : public EffectObject {
 public:
  Shards(const ObjectSetup& setup, const ShardSettings& settings)
      : EffectObject(setup, "shards.fx",
                     {{"POSITION", 0, DXGI_FORMAT_R32G32B32_FLOAT, 0, 0, INPUT_PER_VERTEX_DATA, 0},
                      {"NORMAL", 0, DXGI_FORMAT_R32G32B32_FLOAT, 0, 12, INPUT_PER_VERTEX_DATA, 0},
                      {"WORLD", 0, DXGI_FORMAT_R32G32B32A32_FLOAT, 1, 0, INPUT_PER_INSTANCE_DATA, 1},
                      {"WORLD", 1, DXGI_FORMAT_R32G32B32A32_FLOAT, 1, 16, INPUT_PER_INSTANCE_DATA, 1},
                      {"WORLD", 2, DXGI_FORMAT_R32G32B32A32_FLOAT, 1, 32, INPUT_PER_INSTANCE_DATA, 1},
                      {"WORLD", 3, DXGI_FORMAT_R32G32B32A32_FLOAT, 1, 48, INPUT_PER_INSTANCE_DATA, 1},
                      {"TINT", 0, DXGI_FORMAT_R32G32B32A32_FLOAT, 1, 64, INPUT_PER_INSTANCE_DATA, 1}}),
        settings_(settings) {}

  bool Initialize(std::string* error) {
    std::vector<ShardVertex> mesh = ShardMesh(setup_.seed);
    std::vector<uint16_t> indices(mesh.size());
    std::iota(indices.begin(), indices.end(), uint16_t(0));
    indexCount_ = UINT(indices.size());
    instances_ = ShardInstances(setup_.seed, settings_);
    const UINT instanceBytes = UINT(std::max<size_t>(1, instances_.size()) * sizeof(ShardInstance));
    // The buffers deferred shading reads (ShadeTriangle) also get raw views.
    const UINT raw = BIND_SHADER_RESOURCE;
    const UINT vertexBytes = UINT(mesh.size() * sizeof(ShardVertex)), indexBytes = UINT(indices.size() * 2);
    if (!CreateBuffer(vertexBytes, USAGE_IMMUTABLE, BIND_VERTEX_BUFFER | raw, mesh.data(), &vertices_) ||
        !CreateBuffer(indexBytes, USAGE_IMMUTABLE, BIND_INDEX_BUFFER | raw, indices.data(), &indices_) ||
        !CreateBuffer(instanceBytes, USAGE_DEFAULT, BIND_VERTEX_BUFFER | raw,
                      instances_.empty() ? nullptr : instances_.data(), &instanceBuffer_) ||
        !CreateBuffer(instanceBytes, USAGE_DEFAULT, BIND_VERTEX_BUFFER, nullptr, &sortedInstances_) ||
        !CreateRawView(setup_.device, vertices_.Get(), vertexBytes, &vertexView_) ||
        !CreateRawView(setup_.device, indices_.Get(), indexBytes, &indexView_) ||
        !CreateRawView(setup_.device, instanceBuffer_.Get(), instanceBytes, &instanceView_)) {
      *error = "shards: creating the buffers failed";
      return false;
    }
    return true;
  }

  bool Draw(DeviceContext* ctx, const oit::MethodInfo& method, const Camera& camera, const char* pass,
            oit::DrawOrder order, std::string* error) override {
    if (Empty()) return true;
    fx::EffectPass* p = PassForFrame(method, camera, pass, error);
    if (!p) return false;
    Buffer* instances =
        order == oit::DrawOrder::BackToFront ? SortBackToFront(ctx, camera) : instanceBuffer_.Get();
    Buffer* vbs[2] = {vertices_.Get(), instances};
    UINT strides[2] = {sizeof(ShardVertex), sizeof(ShardInstance)}, offsets[2] = {0, 0};
    ctx->IASetInputLayout(layout_.Get());
    ctx->IASetVertexBuffers(0, 2, vbs, strides, offsets);
    ctx->IASetIndexBuffer(indices_.Get(), DXGI_FORMAT_R16_UINT, 0);
    ctx->IASetPrimitiveTopology(PRIMITIVE_TOPOLOGY_TRIANGLELIST);
    p->Apply(0, ctx);
    ctx->DrawIndexedInstanced(indexCount_, UINT(instances_.size()), 0, 0, 0);
    return true;
  }

 private:
  // The raw views ShadeTriangle reads; the ids are of the unsorted instance buffer,
  // which the deferred passes draw.
  bool Configure(fx::Effect& effect, const oit::MethodInfo&, std::string*) override {
    effect.GetVariableByName("SurfaceTint")->AsScalar()->SetFloat(settings_.surfaceTint);
    effect.GetVariableByName("TrianglesPerShard")->AsScalar()->SetInt(int(indexCount_ / 3));
    effect.GetVariableByName("ShardVertices")->AsShaderResource()->SetResource(vertexView_.Get());
    effect.GetVariableByName("ShardIndices")->AsShaderResource()->SetResource(indexView_.Get());
    effect.GetVariableByName("ShardInstances")->AsShaderResource()->SetResource(instanceView_.Get());
    return true;
  }
  bool Empty() const override { return instances_.empty(); }

  // The reference order: instances reordered back to front by the view depth of
  // their centre (stable, so ties keep their order); returns their buffer.
  Buffer* SortBackToFront(DeviceContext* ctx, const Camera& camera) {
    std::vector<float> depth(instances_.size());
    for (size_t i = 0; i < depth.size(); ++i) depth[i] = ViewDepth(camera, glm::vec3(instances_[i].world[3]));
    const std::vector<uint32_t> order = BackToFrontOrder(depth);
    std::vector<ShardInstance> sorted(order.size());
    for (size_t i = 0; i < order.size(); ++i) sorted[i] = instances_[order[i]];
    ctx->UpdateSubresource(sortedInstances_.Get(), 0, nullptr, sorted.data(), 0, 0);
    return sortedInstances_.Get();
  }

  ShardSettings settings_;
  UINT indexCount_ = 0;
  std::vector<ShardInstance> instances_;
  ComPtr<Buffer> vertices_, indices_, instanceBuffer_, sortedInstances_;
  ComPtr<ShaderResourceView> vertexView_, indexView_, instanceView_;  // raw, for ShadeTriangle
};

}  // namespace

std::unique_ptr<TranslucentObject> CreateShards(const ObjectSetup& setup, const ShardSettings& shards,
                                                std::string* error) {
  auto object = std::make_unique<Shards>(setup, shards);
  if (!object->Initialize(error)) return nullptr;
  return object;
}

}  // namespace renderer
