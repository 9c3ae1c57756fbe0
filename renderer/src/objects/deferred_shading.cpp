// What the objects share for deferred shading (objects.h).
#include "objects/objects.h"
#include "renderer/effect_files.h"

namespace renderer {

bool CreateRawView(rhi::Device* device, rhi::Buffer* buffer, uint32_t bytes,
                   rhi::ComPtr<rhi::ShaderResourceView>* out) {
  rhi::SHADER_RESOURCE_VIEW_DESC desc{};
  desc.Format = rhi::DXGI_FORMAT_R32_TYPELESS;
  desc.ViewDimension = rhi::SRV_DIMENSION_BUFFEREX;
  desc.BufferEx = {0, bytes / 4, rhi::BUFFEREX_SRV_FLAG_RAW};
  return rhi::SUCCEEDED(device->CreateShaderResourceView(buffer, &desc, out->GetAddressOf()));
}

void SetInverseViewProj(fx::Effect* effect, const Camera& camera) {
  const glm::mat4 inverse = glm::inverse(camera.viewProj);
  effect->GetVariableByName("InvViewProj")->AsMatrix()->SetMatrixTranspose(&inverse[0][0]);  // GLM: columns
}

bool DrawFullscreenPass(rhi::DeviceContext* context, fx::Effect* effect, const oit::FrameDesc& frame,
                        const char* technique, const char* pass, std::string* error) {
  fx::EffectPass* p = FindPass(effect, technique, pass, error);
  if (!p) return false;
  const float size[4] = {float(frame.width), float(frame.height), 0, 0};
  effect->GetVariableByName("FrameSize")->AsVector()->SetFloatVector(size);
  context->IASetInputLayout(nullptr);
  context->IASetPrimitiveTopology(rhi::PRIMITIVE_TOPOLOGY_TRIANGLELIST);
  p->Apply(0, context);
  context->Draw(3, 0);
  return true;
}

}  // namespace renderer
