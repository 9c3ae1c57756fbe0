#include "objects/effect_object.h"

#include <algorithm>
#include <numeric>

namespace renderer {

using namespace rhi;

bool EffectObject::PrepareMethod(const oit::MethodInfo& method, std::string* error) {
  if (effects_.count(method.name)) return true;
  LoadedEffect e;
  e.effect = oit::LoadMethodEffect(setup_.device, method, file_, Defines(), error);
  if (!e.effect) return false;
  fx::Effect* fx = e.effect.Get();
  const float light[4] = {setup_.lightDir.x, setup_.lightDir.y, setup_.lightDir.z, 0};
  fx->GetVariableByName("LightDir")->AsVector()->SetFloatVector(light);
  e.viewProj = fx->GetVariableByName("ViewProj")->AsMatrix();
  e.eye = fx->GetVariableByName("Eye")->AsVector();
  if (!Configure(*fx, method, error)) return false;
  if (!layout_ && !CreateInputLayout(*fx, error)) return false;
  effects_.emplace(method.name, std::move(e));
  return true;
}

// From the first pass that reads vertices: a method's first pass may be a compute
// pass, or read none (the compute-tile methods' Footprints, from SV_VertexID alone).
bool EffectObject::CreateInputLayout(fx::Effect& effect, std::string* error) {
  fx::EffectTechnique* technique = effect.GetTechniqueByIndex(0);
  fx::TECHNIQUE_DESC techniqueDesc;
  if (FAILED(technique->GetDesc(&techniqueDesc))) return true;
  for (UINT i = 0; i < techniqueDesc.Passes; ++i) {
    fx::PASS_DESC desc;
    if (FAILED(technique->GetPassByIndex(i)->GetDesc(&desc)) || desc.IAInputSignatureSize == 0) continue;
    if (SUCCEEDED(setup_.device->CreateInputLayout(layoutElements_.data(), UINT(layoutElements_.size()),
                                                   desc.pIAInputSignature, desc.IAInputSignatureSize,
                                                   layout_.GetAddressOf())))
      return true;
    *error = std::string(file_) + ": creating the input layout failed";
    return false;
  }
  return true;  // no pass of this method reads vertices: a later method's makes the layout
}

void EffectObject::SetCamera(LoadedEffect& e, const Camera& camera) {
  e.viewProj->SetMatrixTranspose(&camera.viewProj[0][0]);  // GLM stores columns: FX11's row-major, transposed
  const float eye[4] = {camera.eye.x, camera.eye.y, camera.eye.z, 0};
  e.eye->SetFloatVector(eye);
  SetInverseViewProj(e.effect.Get(), camera);
}

fx::EffectPass* EffectObject::PassForFrame(const oit::MethodInfo& method, const Camera& camera, const char* pass,
                                           std::string* error) {
  LoadedEffect& e = effects_.at(method.name);
  fx::EffectPass* p = FindPass(e.effect.Get(), nullptr, pass, error);
  if (!p) return nullptr;
  SetCamera(e, camera);
  SetFrameVariables(*e.effect.Get());
  return p;
}

bool EffectObject::DrawFullscreen(DeviceContext* context, const oit::MethodInfo& method, const Camera& camera,
                                  const oit::FrameDesc& frame, const char* pass, std::string* error) {
  if (Empty()) return true;
  LoadedEffect& e = effects_.at(method.name);
  SetCamera(e, camera);
  SetFrameVariables(*e.effect.Get());
  return DrawFullscreenPass(context, e.effect.Get(), frame, nullptr, pass, error);
}

bool EffectObject::Dispatch(DeviceContext* context, const oit::MethodInfo& method, const Camera& camera,
                            const oit::FrameDesc& frame, const char* pass, uint32_t x, uint32_t y, uint32_t z,
                            std::string* error) {
  if (Empty()) return true;
  fx::EffectPass* p = PassForFrame(method, camera, pass, error);
  if (!p) return false;
  const float size[4] = {float(frame.width), float(frame.height), 0, 0};
  effects_.at(method.name).effect->GetVariableByName("FrameSize")->AsVector()->SetFloatVector(size);
  p->Apply(0, context);
  context->Dispatch(x, y, z);
  return true;
}

bool EffectObject::CreateBuffer(UINT size, USAGE usage, UINT bind, const void* data, ComPtr<Buffer>* out) const {
  // A raw view needs RESOURCE_MISC_BUFFER_ALLOW_RAW_VIEWS on its buffer.
  const UINT misc = (bind & BIND_SHADER_RESOURCE) ? UINT(RESOURCE_MISC_BUFFER_ALLOW_RAW_VIEWS) : 0u;
  BUFFER_DESC d{size, usage, bind, 0, misc, 0};
  SUBRESOURCE_DATA init{data, 0, 0};
  return SUCCEEDED(setup_.device->CreateBuffer(&d, data ? &init : nullptr, out->GetAddressOf()));
}

float ViewDepth(const Camera& camera, const glm::vec3& position) {
  const glm::vec3 forward =
      glm::normalize(glm::vec3(camera.viewProj[0][3], camera.viewProj[1][3], camera.viewProj[2][3]));
  return glm::dot(position - camera.eye, forward);
}

std::vector<uint32_t> BackToFrontOrder(const std::vector<float>& depths) {
  std::vector<uint32_t> order(depths.size());
  std::iota(order.begin(), order.end(), 0u);
  std::stable_sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) { return depths[a] > depths[b]; });
  return order;
}

}  // namespace renderer
