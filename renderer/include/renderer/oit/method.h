// A transparency method: the passes that draw a scene's translucent geometry
// over its opaque frame. Every method of the source documents is one Method,
// listed once in the registry (Methods()), which the apps and the tests iterate.
//
// A method's shaders and blend tables live in its effect include,
// shaders_hlsl/oit/<name>.fxh: each translucent object's effect is the object's
// shader file built with OIT_METHOD defined to that include (one object shader
// times one method include, never a hand-written technique per pair), and the
// passes that draw no object (composing) come from shaders_hlsl/oit/method.fx
// built the same way. docs/ARCHITECTURE.md, "Adding a transparency method".
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "rhi/rhi.h"

namespace fx {
class Effect;
}

namespace renderer::oit {

// What a method needs of the device beyond Direct3D 11.0's guarantees.
enum Need : uint32_t {
  kNeedsPixelShaderUavs = 1u << 0,  // UAVs written by pixel shaders (fragmentStoresAndAtomics)
  kNeedsMsaa = 1u << 1,             // multisampled targets read per sample
  kNeedsFloat32Blend = 1u << 2,     // blending into R32_FLOAT-class targets (optional in Vulkan)
  kNeedsCompute = 1u << 3,          // compute-shader passes
  // Dual-source blending (SRC1_COLOR): D3D11.0 has it, Vulkan makes it optional (dualSrcBlend).
  kNeedsDualSourceBlend = 1u << 4,
  // Not of the device: objects whose primitives are camera-facing quads (the particles:
  // OBJECT_QUADS, oit/common.fxh), which the method bins and shades in compute.
  kNeedsQuadObjects = 1u << 5,
};
// "pixel-shader UAVs, MSAA", or "nothing beyond D3D11.0" for 0.
std::string DescribeNeeds(uint32_t needs);

// The size of the frame a method renders into.
struct FrameDesc {
  uint32_t width = 0, height = 0;
  uint32_t sampleCount = 1;
};

// How the frame driver draws the opaque objects before the method's passes.
enum class OpaqueShading {
  Forward,  // shaded as rasterized, into the frame
  // Document 004: into a visibility buffer (the triangle id a pixel shows) and the
  // depth; the frame holds only the background until the method calls
  // OpaqueScene::ShadeVisibility, which shades those pixels from their triangles.
  VisibilityBuffer,
};

// The opaque objects, for a method that shades them deferred (OpaqueShading::VisibilityBuffer).
class OpaqueScene {
 public:
  // Shades every pixel the visibility buffer names into the frame (one full-screen
  // pass; the background keeps its colour). Binds its own render target.
  virtual void ShadeVisibility(rhi::DeviceContext* context) = 0;

 protected:
  ~OpaqueScene() = default;
};

// The frame, with the opaque objects drawn: the method leaves its composite in `frame`.
struct FrameTargets {
  rhi::RenderTargetView* frame = nullptr;  // R8G8B8A8_UNORM
  rhi::DepthStencilView* depth = nullptr;  // D32_FLOAT opaque depth: tested, never written by translucency
  rhi::ShaderResourceView* frameView = nullptr;  // the frame's texture, for a method that composites elsewhere
  rhi::ShaderResourceView* depthView = nullptr;  // the opaque depth as R32_FLOAT, for a method that tests in compute
};

enum class DrawOrder {
  AsSubmitted,  // the order the objects keep their primitives in (particles: buffer order)
  BackToFront,  // sorted on the CPU by view depth (the sorted reference)
};

// The scene's translucent objects, as a method's passes see them: Draw draws
// every object with the pass `pass` of the method's technique in each object's effect.
class Geometry {
 public:
  virtual void Draw(rhi::DeviceContext* context, const char* pass, DrawOrder order) = 0;
  // Sets the shader-resource variable `name` of every object's effect for this
  // method: a texture the method made that its object passes read (depth peeling's
  // previous layer). Later Draws bind it.
  virtual void SetShaderResource(const char* name, rhi::ShaderResourceView* view) = 0;
  // Applies the pass `pass` of the object's effect to a full-screen triangle: a
  // resolve that shades the object's stored fragments per pixel (deferred shading,
  // shaders_hlsl/oit/common.fxh). One object's pass covers the frame, so a method that
  // resolves this way refuses scenes of several objects (MethodSetup::objectCount).
  virtual void DrawFullscreen(rhi::DeviceContext* context, const char* pass) = 0;
  // Calls `set` with every object's effect for the method: the variables of the
  // method's own passes in those effects (the views of its per-pixel buffers).
  virtual void SetEffectVariables(const std::function<void(fx::Effect& effect)>& set) = 0;
  // Applies the compute pass `pass` of the object's effect, with what its shaders read
  // of the object bound (as DrawFullscreen's resolve), and dispatches x * y * z groups;
  // then unbinds the compute shader's resources. One object's pass, as DrawFullscreen.
  virtual void Dispatch(rhi::DeviceContext* context, const char* pass, uint32_t x, uint32_t y, uint32_t z) = 0;

 protected:
  ~Geometry() = default;
};

// The frame driver's timing hook: a method calls BeginPass(i) as its i-th pass
// (PassNames()[i]) starts.
class PassMarks {
 public:
  virtual void BeginPass(size_t index) = 0;

 protected:
  ~PassMarks() = default;
};

// The scene's opaque backdrop, which the frame driver draws into the frame
// before the method runs. A method that needs the opaque objects in targets of
// its own (document 001's multisampled colour and depth) draws them again here:
// Draw clears `color` to the scene's background and `depth` to 1, binds them with
// a full-frame viewport and draws the backdrop (scene.fx Opaque/Scene) with the
// frame's camera. The targets may be multisampled; their size is the frame's.
class Backdrop {
 public:
  virtual void Draw(rhi::DeviceContext* context, rhi::RenderTargetView* color, rhi::DepthStencilView* depth) = 0;

 protected:
  ~Backdrop() = default;
};

struct RenderArgs {
  rhi::DeviceContext* context = nullptr;
  FrameTargets targets;
  Geometry* geometry = nullptr;
  PassMarks* marks = nullptr;
  Backdrop* backdrop = nullptr;
  OpaqueScene* opaque = nullptr;  // the opaque objects, when the method's Opaque() is VisibilityBuffer
  // The frame's projection planes, view depths in scene units (renderer::Camera):
  // what a method needs to turn window depth into view depth (the moment methods).
  float nearPlane = 0, farPlane = 0;
};

class Method {
 public:
  virtual ~Method() = default;
  // Renders every pass of the method over the frame.
  virtual void Render(const RenderArgs& args) = 0;
  // The bytes of the targets and buffers the method created for its frame.
  virtual uint64_t MemoryBytes() const = 0;
  // Its passes in the order Render runs them (the names of their effect passes).
  virtual const std::vector<std::string>& PassNames() const = 0;
  // The pass that draws the translucent objects, whose pixel-shader invocations the
  // frame counts (PassTimes::fragmentPassInvocations): the first for most methods; a
  // later one where the method first draws the opaque objects into targets of its own.
  virtual size_t FragmentPass() const { return 0; }
  // After Render: true when the frame it drew is incomplete and the method has grown
  // its storage so that drawing the same frame again completes it (prefix-sum with
  // FragmentSizing::GrowAndRedraw, which waits here for the frame's total).
  virtual bool FrameNeedsRedraw(rhi::DeviceContext* /*context*/) { return false; }
  // How the opaque objects reach the frame before Render.
  virtual OpaqueShading Opaque() const { return OpaqueShading::Forward; }

  // Methods that keep the translucent fragments as depth layers (depth peeling).
  // From the next Render on, the frame shows layer `layer` (0: the nearest) alone
  // instead of the composite; false when the method keeps no such layer.
  virtual bool ShowLayer(uint32_t /*layer*/) { return false; }
  // The samples each layer of the last Render holds (an occlusion query per
  // layer), waiting for the GPU; empty when the method keeps no layers.
  virtual std::vector<uint64_t> LayerSamples(rhi::DeviceContext* /*context*/) const { return {}; }
  // Translucent fragments the method could not store in the last frame whose count
  // has come back from the GPU (a frame or more late: no wait), for methods with
  // bounded per-fragment storage; never dropped silently. 0 for the others.
  virtual uint64_t LostFragments() const { return 0; }
};

struct MethodInfo;

// The layers the peeling methods keep unless told otherwise.
inline constexpr uint32_t kDefaultPeelLayers = 8;
// How prefix-sum sizes its fragment buffer to the frame's total, which only the GPU
// has (document 004 step 3) until the CPU reads it back.
enum class FragmentSizing {
  // The default, document 004's way: to each frame's own total, read back in the frame.
  // The CPU waits for the count and scan, and the GPU idles until the CPU has recorded
  // the fill (1.6-3.5 ms a frame on an H200 at 1920x1080). Exact and deterministic.
  Exact,
  // From earlier frames' totals, read back a frame late without waiting, grown with
  // hysteresis (1.5x a total that exceeded it). A frame whose total outgrows the
  // buffer loses fragments (counted in LostFragments; which ones is a race).
  Late,
  // The same hysteresis, but the frame's total is read back after its last pass (a
  // wait at the end of the frame, not in its middle), and a frame that did not fit is
  // drawn again with the buffer grown (Method::FrameNeedsRedraw). Exact.
  GrowAndRedraw,
};

// How the fragment-buffer methods (prefix-sum, linked-list) size their storage.
struct FragmentStorage {
  FragmentSizing sizing = FragmentSizing::Exact;  // prefix-sum
  // linked-list: the node pool's capacity, in nodes per pixel of the frame.
  uint32_t nodesPerPixel = 16;
  // The compute-tile methods: the (tile, particle) pairs their buffers first hold, per
  // quad the objects can draw (at least 4,096 pairs); a frame that needs more grows
  // them and is drawn again (Method::FrameNeedsRedraw).
  uint32_t tilePairsPerQuad = 4;
};

// Document 003's m, the slope of the minimum-depth correction (per scene unit of view depth).
inline constexpr float kDefaultMinDepthSlope = 100.0f;
// The samples per pixel of the multisampled methods (document 001's WBOIT with
// MSAA) unless told otherwise: 4, which every D3D11 device and lavapipe have for
// the formats those methods use; 8 where the device has it (they refuse it with
// the reason where CheckMultisampleQualityLevels says it has not).
inline constexpr uint32_t kDefaultMsaaSamples = 4;

// What a method is created with.
struct MethodSetup {
  rhi::Device* device = nullptr;
  FrameDesc frame;
  uint32_t peelLayers = kDefaultPeelLayers;  // the peeling methods: at most this many depth layers
  uint32_t objectCount = 0;  // the scene's translucent objects
  FragmentStorage fragmentStorage;
  float minDepthSlope = kDefaultMinDepthSlope;  // moment-transparency-mindepth: m
  uint32_t msaaSamples = kDefaultMsaaSamples;  // the multisampled methods' samples per pixel
  // The most quads an object of the scene draws in a frame (a particle system's
  // capacity; TranslucentObject::QuadCapacity): what the compute-tile methods size
  // their per-particle buffers for.
  uint32_t quadCapacity = 0;
};

using MethodFactory = std::unique_ptr<Method> (*)(const MethodInfo& info, const MethodSetup& setup,
                                                  std::string* error);

// Whether a method's composite is the exact one: every fragment of a pixel composited
// in depth order with its object's per-surface model (oit/common.fxh,
// TransmissionFactor). The comparison (renderer/comparison.h) takes its reference from
// the exact methods and expects them at zero error.
enum class Exactness {
  kApproximate,
  kExact,                  // at any depth complexity (the fragment-buffer methods)
  kExactWithEnoughLayers,  // when MethodSetup::peelLayers covers every layer of the pixel (peeling)
};

struct MethodInfo {
  const char* name;      // command lines and file names: "wboit"
  const char* include;   // its effect include, relative to shaders_hlsl/: "oit/wboit.fxh"
  uint32_t needs;        // Need bits
  DrawOrder order;       // the order its passes draw the geometry in
  const char* summary;   // one line for listings
  MethodFactory create;
  Exactness exactness = Exactness::kApproximate;
};

// The registry: every method, in the order listings show them.
const std::vector<const MethodInfo*>& Methods();
// nullptr when no method has that name.
const MethodInfo* FindMethod(std::string_view name);
// "alpha, sorted, ..." for usage messages.
std::string MethodNames();

}  // namespace renderer::oit
