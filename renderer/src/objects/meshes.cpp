// Translucent triangle meshes (renderer/meshes.h): any number of meshes in one
// vertex and one index buffer, each vertex carrying its mesh's material, drawn with
// one DrawIndexed through shaders_hlsl/meshes.fx, built once per transparency method.
//
// Back to front (the `sorted` reference) sorts the triangles by the view depth of
// their centroids and draws them in that order from an index buffer uploaded each
// frame. That is the exact OVER order only where triangles neither intersect nor
// overlap cyclically: the teapot's spout and handle pass through its body, so there
// `sorted` is a per-triangle approximation of the reference; the complexity scene's
// quads are parallel and perpendicular to the view axis, where it is exact.
#include <algorithm>
#include <map>
#include <numeric>
#include <vector>

#include "fx/effect.h"
#include "objects/effect_object.h"
#include "renderer/effect_files.h"

namespace renderer {
namespace {

using namespace rhi;

struct MeshVertex {
  glm::vec3 position, normal, front, back;
  float opacity;
  glm::vec3 transmission;
};
static_assert(sizeof(MeshVertex) == 64);

class Meshes final : public EffectObject {
 public:
  explicit Meshes(const ObjectSetup& setup)
      : EffectObject(setup, "meshes.fx",
                     {{"POSITION", 0, DXGI_FORMAT_R32G32B32_FLOAT, 0, 0, INPUT_PER_VERTEX_DATA, 0},
                      {"NORMAL", 0, DXGI_FORMAT_R32G32B32_FLOAT, 0, 12, INPUT_PER_VERTEX_DATA, 0},
                      {"FRONTCOLOR", 0, DXGI_FORMAT_R32G32B32_FLOAT, 0, 24, INPUT_PER_VERTEX_DATA, 0},
                      {"BACKCOLOR", 0, DXGI_FORMAT_R32G32B32_FLOAT, 0, 36, INPUT_PER_VERTEX_DATA, 0},
                      {"OPACITY", 0, DXGI_FORMAT_R32_FLOAT, 0, 48, INPUT_PER_VERTEX_DATA, 0},
                      {"TRANSMISSION", 0, DXGI_FORMAT_R32G32B32_FLOAT, 0, 52, INPUT_PER_VERTEX_DATA, 0}}) {}

  bool Initialize(const std::vector<TriangleMesh>& meshes, std::string* error) {
    for (const TriangleMesh& mesh : meshes) Append(mesh);
    if (indices_.empty()) return true;
    // The buffers deferred shading reads (ShadeTriangle) also get raw views.
    const UINT indexBytes = UINT(indices_.size() * sizeof(uint32_t));
    const UINT vertexBytes = UINT(vertices_.size() * sizeof(MeshVertex));
    if (!CreateBuffer(vertexBytes, USAGE_IMMUTABLE, BIND_VERTEX_BUFFER | BIND_SHADER_RESOURCE, vertices_.data(),
                      &vertexBuffer_) ||
        !CreateBuffer(indexBytes, USAGE_IMMUTABLE, BIND_INDEX_BUFFER | BIND_SHADER_RESOURCE, indices_.data(),
                      &indexBuffer_) ||
        !CreateBuffer(indexBytes, USAGE_DEFAULT, BIND_INDEX_BUFFER, nullptr, &sortedIndexBuffer_) ||
        !CreateRawView(setup_.device, vertexBuffer_.Get(), vertexBytes, &vertexView_) ||
        !CreateRawView(setup_.device, indexBuffer_.Get(), indexBytes, &indexView_)) {
      *error = "meshes: creating the buffers failed";
      return false;
    }
    return true;
  }

  bool Draw(DeviceContext* ctx, const oit::MethodInfo& method, const Camera& camera, const char* pass,
            oit::DrawOrder order, std::string* error) override {
    if (Empty()) return true;
    fx::EffectPass* p = PassForFrame(method, camera, pass, error);
    if (!p) return false;
    Buffer* indices = order == oit::DrawOrder::BackToFront ? SortBackToFront(ctx, camera) : indexBuffer_.Get();
    Buffer* vb = vertexBuffer_.Get();
    const UINT stride = sizeof(MeshVertex), offset = 0;
    ctx->IASetInputLayout(layout_.Get());
    ctx->IASetVertexBuffers(0, 1, &vb, &stride, &offset);
    ctx->IASetIndexBuffer(indices, DXGI_FORMAT_R32_UINT, 0);
    ctx->IASetPrimitiveTopology(PRIMITIVE_TOPOLOGY_TRIANGLELIST);
    p->Apply(0, ctx);
    ctx->DrawIndexed(UINT(indices_.size()), 0, 0);
    return true;
  }

 private:
  // The raw views ShadeTriangle reads; the ids are of the unsorted index buffer,
  // which the deferred passes draw.
  bool Configure(fx::Effect& effect, const oit::MethodInfo&, std::string*) override {
    effect.GetVariableByName("MeshVertices")->AsShaderResource()->SetResource(vertexView_.Get());
    effect.GetVariableByName("MeshIndices")->AsShaderResource()->SetResource(indexView_.Get());
    return true;
  }
  bool Empty() const override { return indices_.empty(); }

  void Append(const TriangleMesh& mesh) {
    const uint32_t base = uint32_t(vertices_.size());
    const MeshMaterial& m = mesh.material;
    for (size_t i = 0; i < mesh.positions.size(); ++i)
      vertices_.push_back({mesh.positions[i], mesh.normals[i], m.front, m.back, m.opacity, m.transmission});
    for (uint32_t index : mesh.indices) indices_.push_back(base + index);
  }

  // The triangles reordered back to front by the view depth of their centroids
  // (stable: ties keep submission order); returns the index buffer holding them.
  Buffer* SortBackToFront(DeviceContext* ctx, const Camera& camera) {
    const size_t triangles = indices_.size() / 3;
    std::vector<float> depth(triangles);
    for (size_t t = 0; t < triangles; ++t) {
      const glm::vec3 centroid = (vertices_[indices_[3 * t]].position + vertices_[indices_[3 * t + 1]].position +
                                  vertices_[indices_[3 * t + 2]].position) /
                                 3.0f;
      depth[t] = ViewDepth(camera, centroid);
    }
    std::vector<uint32_t> sorted;
    sorted.reserve(indices_.size());
    for (uint32_t t : BackToFrontOrder(depth)) sorted.insert(sorted.end(), &indices_[3 * t], &indices_[3 * t] + 3);
    ctx->UpdateSubresource(sortedIndexBuffer_.Get(), 0, nullptr, sorted.data(), 0, 0);
    return sortedIndexBuffer_.Get();
  }

  std::vector<MeshVertex> vertices_;
  std::vector<uint32_t> indices_;
  ComPtr<Buffer> vertexBuffer_, indexBuffer_, sortedIndexBuffer_;
  ComPtr<ShaderResourceView> vertexView_, indexView_;  // raw, for ShadeTriangle
};

}  // namespace

std::unique_ptr<TranslucentObject> CreateMeshes(const ObjectSetup& setup, const std::vector<TriangleMesh>& meshes,
                                                std::string* error) {
  auto object = std::make_unique<Meshes>(setup);
  if (!object->Initialize(meshes, error)) return nullptr;
  return object;
}

}  // namespace renderer
