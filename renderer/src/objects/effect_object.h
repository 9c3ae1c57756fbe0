// What every translucent object shares: its shader file built once per
// transparency method (oit::LoadMethodEffect), the variables each frame sets in
// it (the camera, and the inverse for deferred shading), the input layout of its
// vertex shader, the deferred resolve's full-screen pass, and the reference
// (back-to-front) order.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "fx/effect.h"
#include "objects/objects.h"
#include "renderer/effect_files.h"

namespace renderer {

class EffectObject : public TranslucentObject {
 public:
  const char* Name() const override { return file_; }
  fx::Effect* MethodEffect(const oit::MethodInfo& method) override { return effects_.at(method.name).effect.Get(); }
  // Loads the file for `method` once, sets LightDir and what Configure sets, and
  // makes the input layout from the first effect's vertex shader.
  bool PrepareMethod(const oit::MethodInfo& method, std::string* error) override;
  // The resolve of deferred shading: the method's pass `pass` on a full-screen triangle.
  bool DrawFullscreen(rhi::DeviceContext* context, const oit::MethodInfo& method, const Camera& camera,
                      const oit::FrameDesc& frame, const char* pass, std::string* error) override;
  // A method's compute pass over the object's buffers (as the resolve).
  bool Dispatch(rhi::DeviceContext* context, const oit::MethodInfo& method, const Camera& camera,
                const oit::FrameDesc& frame, const char* pass, uint32_t x, uint32_t y, uint32_t z,
                std::string* error) override;

 protected:
  EffectObject(const ObjectSetup& setup, const char* file, std::vector<rhi::INPUT_ELEMENT_DESC> layout)
      : setup_(setup), file_(file), layoutElements_(std::move(layout)) {}
  // The defines the file is built with besides OIT_METHOD.
  virtual EffectDefines Defines() const { return {}; }
  // The object's constants and buffers in a freshly loaded effect; also where it
  // prepares what `method` needs of it (the sorted copy of a back-to-front method).
  virtual bool Configure(fx::Effect& effect, const oit::MethodInfo& method, std::string* error) = 0;
  // Variables that change from frame to frame besides the camera.
  virtual void SetFrameVariables(fx::Effect& /*effect*/) {}
  // True when there is nothing to draw (no instances, no triangles).
  virtual bool Empty() const { return false; }

  // The pass `pass` of `method`'s effect with the frame's variables set; null (and
  // `error`) when the effect has no such pass.
  fx::EffectPass* PassForFrame(const oit::MethodInfo& method, const Camera& camera, const char* pass,
                               std::string* error);
  // A buffer; one bound as a shader resource may be viewed raw (ShadeTriangle's reads).
  bool CreateBuffer(rhi::UINT size, rhi::USAGE usage, rhi::UINT bind, const void* data,
                    rhi::ComPtr<rhi::Buffer>* out) const;

  const ObjectSetup setup_;
  rhi::ComPtr<rhi::InputLayout> layout_;

 private:
  struct LoadedEffect {
    rhi::ComPtr<fx::Effect> effect;
    fx::EffectMatrixVariable* viewProj = nullptr;
    fx::EffectVectorVariable* eye = nullptr;
  };
  void SetCamera(LoadedEffect& e, const Camera& camera);
  bool CreateInputLayout(fx::Effect& effect, std::string* error);

  const char* file_;
  std::vector<rhi::INPUT_ELEMENT_DESC> layoutElements_;
  std::map<std::string, LoadedEffect> effects_;  // by method name
};

// The view depth of `position` from `camera` (along its forward axis, the w row of
// its view-projection).
float ViewDepth(const Camera& camera, const glm::vec3& position);
// The indices of `depths` from the farthest to the nearest, stable (ties keep their
// order): the reference order of the sorted method.
std::vector<uint32_t> BackToFrontOrder(const std::vector<float>& depths);

}  // namespace renderer
