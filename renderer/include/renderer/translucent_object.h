// A unit of translucent geometry (the smoke, the flames, the glass shards):
// what a transparency method's passes draw. An object owns its buffers and its
// shader file (shaders_hlsl/<object>.fx, which includes the method's include),
// and builds one effect per method it is drawn with. Scenes (renderer/scenes.h)
// are lists of objects over the opaque backdrop.
#pragma once

#include <cstdint>
#include <string>

#include "fx/effect.h"
#include "renderer/oit/method.h"
#include "renderer/particle_system.h"
#include "rhi/rhi.h"

namespace fx {
class Effect;
}

namespace renderer {

class TranslucentObject {
 public:
  virtual ~TranslucentObject() = default;
  // "smoke.fx": for messages.
  virtual const char* Name() const = 0;
  // Builds the object's effect for `method`; once per method, before its first Draw.
  virtual bool PrepareMethod(const oit::MethodInfo& method, std::string* error) = 0;
  // That effect (after PrepareMethod), for the variables a method sets in it.
  virtual fx::Effect* MethodEffect(const oit::MethodInfo& method) = 0;
  // The object's passes that precede every transparency pass (the particle update
  // pass); with countLive, LiveCount() then gives what it left alive.
  virtual void Update(rhi::DeviceContext* /*context*/, bool /*countLive*/) {}
  // Draws the object with the pass `pass` of `method`'s technique; false (and
  // `error`) when its effect for the method has no such pass.
  virtual bool Draw(rhi::DeviceContext* context, const oit::MethodInfo& method, const Camera& camera,
                    const char* pass, oit::DrawOrder order, std::string* error) = 0;
  // Draws a full-screen triangle with the pass `pass` of `method`'s technique (a
  // deferred resolve over a frame of size `frame`), with what the object's
  // ShadeTriangle reads bound (oit/common.fxh); false (and `error`) when its effect
  // for the method has no such pass.
  virtual bool DrawFullscreen(rhi::DeviceContext* context, const oit::MethodInfo& method, const Camera& camera,
                              const oit::FrameDesc& frame, const char* pass, std::string* error) = 0;
  // Applies the compute pass `pass` of `method`'s technique, with what the object's
  // shaders read bound (its buffers, the camera), and dispatches x * y * z groups;
  // false (and `error`) when its effect for the method has no such pass.
  virtual bool Dispatch(rhi::DeviceContext* context, const oit::MethodInfo& method, const Camera& camera,
                        const oit::FrameDesc& frame, const char* pass, uint32_t x, uint32_t y, uint32_t z,
                        std::string* error) = 0;
  // Primitives alive after the last counting Update; 0 for objects that do not change.
  virtual uint64_t LiveCount() const { return 0; }
  // The most camera-facing quads a frame of the object can draw, where its
  // primitives are such quads (OBJECT_QUADS, oit/common.fxh: the particles); 0 where
  // they are not.
  virtual uint32_t QuadCapacity() const { return 0; }
};

}  // namespace renderer
