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
#include "objects/objects.h"
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

// meshes.fx built for one method, with the variables a frame sets.
struct MeshEffect {
  ComPtr<fx::Effect> effect;
  fx::EffectMatrixVariable* viewProj = nullptr;
  fx::EffectVectorVariable* eye = nullptr;
};

class Meshes final : public TranslucentObject {
 public:
  explicit Meshes(const ObjectSetup& setup) : setup_(setup) {}

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

  const char* Name() const override { return "meshes.fx"; }

  fx::Effect* MethodEffect(const oit::MethodInfo& method) override { return effects_.at(method.name).effect.Get(); }

  bool PrepareMethod(const oit::MethodInfo& method, std::string* error) override {
    if (effects_.count(method.name)) return true;
    MeshEffect e;
    e.effect = oit::LoadMethodEffect(setup_.device, method, "meshes.fx", {}, error);
    if (!e.effect) return false;
    fx::Effect* fx = e.effect.Get();
    const float light[4] = {setup_.lightDir.x, setup_.lightDir.y, setup_.lightDir.z, 0};
    fx->GetVariableByName("LightDir")->AsVector()->SetFloatVector(light);
    e.viewProj = fx->GetVariableByName("ViewProj")->AsMatrix();
    e.eye = fx->GetVariableByName("Eye")->AsVector();
    fx->GetVariableByName("MeshVertices")->AsShaderResource()->SetResource(vertexView_.Get());
    fx->GetVariableByName("MeshIndices")->AsShaderResource()->SetResource(indexView_.Get());
    if (!layout_ && !CreateLayout(fx, error)) return false;
    effects_.emplace(method.name, std::move(e));
    return true;
  }

  bool Draw(DeviceContext* ctx, const oit::MethodInfo& method, const Camera& camera, const char* pass,
            oit::DrawOrder order, std::string* error) override {
    if (indices_.empty()) return true;
    MeshEffect& e = effects_.at(method.name);
    fx::EffectPass* p = FindPass(e.effect.Get(), nullptr, pass, error);
    if (!p) return false;
    SetCamera(e, camera);
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


  // The raw views ShadeTriangle reads were set with the effect; the ids are of the
  // unsorted index buffer, which the deferred passes draw.
  bool DrawFullscreen(DeviceContext* ctx, const oit::MethodInfo& method, const Camera& camera,
                      const oit::FrameDesc& frame, const char* pass, std::string* error) override {
    if (indices_.empty()) return true;
    MeshEffect& e = effects_.at(method.name);
    SetCamera(e, camera);
    return DrawFullscreenPass(ctx, e.effect.Get(), frame, pass, error);
  }

 private:
  static void SetCamera(MeshEffect& e, const Camera& camera) {
    e.viewProj->SetMatrixTranspose(&camera.viewProj[0][0]);  // GLM stores columns: FX11's row-major, transposed
    const float eye[4] = {camera.eye.x, camera.eye.y, camera.eye.z, 0};
    e.eye->SetFloatVector(eye);
    SetInverseViewProj(e.effect.Get(), camera);
  }

  void Append(const TriangleMesh& mesh) {
    const uint32_t base = uint32_t(vertices_.size());
    const MeshMaterial& m = mesh.material;
    for (size_t i = 0; i < mesh.positions.size(); ++i)
      vertices_.push_back({mesh.positions[i], mesh.normals[i], m.front, m.back, m.opacity, m.transmission});
    for (uint32_t index : mesh.indices) indices_.push_back(base + index);
  }

  bool CreateBuffer(UINT size, USAGE usage, UINT bind, const void* data, ComPtr<Buffer>* out) {
    // A raw view needs RESOURCE_MISC_BUFFER_ALLOW_RAW_VIEWS on its buffer.
    const UINT misc = (bind & BIND_SHADER_RESOURCE) ? UINT(RESOURCE_MISC_BUFFER_ALLOW_RAW_VIEWS) : 0u;
    BUFFER_DESC d{size, usage, bind, 0, misc, 0};
    SUBRESOURCE_DATA init{data, 0, 0};
    return SUCCEEDED(setup_.device->CreateBuffer(&d, data ? &init : nullptr, out->GetAddressOf()));
  }

  bool CreateLayout(fx::Effect* effect, std::string* error) {
    const INPUT_ELEMENT_DESC elements[] = {
        {"POSITION", 0, DXGI_FORMAT_R32G32B32_FLOAT, 0, 0, INPUT_PER_VERTEX_DATA, 0},
        {"NORMAL", 0, DXGI_FORMAT_R32G32B32_FLOAT, 0, 12, INPUT_PER_VERTEX_DATA, 0},
        {"FRONTCOLOR", 0, DXGI_FORMAT_R32G32B32_FLOAT, 0, 24, INPUT_PER_VERTEX_DATA, 0},
        {"BACKCOLOR", 0, DXGI_FORMAT_R32G32B32_FLOAT, 0, 36, INPUT_PER_VERTEX_DATA, 0},
        {"OPACITY", 0, DXGI_FORMAT_R32_FLOAT, 0, 48, INPUT_PER_VERTEX_DATA, 0},
        {"TRANSMISSION", 0, DXGI_FORMAT_R32G32B32_FLOAT, 0, 52, INPUT_PER_VERTEX_DATA, 0}};
    fx::PASS_DESC desc;
    if (FAILED(effect->GetTechniqueByIndex(0)->GetPassByIndex(0)->GetDesc(&desc)) ||
        FAILED(setup_.device->CreateInputLayout(elements, 6, desc.pIAInputSignature, desc.IAInputSignatureSize,
                                                layout_.GetAddressOf()))) {
      *error = "meshes: creating the input layout failed";
      return false;
    }
    return true;
  }

  // The triangles reordered back to front by the view depth of their centroids
  // (stable: ties keep submission order); returns the index buffer holding them.
  Buffer* SortBackToFront(DeviceContext* ctx, const Camera& camera) {
    const glm::vec3 forward =
        glm::normalize(glm::vec3(camera.viewProj[0][3], camera.viewProj[1][3], camera.viewProj[2][3]));  // w row
    const size_t triangles = indices_.size() / 3;
    std::vector<float> depth(triangles);
    for (size_t t = 0; t < triangles; ++t) {
      const glm::vec3 centroid = (vertices_[indices_[3 * t]].position + vertices_[indices_[3 * t + 1]].position +
                                  vertices_[indices_[3 * t + 2]].position) /
                                 3.0f;
      depth[t] = glm::dot(centroid - camera.eye, forward);
    }
    std::vector<uint32_t> order(triangles);
    std::iota(order.begin(), order.end(), 0u);
    std::stable_sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) { return depth[a] > depth[b]; });
    std::vector<uint32_t> sorted;
    sorted.reserve(indices_.size());
    for (uint32_t t : order) sorted.insert(sorted.end(), &indices_[3 * t], &indices_[3 * t] + 3);
    ctx->UpdateSubresource(sortedIndexBuffer_.Get(), 0, nullptr, sorted.data(), 0, 0);
    return sortedIndexBuffer_.Get();
  }

  ObjectSetup setup_;
  std::vector<MeshVertex> vertices_;
  std::vector<uint32_t> indices_;
  ComPtr<Buffer> vertexBuffer_, indexBuffer_, sortedIndexBuffer_;
  ComPtr<ShaderResourceView> vertexView_, indexView_;  // raw, for ShadeTriangle
  ComPtr<InputLayout> layout_;
  std::map<std::string, MeshEffect> effects_;  // by method name
};

}  // namespace

std::unique_ptr<TranslucentObject> CreateMeshes(const ObjectSetup& setup, const std::vector<TriangleMesh>& meshes,
                                                std::string* error) {
  auto object = std::make_unique<Meshes>(setup);
  if (!object->Initialize(meshes, error)) return nullptr;
  return object;
}

}  // namespace renderer
