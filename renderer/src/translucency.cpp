#include "renderer/translucency.h"

#include <glm/gtc/matrix_transform.hpp>

#include "fx/effect.h"
#include "objects/objects.h"
#include "renderer/effect_files.h"
#include "rhi/capture.h"
#include "rhi/query_wait.h"

namespace renderer {

using namespace rhi;

namespace {

void SetMatrix(fx::EffectMatrixVariable* v, const glm::mat4& m) {
  v->SetMatrixTranspose(&m[0][0]);  // GLM stores columns: the transpose of FX11's row-major array
}
void SetVector(fx::EffectVectorVariable* v, const glm::vec3& x) {
  const float f[4] = {x.x, x.y, x.z, 0};
  v->SetFloatVector(f);
}

// Timestamps of a frame: the start, after the opaque pass, after the object
// updates, at the start of each method pass, and the end.
constexpr size_t kStampsBeforeMethod = 3;

}  // namespace

// A method made for this replay, with the timestamp queries of its frames.
struct Translucency::MethodState {
  std::unique_ptr<oit::Method> method;
  std::vector<ComPtr<Query>> stamps;  // kStampsBeforeMethod + passes + 1
};

struct Translucency::Impl {
  Device* device = nullptr;
  DeviceContext* context = nullptr;
  // The opaque pass: shaders_hlsl/scene.fx, technique Opaque.
  ComPtr<fx::Effect> sceneFx;
  fx::EffectPass* opaquePass = nullptr;
  fx::EffectMatrixVariable* viewProj = nullptr;
  fx::EffectVectorVariable* lightDir = nullptr;
  fx::EffectScalarVariable* ambient = nullptr;
  ComPtr<InputLayout> opaqueLayout;
  ComPtr<Buffer> opaqueVb;
  UINT opaqueVertices = 0;
  // Document 004's visibility buffer (technique Visibility), made when a method
  // that shades the opaque objects deferred first renders: the triangle id a pixel
  // shows (R32_UINT), and the raw view of the vertices that Visibility/Shade reads.
  fx::EffectPass* visibilityIdsPass = nullptr;
  ComPtr<Texture2D> visibility;
  ComPtr<RenderTargetView> visibilityRtv;
  ComPtr<ShaderResourceView> visibilitySrv, opaqueVerticesSrv;
  // The frame (R8G8B8A8_UNORM) and the opaque depth.
  ComPtr<Texture2D> frame, depth;
  ComPtr<RenderTargetView> frameRtv;
  ComPtr<ShaderResourceView> frameSrv;
  ComPtr<DepthStencilView> dsv;
  ComPtr<ShaderResourceView> depthSrv;  // the opaque depth, R32_FLOAT
  // The scene's translucent objects and the methods made for them, by name.
  std::vector<std::unique_ptr<TranslucentObject>> objects;
  std::map<std::string, MethodState> methods;
  // Timing.
  ComPtr<Query> disjoint, fragmentPassStatistics;
  MethodState* timed = nullptr;  // the method of the last timed frame, until LastTimes reads it

  void Stamp(MethodState& state, size_t index) { context->End(state.stamps[index].Get()); }
};

// The opaque objects shaded from the visibility buffer, for the frame's camera.
class Translucency::FrameOpaque final : public oit::OpaqueScene {
 public:
  FrameOpaque(Impl& impl, const Camera& camera, const oit::FrameDesc& frame)
      : impl_(impl), camera_(camera), frame_(frame) {}
  void ShadeVisibility(DeviceContext* context) override {
    fx::Effect* effect = impl_.sceneFx.Get();
    RenderTargetView* rtv = impl_.frameRtv.Get();
    context->OMSetRenderTargets(1, &rtv, nullptr);
    SetInverseViewProj(effect, camera_);
    effect->GetVariableByName("VisibilityIds")->AsShaderResource()->SetResource(impl_.visibilitySrv.Get());
    effect->GetVariableByName("OpaqueVertices")->AsShaderResource()->SetResource(impl_.opaqueVerticesSrv.Get());
    if (!DrawFullscreenPass(context, effect, frame_, "Visibility", "ShadeOpaque", &error)) return;
    ShaderResourceView* none[2] = {};
    context->PSSetShaderResources(0, 2, none);  // the next frame renders ids into the visibility buffer
  }
  std::string error;

 private:
  Impl& impl_;
  const Camera& camera_;
  oit::FrameDesc frame_;
};

// The objects as a method's passes draw them: every object, with the method of the frame.
class Translucency::FrameGeometry final : public oit::Geometry {
 public:
  FrameGeometry(Impl& impl, const oit::MethodInfo& method, const Camera& camera, const oit::FrameDesc& frame)
      : impl_(impl), method_(method), camera_(camera), frame_(frame) {}
  void Draw(DeviceContext* context, const char* pass, oit::DrawOrder order) override {
    for (auto& object : impl_.objects) {
      std::string why;
      if (!object->Draw(context, method_, camera_, pass, order, &why)) Fail(*object, why);
    }
  }
  void SetShaderResource(const char* name, ShaderResourceView* view) override {
    for (auto& object : impl_.objects)
      if (FAILED(object->MethodEffect(method_)->GetVariableByName(name)->AsShaderResource()->SetResource(view)))
        Fail(*object, std::string("no shader-resource variable ") + name);
  }
  // Then unbinds the pixel shader's resources: the object's buffers it read are
  // stream-output targets in the next frame's update, and the method's per-pixel
  // buffers UAVs again (D3D11 would unbind them with a hazard warning).
  void DrawFullscreen(DeviceContext* context, const char* pass) override {
    for (auto& object : impl_.objects) {
      std::string why;
      if (!object->DrawFullscreen(context, method_, camera_, frame_, pass, &why)) Fail(*object, why);
    }
    ShaderResourceView* none[COMMONSHADER_INPUT_RESOURCE_SLOT_COUNT] = {};
    context->PSSetShaderResources(0, COMMONSHADER_INPUT_RESOURCE_SLOT_COUNT, none);
  }
  void SetEffectVariables(const std::function<void(fx::Effect&)>& set) override {
    for (auto& object : impl_.objects) set(*object->MethodEffect(method_));
  }
  // Then unbinds the compute shader's resources and UAVs: the method's buffers are
  // read, written or copied by its next passes.
  void Dispatch(DeviceContext* context, const char* pass, uint32_t x, uint32_t y, uint32_t z) override {
    for (auto& object : impl_.objects) {
      std::string why;
      if (!object->Dispatch(context, method_, camera_, frame_, pass, x, y, z, &why)) Fail(*object, why);
    }
    ShaderResourceView* none[COMMONSHADER_INPUT_RESOURCE_SLOT_COUNT] = {};
    context->CSSetShaderResources(0, COMMONSHADER_INPUT_RESOURCE_SLOT_COUNT, none);
    UnorderedAccessView* noUavs[PS_CS_UAV_REGISTER_COUNT] = {};
    context->CSSetUnorderedAccessViews(0, PS_CS_UAV_REGISTER_COUNT, noUavs, nullptr);
  }
  std::string error;

 private:
  void Fail(const TranslucentObject& object, const std::string& why) {
    if (error.empty()) error = std::string(object.Name()) + " with " + method_.name + ": " + why;
  }
  Impl& impl_;
  const oit::MethodInfo& method_;
  const Camera& camera_;
  oit::FrameDesc frame_;
};

// The opaque backdrop as a method draws it into its own targets.
class Translucency::FrameBackdrop final : public oit::Backdrop {
 public:
  explicit FrameBackdrop(Translucency& translucency) : translucency_(translucency) {}
  void Draw(DeviceContext*, RenderTargetView* color, DepthStencilView* depth) override {
    translucency_.DrawBackdrop(color, depth);
  }

 private:
  Translucency& translucency_;
};

namespace {

// The method passes' timestamps, and the pipeline statistics of its fragment pass.
class FrameMarks final : public oit::PassMarks {
 public:
  FrameMarks(DeviceContext* context, std::vector<ComPtr<Query>>* stamps, Query* statistics, size_t fragmentPass)
      : context_(context), stamps_(stamps), statistics_(statistics), fragmentPass_(fragmentPass) {}
  void BeginPass(size_t index) override {
    if (!stamps_) return;
    if (index == fragmentPass_ + 1) EndStatistics();
    context_->End((*stamps_)[kStampsBeforeMethod + index].Get());
    if (index == fragmentPass_) {
      context_->Begin(statistics_);
      statisticsOpen_ = true;
    }
  }
  void Finish() {
    if (!stamps_) return;
    EndStatistics();
    context_->End(stamps_->back().Get());
  }

 private:
  void EndStatistics() {
    if (statisticsOpen_) context_->End(statistics_);
    statisticsOpen_ = false;
  }
  DeviceContext* context_;
  std::vector<ComPtr<Query>>* stamps_;  // null: not timing
  Query* statistics_;
  size_t fragmentPass_;
  bool statisticsOpen_ = false;
};

}  // namespace

std::unique_ptr<Translucency> Translucency::Create(Device* device, DeviceContext* context,
                                                   const TranslucencySettings& settings, std::string* error) {
  std::unique_ptr<Translucency> t(new Translucency());
  if (!t->Initialize(device, context, settings)) {
    if (error) *error = "Translucency: " + t->error_;
    return nullptr;
  }
  return t;
}

Translucency::~Translucency() = default;

bool Translucency::Initialize(Device* device, DeviceContext* context, const TranslucencySettings& s) {
  settings_ = s;
  impl_ = std::make_unique<Impl>();
  Impl& m = *impl_;
  m.device = device;
  m.context = context;
  scene_ = FindScene(s.scene);
  if (!scene_) return error_ = "no scene '" + s.scene + "' (scenes: " + SceneNames() + ")", false;
  auto fail = [&](const std::string& what) {
    if (error_.empty()) error_ = what + " failed";
    return false;
  };

  // The frame (R8G8B8A8_UNORM, also a shader resource for windows) and the opaque depth.
  auto texture = [&](DXGI_FORMAT format, UINT bind, ComPtr<Texture2D>* out) {
    TEXTURE2D_DESC d{s.width, s.height, 1, 1, format, {1, 0}, USAGE_DEFAULT, bind, 0, 0};
    return SUCCEEDED(device->CreateTexture2D(&d, nullptr, out->GetAddressOf()));
  };
  // The depth is typeless so that a method can read it (R32_FLOAT) as well as test it (D32_FLOAT).
  DEPTH_STENCIL_VIEW_DESC dsvDesc{DXGI_FORMAT_D32_FLOAT, DSV_DIMENSION_TEXTURE2D, 0, {}};
  SHADER_RESOURCE_VIEW_DESC depthSrvDesc{};
  depthSrvDesc.Format = DXGI_FORMAT_R32_FLOAT;
  depthSrvDesc.ViewDimension = SRV_DIMENSION_TEXTURE2D;
  depthSrvDesc.Texture2D = {0, 1};
  if (!texture(DXGI_FORMAT_R8G8B8A8_UNORM, BIND_RENDER_TARGET | BIND_SHADER_RESOURCE, &m.frame) ||
      !texture(DXGI_FORMAT_R32_TYPELESS, BIND_DEPTH_STENCIL | BIND_SHADER_RESOURCE, &m.depth) ||
      FAILED(device->CreateRenderTargetView(m.frame.Get(), nullptr, m.frameRtv.GetAddressOf())) ||
      FAILED(device->CreateShaderResourceView(m.frame.Get(), nullptr, m.frameSrv.GetAddressOf())) ||
      FAILED(device->CreateDepthStencilView(m.depth.Get(), &dsvDesc, m.dsv.GetAddressOf())) ||
      FAILED(device->CreateShaderResourceView(m.depth.Get(), &depthSrvDesc, m.depthSrv.GetAddressOf())))
    return fail("creating the frame and the depth buffer");

  // The opaque backdrop of the scene: scene.fx, technique Opaque.
  m.sceneFx = LoadEffect(device, "scene.fx", {}, &error_);
  if (!m.sceneFx || !(m.opaquePass = FindPass(m.sceneFx.Get(), "Opaque", "Scene", &error_))) return false;
  const INPUT_ELEMENT_DESC opaqueElements[] = {
      {"POSITION", 0, DXGI_FORMAT_R32G32B32_FLOAT, 0, 0, INPUT_PER_VERTEX_DATA, 0},
      {"NORMAL", 0, DXGI_FORMAT_R32G32B32_FLOAT, 0, 12, INPUT_PER_VERTEX_DATA, 0},
      {"COLOR", 0, DXGI_FORMAT_R32G32B32_FLOAT, 0, 24, INPUT_PER_VERTEX_DATA, 0}};
  fx::PASS_DESC opaqueDesc;
  if (FAILED(m.opaquePass->GetDesc(&opaqueDesc)) ||
      FAILED(device->CreateInputLayout(opaqueElements, 3, opaqueDesc.pIAInputSignature,
                                       opaqueDesc.IAInputSignatureSize, m.opaqueLayout.GetAddressOf())))
    return fail("the opaque input layout");
  m.viewProj = m.sceneFx->GetVariableByName("ViewProj")->AsMatrix();
  m.lightDir = m.sceneFx->GetVariableByName("LightDir")->AsVector();
  m.ambient = m.sceneFx->GetVariableByName("Ambient")->AsScalar();
  std::vector<BackdropVertex> scene = scene_->backdrop(s);
  m.opaqueVertices = UINT(scene.size());
  // Also a shader resource: the visibility buffer's shading reads the triangles through a raw view.
  const UINT vbBytes = UINT(scene.size() * sizeof(BackdropVertex));
  BUFFER_DESC vb{vbBytes, USAGE_IMMUTABLE, BIND_VERTEX_BUFFER | BIND_SHADER_RESOURCE, 0,
                 RESOURCE_MISC_BUFFER_ALLOW_RAW_VIEWS, 0};
  SUBRESOURCE_DATA init{scene.data(), 0, 0};
  if (FAILED(device->CreateBuffer(&vb, &init, m.opaqueVb.GetAddressOf())) ||
      !CreateRawView(device, m.opaqueVb.Get(), vbBytes, &m.opaqueVerticesSrv))
    return fail("the opaque vertex buffer");

  QUERY_DESC disjoint{QUERY_TIMESTAMP_DISJOINT, 0}, statistics{QUERY_PIPELINE_STATISTICS, 0};
  if (FAILED(device->CreateQuery(&disjoint, m.disjoint.GetAddressOf())) ||
      FAILED(device->CreateQuery(&statistics, m.fragmentPassStatistics.GetAddressOf())))
    return fail("the queries");

  return scene_->build(device, s, &m.objects, &error_) || fail(std::string("the scene ") + scene_->name);
}

// The method's instance for this frame size and its effects for every object, made on first use.
Translucency::MethodState* Translucency::Prepare(const oit::MethodInfo& info) {
  Impl& m = *impl_;
  if (auto found = m.methods.find(info.name); found != m.methods.end()) return &found->second;
  MethodState state;
  std::string why;
  if (!Accepts(info, &why)) return error_ = why, nullptr;
  uint32_t quadCapacity = 0;
  for (auto& object : m.objects) quadCapacity = std::max(quadCapacity, object->QuadCapacity());
  oit::MethodSetup setup{m.device,
                               {settings_.width, settings_.height, 1},
                               settings_.peelLayers,
                               uint32_t(m.objects.size()),
                               settings_.fragmentStorage,
                               settings_.minDepthSlope,
                               settings_.msaaSamples};
  setup.quadCapacity = quadCapacity;
  state.method = info.create(info, setup, &why);
  if (!state.method) return error_ = std::string(info.name) + ": " + why, nullptr;
  if (state.method->Opaque() == oit::OpaqueShading::VisibilityBuffer && !PrepareVisibilityBuffer()) return nullptr;
  if (settings_.showLayer >= 0 && !state.method->ShowLayer(uint32_t(settings_.showLayer)))
    return error_ = std::string(info.name) + " keeps no layer " + std::to_string(settings_.showLayer), nullptr;
  for (auto& object : m.objects)
    if (!object->PrepareMethod(info, &why))
      return error_ = std::string(object->Name()) + " with " + info.name + ": " + why, nullptr;
  if (settings_.timestamps) {
    QUERY_DESC stamp{QUERY_TIMESTAMP, 0};
    state.stamps.resize(kStampsBeforeMethod + state.method->PassNames().size() + 1);
    for (auto& q : state.stamps)
      if (FAILED(m.device->CreateQuery(&stamp, q.GetAddressOf()))) return error_ = "the timestamp queries", nullptr;
  }
  return &m.methods.emplace(info.name, std::move(state)).first->second;
}

bool Translucency::Accepts(const oit::MethodInfo& method, std::string* why) const {
  if (!(method.needs & oit::kNeedsQuadObjects)) return true;
  for (const auto& object : impl_->objects)
    if (object->QuadCapacity() == 0) {
      if (why)
        *why = std::string(method.name) + " bins and shades camera-facing quads (the particles) in compute; " +
               object->Name() + " draws other primitives";
      return false;
    }
  return true;
}

bool Translucency::PrepareVisibilityBuffer() {
  Impl& m = *impl_;
  if (m.visibility) return true;
  if (!(m.visibilityIdsPass = FindPass(m.sceneFx.Get(), "Visibility", "Ids", &error_))) return false;
  TEXTURE2D_DESC d{settings_.width, settings_.height, 1, 1, DXGI_FORMAT_R32_UINT, {1, 0}, USAGE_DEFAULT,
                   BIND_RENDER_TARGET | BIND_SHADER_RESOURCE, 0, 0};
  if (FAILED(m.device->CreateTexture2D(&d, nullptr, m.visibility.GetAddressOf())) ||
      FAILED(m.device->CreateRenderTargetView(m.visibility.Get(), nullptr, m.visibilityRtv.GetAddressOf())) ||
      FAILED(m.device->CreateShaderResourceView(m.visibility.Get(), nullptr, m.visibilitySrv.GetAddressOf())))
    return error_ = "creating the visibility buffer failed", false;
  return true;
}

const oit::Method* Translucency::MethodInstance(const oit::MethodInfo& method) const {
  auto found = impl_->methods.find(method.name);
  return found == impl_->methods.end() ? nullptr : found->second.method.get();
}

Camera Translucency::CameraForFrame(uint32_t n) const {
  Camera c;
  c.eye = ScriptedEye(scene_->cameraTarget, scene_->cameraRadius, n);
  c.nearPlane = settings_.nearPlane > 0 ? settings_.nearPlane : scene_->nearPlane;
  c.farPlane = settings_.farPlane > 0 ? settings_.farPlane : scene_->farPlane;
  glm::mat4 view = glm::lookAtLH(c.eye, scene_->cameraTarget, glm::vec3(0, 1, 0));
  glm::mat4 proj = glm::perspectiveLH_ZO(glm::radians(50.0f), float(settings_.width) / float(settings_.height),
                                         c.nearPlane, c.farPlane);
  c.viewProj = proj * view;
  return c;
}

// A method whose storage proved too small for the frame has grown it: the frame is
// drawn again, the same frame (FragmentSizing::GrowAndRedraw).
bool Translucency::RenderFrame(const oit::MethodInfo& method) { return RenderComplete(method, true); }

bool Translucency::RenderComplete(const oit::MethodInfo& method, bool advance) {
  if (!Render(method, advance)) return false;
  if (!impl_->methods.at(method.name).method->FrameNeedsRedraw(impl_->context)) return true;
  ++redrawnFrames_;
  return Render(method, false);
}

bool Translucency::RenderFrameAgain(const oit::MethodInfo& method) {
  if (frame_ == 0) return error_ = "RenderFrameAgain before the first frame", false;
  if (method.order == oit::DrawOrder::BackToFront && !lastUpdateCounted_)
    return error_ = std::string(method.name) + " sorts the live particles, which the last update did not count "
                    "(TranslucencySettings::countParticles)", false;
  return RenderComplete(method, false);
}

// One frame with `method`; `advance`: the next frame (camera, object updates), else the last one again.
bool Translucency::Render(const oit::MethodInfo& method, bool advance) {
  Impl& m = *impl_;
  MethodState* state = Prepare(method);
  if (!state) return false;
  DeviceContext* ctx = m.context;
  // Every frame starts from D3D11's default state, so that no binding of the last
  // frame (the composing pass's shader resources, say) meets this frame's outputs.
  ctx->ClearState();
  if (advance) camera_ = cameraOverride_ ? *cameraOverride_ : CameraForFrame(frame_);
  // A back-to-front method sorts what the updates left alive: count it.
  const bool count = settings_.countParticles || method.order == oit::DrawOrder::BackToFront;
  const bool timed = settings_.timestamps;
  if (timed) {
    ctx->Begin(m.disjoint.Get());
    m.Stamp(*state, 0);
  }
  const bool visibility = state->method->Opaque() == oit::OpaqueShading::VisibilityBuffer;
  OpaquePass(visibility);
  if (timed) m.Stamp(*state, 1);
  if (advance) {
    for (auto& object : m.objects) object->Update(ctx, count);
    lastUpdateCounted_ = count;
  }
  if (timed) m.Stamp(*state, 2);
  FrameGeometry geometry(m, method, camera_, {settings_.width, settings_.height, 1});
  FrameMarks marks(ctx, timed ? &state->stamps : nullptr, m.fragmentPassStatistics.Get(),
                   state->method->FragmentPass());
  FrameOpaque opaque(m, camera_, {settings_.width, settings_.height, 1});
  FrameBackdrop backdrop(*this);
  state->method->Render({ctx,
                         {m.frameRtv.Get(), m.dsv.Get(), m.frameSrv.Get(), m.depthSrv.Get()},
                         &geometry,
                         &marks,
                         &backdrop,
                         visibility ? &opaque : nullptr,
                         camera_.nearPlane,
                         camera_.farPlane});
  marks.Finish();
  if (timed) {
    ctx->End(m.disjoint.Get());
    m.timed = state;
  }
  if (!geometry.error.empty()) return error_ = geometry.error, false;
  if (!opaque.error.empty()) return error_ = opaque.error, false;
  if (advance) ++frame_;
  return true;
}

// Opaque objects into the depth buffer and, forward (scene.fx Opaque/Scene), the
// frame, or their triangle ids into the visibility buffer (Visibility/Ids: the frame
// keeps the background until the method shades them).
void Translucency::OpaquePass(bool visibilityBuffer) {
  Impl& m = *impl_;
  DeviceContext* ctx = m.context;
  ctx->ClearRenderTargetView(m.frameRtv.Get(), settings_.neutralBackground ? kNeutralColour : kSkyColour);
  ctx->ClearDepthStencilView(m.dsv.Get(), CLEAR_DEPTH, 1.0f, 0);
  RenderTargetView* rtv = m.frameRtv.Get();
  if (visibilityBuffer) {
    const float background[4] = {0, 0, 0, 0};  // id 0: no triangle (D3D11 converts the floats to UINT)
    ctx->ClearRenderTargetView(m.visibilityRtv.Get(), background);
    rtv = m.visibilityRtv.Get();
  }
  DrawOpaqueObjects(rtv, m.dsv.Get(), visibilityBuffer);
}

// The backdrop, forward, into a method's own `color` and `depth` (oit::Backdrop),
// cleared as the frame is.
void Translucency::DrawBackdrop(RenderTargetView* color, DepthStencilView* depth) {
  DeviceContext* ctx = impl_->context;
  ctx->ClearRenderTargetView(color, settings_.neutralBackground ? kNeutralColour : kSkyColour);
  ctx->ClearDepthStencilView(depth, CLEAR_DEPTH, 1.0f, 0);
  DrawOpaqueObjects(color, depth, false);
}

// The opaque objects into `target` and `depth`: scene.fx Opaque/Scene, or Visibility/Ids.
void Translucency::DrawOpaqueObjects(RenderTargetView* target, DepthStencilView* depth, bool visibilityIds) {
  Impl& m = *impl_;
  DeviceContext* ctx = m.context;
  ctx->OMSetRenderTargets(1, &target, depth);
  VIEWPORT viewport{0, 0, float(settings_.width), float(settings_.height), 0, 1};
  ctx->RSSetViewports(1, &viewport);
  SetMatrix(m.viewProj, camera_.viewProj);
  SetVector(m.lightDir, SceneLightDirection());
  m.ambient->SetFloat(0.45f);
  UINT stride = sizeof(BackdropVertex), offset = 0;
  Buffer* vb = m.opaqueVb.Get();
  ctx->IASetInputLayout(m.opaqueLayout.Get());
  ctx->IASetVertexBuffers(0, 1, &vb, &stride, &offset);
  ctx->IASetPrimitiveTopology(PRIMITIVE_TOPOLOGY_TRIANGLELIST);
  (visibilityIds ? m.visibilityIdsPass : m.opaquePass)->Apply(0, ctx);
  ctx->Draw(m.opaqueVertices, 0);
}

uint64_t Translucency::particleCount() const {
  uint64_t live = 0;
  for (const auto& object : impl_->objects) live += object->LiveCount();
  return live;
}

Texture2D* Translucency::FrameTexture() const { return impl_->frame.Get(); }

std::vector<uint8_t> Translucency::ReadFrame() {
  std::vector<uint8_t> pixels;
  if (FAILED(rhi::CaptureTexture2D(impl_->device, impl_->context, impl_->frame.Get(), 0, &pixels))) return {};
  return pixels;
}

PassTimes Translucency::LastTimes() {
  Impl& m = *impl_;
  PassTimes t;
  MethodState* state = std::exchange(m.timed, nullptr);
  if (!state) return t;
  QUERY_DATA_TIMESTAMP_DISJOINT disjoint{};
  std::vector<UINT64> stamps(state->stamps.size());
  QUERY_DATA_PIPELINE_STATISTICS statistics{};
  bool ready = SUCCEEDED(WaitForData(m.context, m.disjoint.Get(), &disjoint));
  for (size_t i = 0; i < stamps.size(); ++i)
    ready = SUCCEEDED(WaitForData(m.context, state->stamps[i].Get(), &stamps[i])) && ready;
  ready = SUCCEEDED(WaitForData(m.context, m.fragmentPassStatistics.Get(), &statistics)) && ready;
  if (!ready || disjoint.Disjoint || disjoint.Frequency == 0) return t;
  auto ms = [&](size_t a, size_t b) { return double(stamps[b] - stamps[a]) * 1000.0 / double(disjoint.Frequency); };
  t.valid = true;
  t.opaqueMs = ms(0, 1);
  t.updateMs = ms(1, 2);
  for (size_t i = kStampsBeforeMethod; i + 1 < stamps.size(); ++i) t.methodPassMs.push_back(ms(i, i + 1));
  t.totalMs = ms(0, stamps.size() - 1);
  t.fragmentPass = state->method->FragmentPass();
  t.fragmentPassInvocations = statistics.PSInvocations;
  return t;
}

}  // namespace renderer
