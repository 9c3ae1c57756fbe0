// replay --window: document 000's translucency demos in a GLFW window.
//
//   replay --window [--demo SCENE] [--method METHOD] [--size WxH]
//                   [--validation] [--screenshot PATH --frames N]
// (SCENE and METHOD: names of the registries, replay --list-scenes / --list-methods)
//
// Each frame: renderer::Translucency renders the next frame offscreen (settings.timestamps
// and settings.countParticles on, so the overlay has per-pass GPU times and the live
// particle count); its frame target (Translucency::FrameTexture), bound as a shader
// resource, is what a full-screen triangle (shaders_hlsl/imgui.hlsl, BlitVS /
// BlitPS) draws into the swap chain's back buffer, letterboxed when the window's aspect
// differs from the scene's (--size, also the initial window size); Dear ImGui draws its
// overlay on top through the RHI (imgui_rhi.h); then Present. The swap chain is
// R8G8B8A8_UNORM like the scene target, so the window shows the same bytes as the PNGs
// of headless `replay`.
//
// Input: left-drag orbits the camera around the demo's target, the wheel zooms (both turn
// the scripted camera into an orbit camera through Translucency::SetCameraOverride; C goes
// back to the scripted one), 1-9 pick the method (the registry's order), D cycles
// the scenes, Space pauses (no RenderFrame: the last frame stays), H hides the
// overlay (its arrow collapses it), Esc quits. Parameters in
// the overlay that are creation settings of Translucency (shard count, particle size,
// ...) recreate it, which restarts the demo at frame 0.
//
// --screenshot PATH --frames N: after the N-th frame (frame index N-1, the frame headless
// `replay --frames N` writes) the back buffer, overlay included, is read back through the
// RHI before Present and written as PNG; the overlay window's rectangle is printed as
// "overlay: x y w h" (pixels), then the program exits. While nothing is dragged or
// zoomed the camera is the scripted one, so the scene part of the screenshot is the
// headless frame (tests/window checks that).
//
// Resizing recreates the swap chain's buffers (DXGI rule: every back-buffer reference is
// released first); a minimised window (zero framebuffer) waits for events and draws nothing.
#include "replay_window.h"

#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>

#include <imgui.h>
#include <backends/imgui_impl_glfw.h>

#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>

// A private copy (static functions), independent of the one app/replay.cpp defines.
#define STB_IMAGE_WRITE_STATIC
#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb_image_write.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "cli_args.h"
#include "fx/shader_directory.h"
#include "hlsl/hlsl_compiler.h"
#include "imgui_rhi.h"
#include "renderer/translucency.h"
#include "rhi/capture.h"
#include "rhi/rhi.h"
#include "rhi/swap_chain.h"

using renderer::oit::MethodInfo;
using rhi::ComPtr;
using rhi::UINT;

namespace {

int gErrors = 0;  // RHI errors and validation-layer messages of any severity

struct Options {
  std::string demo = "smoke";  // a scene of renderer::Scenes()
  const MethodInfo* method = renderer::oit::FindMethod("wboit");
  uint32_t width = 960, height = 540;
  std::string screenshot;
  int frames = 0;  // with --screenshot: frames before the capture; else 0 = until closed
  bool validation = false;
  bool testResize = false;  // resize the window to 800x450 after 3 frames, to 500x400 after 6
};

constexpr UINT kTestResizeWidth = 500, kTestResizeHeight = 400;

void Usage() {
  std::fprintf(stderr,
               "usage: replay --window [--demo SCENE] [--method METHOD] [--size WxH]\n"
               "                       [--validation] [--screenshot PATH --frames N] [--test-resize]\n"
               "  --screenshot PATH --frames N  after N frames write the back buffer (overlay included) as PNG\n"
               "                                and exit; prints the overlay window's rectangle\n"
               "  --test-resize                 resize the window to 800x450 after 3 frames, 500x400 after 6\n"
               "                                (the screenshot waits for the final size)\n"
               "  keys: 1-9 method, D scene, Space pause, C scripted camera, H overlay on/off, Esc quit;\n"
               "        left-drag orbits, the wheel zooms\n");
}

bool ParseOptions(int argc, char** argv, Options* o, std::string* error) {
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto next = [&](std::string* value) {
      if (i + 1 >= argc) return false;
      *value = argv[++i];
      return true;
    };
    std::string v;
    if (a == "--window") {
    } else if (a == "--demo") {
      if (!next(&o->demo) || !renderer::FindScene(o->demo))
        return *error = "--demo takes a scene: " + renderer::SceneNames(), false;
    } else if (a == "--method") {
      if (!next(&v) || !(o->method = renderer::oit::FindMethod(v)))
        return *error = "--method takes a method: " + renderer::oit::MethodNames(), false;
    } else if (a == "--size") {
      if (!next(&v)) return *error = "--size takes WxH", false;
      std::optional<std::vector<int64_t>> size = cli::ParseIntegers(a, v, 'x', 2, 1, 16384, error);
      if (!size) return false;
      o->width = static_cast<uint32_t>((*size)[0]);
      o->height = static_cast<uint32_t>((*size)[1]);
    } else if (a == "--screenshot") {
      if (!next(&o->screenshot)) return *error = "--screenshot takes a path", false;
    } else if (a == "--frames") {
      if (!next(&v)) return *error = "--frames takes N > 0", false;
      std::optional<int64_t> frames = cli::ParseInteger(a, v, 1, 1000000, error);
      if (!frames) return false;
      o->frames = static_cast<int>(*frames);
    } else if (a == "--validation") {
      o->validation = true;
    } else if (a == "--test-resize") {
      o->testResize = true;
    } else {
      return *error = "unknown argument " + a, false;
    }
  }
  if (!o->screenshot.empty() && o->frames <= 0) return *error = "--screenshot needs --frames N", false;
  return true;
}

bool Compile(const char* entry, const char* profile, std::vector<uint32_t>* spirv) {
  hlsl::CompileResult result =
      hlsl::CompileHlslFile(fx::ShaderDirectory() + "/imgui.hlsl", entry, profile);
  if (!result.ok) {
    std::fprintf(stderr, "%s", result.FormatErrors().c_str());
    return false;
  }
  *spirv = std::move(result.spirv);
  return true;
}

// D cycles through the scenes in the registry's order.
std::string NextScene(const std::string& scene) {
  const auto& scenes = renderer::Scenes();
  for (size_t i = 0; i < scenes.size(); ++i)
    if (scene == scenes[i]->name) return scenes[(i + 1) % scenes.size()]->name;
  return scenes.front()->name;
}

// The keys 1-9 pick the registry's first nine methods.
constexpr size_t kMethodKeys = 9;

// The orbit camera: yaw/pitch/distance around the scene's target. The start pose is
// that of Translucency::CameraForFrame (renderer/src/translucency.cpp), so taking
// over from the scripted camera does not jump.
struct Orbit {
  glm::vec3 target{0};
  float yaw = 0, pitch = 0, distance = 7;

  void StartFromScripted(const renderer::SceneInfo& scene, uint32_t frame) {
    target = scene.cameraTarget;
    const float radius = scene.cameraRadius, height = 1.2f;
    yaw = 0.3f * std::sin(float(frame) * 0.01f);
    pitch = std::atan2(height, radius);
    distance = std::sqrt(radius * radius + height * height);
  }
  // The scripted camera's planes (`scripted`, Translucency::CameraForFrame) are kept.
  renderer::Camera ToCamera(uint32_t width, uint32_t height, const renderer::Camera& scripted) const {
    renderer::Camera c;
    c.nearPlane = scripted.nearPlane, c.farPlane = scripted.farPlane;
    c.eye = target + distance * glm::vec3(std::cos(pitch) * std::sin(yaw), std::sin(pitch),
                                          -std::cos(pitch) * std::cos(yaw));
    const glm::mat4 view = glm::lookAtLH(c.eye, target, glm::vec3(0, 1, 0));
    const glm::mat4 proj =
        glm::perspectiveLH_ZO(glm::radians(50.0f), float(width) / float(height), c.nearPlane, c.farPlane);
    c.viewProj = proj * view;
    return c;
  }
};

class ReplayWindow {
 public:
  ReplayWindow(rhi::Device* device, rhi::DeviceContext* ctx, GLFWwindow* window, const Options& o)
      : device_(device), ctx_(ctx), window_(window), options_(o), method_(o.method) {
    settings_.scene = o.demo;
    settings_.width = o.width;
    settings_.height = o.height;
    settings_.timestamps = true;
    settings_.countParticles = true;
  }

  int Run();

  // GLFW input (installed before ImGui's GLFW backend, which chains to them).
  void OnKey(int key, int action, int mods);
  void OnMouseButton(int button, int action);
  void OnScroll(double dy);

 private:
  bool CreateResources();
  bool CreateScene();
  bool AttachBackBuffer();
  void ReleaseBackBuffer();
  void DrawScene(UINT width, UINT height);
  void BuildOverlay();
  bool SaveScreenshot(const std::string& path);
  void UpdateOrbitFromMouse();

  rhi::Device* device_;
  rhi::DeviceContext* ctx_;
  GLFWwindow* window_;
  Options options_;

  renderer::TranslucencySettings settings_;  // what the next CreateScene uses
  const MethodInfo* method_;
  std::unique_ptr<renderer::Translucency> scene_;
  bool recreate_ = false, paused_ = false, quit_ = false, showOverlay_ = true;
  std::string sceneError_;  // why the last recreation failed
  std::string refusal_;     // why the chosen method does not draw this scene (the last frame stays)

  ComPtr<rhi::SwapChain> swapChain_;
  ComPtr<rhi::Texture2D> backBuffer_;
  ComPtr<rhi::RenderTargetView> backBufferView_;
  UINT width_ = 0, height_ = 0;

  ComPtr<rhi::ShaderResourceView> sceneView_;
  ComPtr<rhi::VertexShader> blitVs_;
  ComPtr<rhi::PixelShader> blitPs_;
  ComPtr<rhi::SamplerState> pointSampler_, linearSampler_;
  ComPtr<rhi::RasterizerState> noCull_;
  ComPtr<rhi::DepthStencilState> noDepth_;

  Orbit orbit_;
  bool orbiting_ = false;  // the override camera is on
  bool dragging_ = false;
  double lastX_ = 0, lastY_ = 0, scroll_ = 0;

  renderer::PassTimes times_;
  std::vector<float> frameMs_;  // recent frame times for the plot
  double lastFrameTime_ = 0;
  float overlayRect_[4] = {};  // x, y, w, h of the overlay window in pixels
};

ReplayWindow* FromWindow(GLFWwindow* w) { return static_cast<ReplayWindow*>(glfwGetWindowUserPointer(w)); }

void ReplayWindow::OnKey(int key, int action, int) {
  if (action != GLFW_PRESS) return;
  if (ImGui::GetCurrentContext() && ImGui::GetIO().WantCaptureKeyboard) return;
  switch (key) {
    case GLFW_KEY_1: case GLFW_KEY_2: case GLFW_KEY_3: case GLFW_KEY_4: case GLFW_KEY_5:
    case GLFW_KEY_6: case GLFW_KEY_7: case GLFW_KEY_8: case GLFW_KEY_9:
      if (size_t(key - GLFW_KEY_1) < renderer::oit::Methods().size())
        method_ = renderer::oit::Methods()[key - GLFW_KEY_1];
      break;
    case GLFW_KEY_D:
      settings_.scene = NextScene(settings_.scene);
      recreate_ = true;
      break;
    case GLFW_KEY_SPACE: paused_ = !paused_; break;
    case GLFW_KEY_C: orbiting_ = false; break;
    case GLFW_KEY_H: showOverlay_ = !showOverlay_; break;
    case GLFW_KEY_ESCAPE: quit_ = true; break;
    default: break;
  }
}

void ReplayWindow::OnMouseButton(int button, int action) {
  if (button != GLFW_MOUSE_BUTTON_LEFT) return;
  if (action == GLFW_PRESS) {
    if (ImGui::GetCurrentContext() && ImGui::GetIO().WantCaptureMouse) return;
    dragging_ = true;
    glfwGetCursorPos(window_, &lastX_, &lastY_);
  } else if (action == GLFW_RELEASE) {
    dragging_ = false;
  }
}

void ReplayWindow::OnScroll(double dy) {
  if (ImGui::GetCurrentContext() && ImGui::GetIO().WantCaptureMouse) return;
  scroll_ += dy;
}

void ReplayWindow::UpdateOrbitFromMouse() {
  double dx = 0, dy = 0;
  if (dragging_) {
    double x, y;
    glfwGetCursorPos(window_, &x, &y);
    dx = x - lastX_, dy = y - lastY_;
    lastX_ = x, lastY_ = y;
  }
  if (dx == 0 && dy == 0 && scroll_ == 0) return;
  if (!orbiting_ && scene_) {  // take over from the scripted camera of the current frame
    orbit_.StartFromScripted(scene_->scene(), scene_->frame());
    orbiting_ = true;
  }
  orbit_.yaw -= float(dx) * 0.008f;  // drag right: the scene turns right
  orbit_.pitch = std::clamp(orbit_.pitch + float(dy) * 0.008f, -1.4f, 1.4f);
  orbit_.distance = std::clamp(orbit_.distance * std::pow(0.9f, float(scroll_)), 1.0f, 30.0f);
  scroll_ = 0;
}

bool ReplayWindow::CreateResources() {
  std::vector<uint32_t> vs, ps;
  if (!Compile("BlitVS", "vs_5_0", &vs) || !Compile("BlitPS", "ps_5_0", &ps)) return false;
  if (rhi::FAILED(device_->CreateVertexShader(vs.data(), vs.size() * 4, nullptr, blitVs_.GetAddressOf())) ||
      rhi::FAILED(device_->CreatePixelShader(ps.data(), ps.size() * 4, nullptr, blitPs_.GetAddressOf())))
    return false;
  rhi::SAMPLER_DESC point;
  point.Filter = rhi::FILTER_MIN_MAG_MIP_POINT;
  rhi::SAMPLER_DESC linear;
  linear.Filter = rhi::FILTER_MIN_MAG_MIP_LINEAR;
  rhi::RASTERIZER_DESC raster;
  raster.CullMode = rhi::CULL_NONE;
  rhi::DEPTH_STENCIL_DESC depth;
  depth.DepthEnable = rhi::FALSE;
  return rhi::SUCCEEDED(device_->CreateSamplerState(&point, pointSampler_.GetAddressOf())) &&
         rhi::SUCCEEDED(device_->CreateSamplerState(&linear, linearSampler_.GetAddressOf())) &&
         rhi::SUCCEEDED(device_->CreateRasterizerState(&raster, noCull_.GetAddressOf())) &&
         rhi::SUCCEEDED(device_->CreateDepthStencilState(&depth, noDepth_.GetAddressOf()));
}

// (Re)creates the Translucency object and the texture its frames are uploaded into. When
// a recreation fails, the running scene and its settings stay and the overlay shows why.
bool ReplayWindow::CreateScene() {
  std::string error;
  auto scene = renderer::Translucency::Create(device_, ctx_, settings_, &error);
  if (!scene) {
    std::fprintf(stderr, "replay: %s\n", error.c_str());
    sceneError_ = error;
    if (scene_) settings_ = scene_->settings();
    return scene_ != nullptr;
  }
  sceneError_.clear();
  scene_ = std::move(scene);
  orbiting_ = false;
  times_ = {};
  return rhi::SUCCEEDED(device_->CreateShaderResourceView(scene_->FrameTexture(), nullptr,
                                                         sceneView_.ReleaseAndGetAddressOf()));
}

bool ReplayWindow::AttachBackBuffer() {
  return rhi::SUCCEEDED(swapChain_->GetBuffer(0, backBuffer_.ReleaseAndGetAddressOf())) &&
         rhi::SUCCEEDED(device_->CreateRenderTargetView(backBuffer_.Get(), nullptr,
                                                        backBufferView_.ReleaseAndGetAddressOf()));
}

void ReplayWindow::ReleaseBackBuffer() {
  ctx_->OMSetRenderTargets(0, nullptr, nullptr);
  backBufferView_.Reset();
  backBuffer_.Reset();
}

// The scene, scaled to fit the back buffer with its aspect kept (bars cleared dark grey).
void ReplayWindow::DrawScene(UINT width, UINT height) {
  const float clear[4] = {0.08f, 0.08f, 0.09f, 1.0f};
  ctx_->ClearRenderTargetView(backBufferView_.Get(), clear);
  rhi::RenderTargetView* rtv = backBufferView_.Get();
  ctx_->OMSetRenderTargets(1, &rtv, nullptr);
  const float scale = std::min(float(width) / float(settings_.width), float(height) / float(settings_.height));
  const float w = std::round(settings_.width * scale), h = std::round(settings_.height * scale);
  const rhi::VIEWPORT viewport{std::floor((float(width) - w) / 2), std::floor((float(height) - h) / 2), w, h, 0, 1};
  ctx_->RSSetViewports(1, &viewport);
  ctx_->RSSetState(noCull_.Get());
  ctx_->OMSetBlendState(nullptr, nullptr, 0xffffffffu);
  ctx_->OMSetDepthStencilState(noDepth_.Get(), 0);
  ctx_->IASetInputLayout(nullptr);
  ctx_->IASetPrimitiveTopology(rhi::PRIMITIVE_TOPOLOGY_TRIANGLELIST);
  ctx_->VSSetShader(blitVs_.Get(), nullptr, 0);
  ctx_->GSSetShader(nullptr, nullptr, 0);
  ctx_->PSSetShader(blitPs_.Get(), nullptr, 0);
  rhi::ShaderResourceView* srv = sceneView_.Get();
  ctx_->PSSetShaderResources(0, 1, &srv);
  // At 1:1 point sampling copies the pixels exactly; scaled, linear filtering.
  rhi::SamplerState* sampler = (w == float(settings_.width) && h == float(settings_.height)) ? pointSampler_.Get()
                                                                                              : linearSampler_.Get();
  ctx_->PSSetSamplers(0, 1, &sampler);
  ctx_->Draw(3, 0);
  rhi::ShaderResourceView* none = nullptr;
  ctx_->PSSetShaderResources(0, 1, &none);
}

void ReplayWindow::BuildOverlay() {
  ImGuiIO& io = ImGui::GetIO();
  ImGui::SetNextWindowPos(ImVec2(10, 10), ImGuiCond_Always);
  ImGui::SetNextWindowBgAlpha(0.94f);
  const bool expanded = ImGui::Begin(
      "replay", nullptr, ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoSavedSettings);
  const ImVec2 pos = ImGui::GetWindowPos(), size = ImGui::GetWindowSize();
  overlayRect_[0] = pos.x * io.DisplayFramebufferScale.x, overlayRect_[1] = pos.y * io.DisplayFramebufferScale.y;
  overlayRect_[2] = size.x * io.DisplayFramebufferScale.x, overlayRect_[3] = size.y * io.DisplayFramebufferScale.y;
  if (!expanded) {  // collapsed to its title bar
    ImGui::End();
    return;
  }

  ImGui::Text("%s", device_->GetAdapterName());
  const uint32_t shown = scene_ && scene_->frame() > 0 ? scene_->frame() - 1 : 0;  // frame() is the next one
  ImGui::Text("%s / %s, frame %u%s", settings_.scene.c_str(), method_->name, shown,
              paused_ ? "  (paused)" : "");
  ImGui::Text("%.1f FPS, %.1f ms/frame", io.Framerate, io.Framerate > 0 ? 1000.0f / io.Framerate : 0.0f);
  if (!frameMs_.empty())
    ImGui::PlotLines("##frame", frameMs_.data(), int(frameMs_.size()), 0, "frame ms", 0.0f,
                     std::max(1.0f, *std::max_element(frameMs_.begin(), frameMs_.end())), ImVec2(250, 28));
  // Per-pass GPU times of the last frame (TIMESTAMP queries inside TIMESTAMP_DISJOINT).
  if (times_.valid) {
    ImGui::Text("GPU ms: opaque %.2f  update %.2f  total %.2f", times_.opaqueMs, times_.updateMs, times_.totalMs);
    // The method's passes by name (Method::PassNames), and its memory.
    const renderer::oit::Method* method = scene_ ? scene_->MethodInstance(*method_) : nullptr;
    for (size_t i = 0; method && i < times_.methodPassMs.size(); ++i)
      ImGui::Text("        %s %.2f", method->PassNames()[i].c_str(), times_.methodPassMs[i]);
    if (method) ImGui::Text("method memory: %.2f MiB", double(method->MemoryBytes()) / (1024.0 * 1024.0));
  } else {
    ImGui::TextDisabled("GPU ms: n/a (disjoint or not measured)");
  }
  if (settings_.scene != "shards")
    ImGui::Text("live particles: %llu", static_cast<unsigned long long>(scene_ ? scene_->particleCount() : 0));
  else
    ImGui::Text("shards: %u (one DrawIndexedInstanced)", settings_.shardCount);

  ImGui::Separator();
  const auto& methods = renderer::oit::Methods();
  int method = 0;
  for (size_t i = 0; i < methods.size(); ++i)
    if (methods[i] == method_) method = int(i);
  for (size_t i = 0; i < methods.size(); ++i) {
    if (i % 3) ImGui::SameLine();
    char label[48];
    if (i < kMethodKeys)
      std::snprintf(label, sizeof label, "%zu %s", i + 1, methods[i]->name);
    else
      std::snprintf(label, sizeof label, "%s", methods[i]->name);
    if (ImGui::RadioButton(label, &method, int(i))) method_ = methods[i];
  }
  if (ImGui::BeginCombo("scene (D)", settings_.scene.c_str())) {
    for (const renderer::SceneInfo* scene : renderer::Scenes())
      if (ImGui::Selectable(scene->name, settings_.scene == scene->name)) {
        settings_.scene = scene->name;
        recreate_ = true;
      }
    ImGui::EndCombo();
  }

  if (ImGui::CollapsingHeader("Parameters (applying restarts the demo)")) {
    // Creation settings of Translucency: a changed value recreates it once the edit ends.
    auto apply = [&] { recreate_ |= ImGui::IsItemDeactivatedAfterEdit(); };
    const std::string& scene = settings_.scene;
    if (scene == "smoke" || scene == "fire") {
      ImGui::SliderFloat("particle size", &settings_.particleSize, 0.05f, 1.0f, "%.2f");
      apply();
      int spawn = int(settings_.rule.spawnPerFrame);
      if (ImGui::SliderInt("spawn / frame", &spawn, 1, 16)) settings_.rule.spawnPerFrame = uint32_t(spawn);
      apply();
      int emitters = int(settings_.rule.emitters);
      if (ImGui::SliderInt("emitters", &emitters, 1, 256)) settings_.rule.emitters = uint32_t(emitters);
      apply();
      int extra = int(settings_.extraShards);
      if (ImGui::SliderInt("extra shards", &extra, 0, 20000)) settings_.extraShards = uint32_t(extra);
      apply();
    } else if (scene == "shards") {
      int shards = int(settings_.shardCount);
      if (ImGui::SliderInt("shard count", &shards, 1, 20000)) settings_.shardCount = uint32_t(shards);
      apply();
      ImGui::SliderFloat("surface tint", &settings_.shardSurfaceTint, 0.0f, 1.0f, "%.2f");
      apply();
      recreate_ |= ImGui::Checkbox("all shards red", &settings_.shardsAllRed);
    } else if (scene == "complexity") {
      int complexity = int(settings_.depthComplexity);
      if (ImGui::SliderInt("depth complexity", &complexity, 1, 64)) settings_.depthComplexity = uint32_t(complexity);
      apply();
    }
    recreate_ |= ImGui::Checkbox("neutral background", &settings_.neutralBackground);
  }
  if (!sceneError_.empty())
    ImGui::TextColored(ImVec4(1.0f, 0.4f, 0.4f, 1.0f), "recreating failed: %.60s", sceneError_.c_str());
  if (!refusal_.empty()) ImGui::TextColored(ImVec4(1.0f, 0.4f, 0.4f, 1.0f), "%s", refusal_.c_str());
  ImGui::Text("camera: %s", orbiting_ ? "orbit (C: scripted)" : "scripted (drag/wheel: orbit)");
  ImGui::TextDisabled("1-9 method  D scene  Space pause  H hide  Esc quit");
  ImGui::End();
}

bool ReplayWindow::SaveScreenshot(const std::string& path) {
  rhi::TEXTURE2D_DESC desc;
  backBuffer_->GetDesc(&desc);
  std::vector<uint8_t> pixels;
  if (rhi::FAILED(rhi::CaptureTexture2D(device_, ctx_, backBuffer_.Get(), 0, &pixels))) return false;
  if (desc.Format == rhi::DXGI_FORMAT_B8G8R8A8_UNORM)
    for (size_t i = 0; i < pixels.size(); i += 4) std::swap(pixels[i], pixels[i + 2]);
  if (!stbi_write_png(path.c_str(), int(desc.Width), int(desc.Height), 4, pixels.data(), int(desc.Width * 4))) {
    std::fprintf(stderr, "replay: cannot write %s\n", path.c_str());
    return false;
  }
  std::printf("wrote %s (%ux%u)\n", path.c_str(), desc.Width, desc.Height);
  std::printf("overlay: %d %d %d %d\n", int(std::lround(overlayRect_[0])), int(std::lround(overlayRect_[1])),
              int(std::lround(overlayRect_[2])), int(std::lround(overlayRect_[3])));
  return true;
}

int ReplayWindow::Run() {
  if (!CreateResources() || !CreateScene()) return 1;

  int fbWidth = 0, fbHeight = 0;
  glfwGetFramebufferSize(window_, &fbWidth, &fbHeight);
  rhi::SWAP_CHAIN_DESC scDesc{};
  scDesc.Width = UINT(std::max(fbWidth, 1));
  scDesc.Height = UINT(std::max(fbHeight, 1));
  scDesc.Format = rhi::DXGI_FORMAT_R8G8B8A8_UNORM;  // the scene's bytes as they are
  scDesc.BufferCount = 2;
  auto createSurface = [this](void* instance, uint64_t* surface) {
    VkSurfaceKHR created = VK_NULL_HANDLE;
    const VkResult result = glfwCreateWindowSurface(static_cast<VkInstance>(instance), window_, nullptr, &created);
    *surface = reinterpret_cast<uint64_t>(created);
    return result == VK_SUCCESS;
  };
  if (rhi::FAILED(rhi::CreateSwapChain(device_, &scDesc, createSurface, swapChain_.GetAddressOf())) ||
      !AttachBackBuffer()) {
    std::fprintf(stderr, "replay: creating the swap chain failed\n");
    return 1;
  }
  width_ = scDesc.Width, height_ = scDesc.Height;

  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini in the working directory
  ImGui::StyleColorsDark();
  // Ours first: ImGui's GLFW backend saves them and calls them before its own handling.
  glfwSetWindowUserPointer(window_, this);
  glfwSetKeyCallback(window_, [](GLFWwindow* w, int key, int, int action, int mods) {
    FromWindow(w)->OnKey(key, action, mods);
  });
  glfwSetMouseButtonCallback(window_, [](GLFWwindow* w, int button, int action, int) {
    FromWindow(w)->OnMouseButton(button, action);
  });
  glfwSetScrollCallback(window_, [](GLFWwindow* w, double, double dy) { FromWindow(w)->OnScroll(dy); });
  ImGui_ImplGlfw_InitForVulkan(window_, true);
  std::string error;
  if (!ImGui_ImplRhi_Init(device_, ctx_, &error)) {
    std::fprintf(stderr, "replay: %s\n", error.c_str());
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
    return 1;
  }

  int rc = 0, frames = 0;
  lastFrameTime_ = glfwGetTime();
  while (!glfwWindowShouldClose(window_) && !quit_) {
    glfwPollEvents();
    glfwGetFramebufferSize(window_, &fbWidth, &fbHeight);
    if (fbWidth == 0 || fbHeight == 0) {  // minimised: nothing to draw into
      glfwWaitEvents();
      continue;
    }
    if (UINT(fbWidth) != width_ || UINT(fbHeight) != height_) {
      width_ = UINT(fbWidth), height_ = UINT(fbHeight);
      ReleaseBackBuffer();  // DXGI: every back-buffer reference goes before ResizeBuffers
      if (rhi::FAILED(swapChain_->ResizeBuffers(0, width_, height_, rhi::DXGI_FORMAT_UNKNOWN, 0)) ||
          !AttachBackBuffer()) {
        std::fprintf(stderr, "replay: resizing the swap chain to %ux%u failed\n", width_, height_);
        rc = 1;
        break;
      }
    }
    if (recreate_) {
      recreate_ = false;
      if (!CreateScene()) {
        rc = 1;
        break;
      }
    }

    // The scene: the next frame of the demo, unless paused.
    UpdateOrbitFromMouse();
    const bool accepted = scene_->Accepts(*method_, &refusal_);
    if (accepted) refusal_.clear();
    if (!paused_ && accepted) {
      scene_->SetCameraOverride(orbiting_ ? std::optional<renderer::Camera>(orbit_.ToCamera(
                                                      settings_.width, settings_.height,
                                                      scene_->CameraForFrame(scene_->frame())))
                                          : std::nullopt);
      if (!scene_->RenderFrame(*method_)) {
        std::fprintf(stderr, "replay: %s\n", scene_->error().c_str());
        rc = 1;
        break;
      }
      times_ = scene_->LastTimes();
    }
    ctx_->ClearState();  // Translucency's bindings (GS, stream output, targets) end here
    DrawScene(width_, height_);

    // The overlay.
    const double now = glfwGetTime();
    frameMs_.push_back(float((now - lastFrameTime_) * 1000.0));
    if (frameMs_.size() > 120) frameMs_.erase(frameMs_.begin());
    lastFrameTime_ = now;
    ImGui_ImplRhi_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
    if (showOverlay_)
      BuildOverlay();
    else
      std::fill(std::begin(overlayRect_), std::end(overlayRect_), 0.0f);
    ImGui::Render();
    ImGui_ImplRhi_RenderDrawData(ImGui::GetDrawData());
    // imgui_rhi leaves its state bound; the next frame of Translucency expects the defaults
    // it has in headless replay (a fresh context).
    ctx_->ClearState();

    ++frames;
    if (options_.testResize && frames == 3) glfwSetWindowSize(window_, 800, 450);
    if (options_.testResize && frames == 6) glfwSetWindowSize(window_, int(kTestResizeWidth), int(kTestResizeHeight));
    const bool sizeReached = !options_.testResize || (width_ == kTestResizeWidth && height_ == kTestResizeHeight);
    if (!options_.screenshot.empty() && frames >= options_.frames && sizeReached) {
      if (!SaveScreenshot(options_.screenshot)) rc = 1;
      quit_ = true;
    } else if (!options_.screenshot.empty() && frames >= options_.frames + 300) {
      std::fprintf(stderr, "replay: the window never reached %ux%u (now %ux%u)\n", kTestResizeWidth,
                   kTestResizeHeight, width_, height_);
      rc = 1;
      quit_ = true;
    }
    if (rhi::FAILED(swapChain_->Present(1, 0))) {
      std::fprintf(stderr, "replay: Present failed\n");
      rc = 1;
      break;
    }
  }

  ImGui_ImplRhi_Shutdown();
  ImGui_ImplGlfw_Shutdown();  // puts our callbacks back
  ImGui::DestroyContext();
  glfwSetKeyCallback(window_, nullptr);
  glfwSetMouseButtonCallback(window_, nullptr);
  glfwSetScrollCallback(window_, nullptr);
  glfwSetWindowUserPointer(window_, nullptr);
  scene_.reset();
  ReleaseBackBuffer();
  swapChain_.Reset();
  std::printf("presented %d frames (%ux%u) on %s\n", frames, width_, height_, device_->GetAdapterName());
  return rc;
}

}  // namespace

bool ReplayWindowRequested(int argc, char** argv) {
  for (int i = 1; i < argc; ++i)
    if (std::strcmp(argv[i], "--window") == 0) return true;
  return false;
}

int RunReplayWindow(int argc, char** argv) {
  Options o;
  std::string error;
  if (!ParseOptions(argc, argv, &o, &error)) {
    std::fprintf(stderr, "replay: %s\n", error.c_str());
    Usage();
    return 2;
  }
  glfwSetErrorCallback([](int code, const char* text) { std::fprintf(stderr, "glfw error %d: %s\n", code, text); });
  if (!glfwInit()) {
    std::fprintf(stderr, "replay: glfwInit failed (no display? try xvfb-run -a)\n");
    return 1;
  }
  if (!glfwVulkanSupported()) {
    std::fprintf(stderr, "replay: GLFW found no Vulkan loader\n");
    glfwTerminate();
    return 1;
  }
  uint32_t extensionCount = 0;
  const char** extensions = glfwGetRequiredInstanceExtensions(&extensionCount);
  if (!extensions) {
    std::fprintf(stderr, "replay: GLFW reports no Vulkan surface extensions for this display\n");
    glfwTerminate();
    return 1;
  }
  rhi::DEVICE_OPTIONS options;
  options.EnableValidation = o.validation ? rhi::TRUE : rhi::FALSE;
  options.InstanceExtensions = extensions;
  options.InstanceExtensionCount = extensionCount;
  options.OnMessage = [](rhi::MESSAGE_CATEGORY category, rhi::MESSAGE_SEVERITY severity, const char* text) {
    const bool validation = category == rhi::MESSAGE_CATEGORY_VULKAN_VALIDATION;
    const bool error = validation || severity <= rhi::MESSAGE_SEVERITY_ERROR;
    if (error) ++gErrors;
    std::fprintf(stderr, "rhi %s%s: %s\n", validation ? "validation " : "", error ? "error" : "warning", text);
  };

  glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
  glfwWindowHint(GLFW_RESIZABLE, GLFW_TRUE);
  GLFWwindow* window = glfwCreateWindow(int(o.width), int(o.height), "replay (D3D11 over Vulkan)", nullptr, nullptr);
  if (!window) {
    std::fprintf(stderr, "replay: glfwCreateWindow failed\n");
    glfwTerminate();
    return 1;
  }
  int rc = 0;
  {
    ComPtr<rhi::Device> device;
    ComPtr<rhi::DeviceContext> context;
    if (rhi::FAILED(rhi::CreateDevice(&options, device.GetAddressOf(), context.GetAddressOf()))) {
      std::fprintf(stderr, "replay: CreateDevice failed\n");
      rc = 1;
    } else {
      ReplayWindow app(device.Get(), context.Get(), window, o);
      rc = app.Run();
    }
  }
  glfwDestroyWindow(window);
  glfwTerminate();
  if (rc == 0 && gErrors > 0) {
    std::fprintf(stderr, "replay: %d RHI error / validation message(s) (see above)\n", gErrors);
    rc = 3;
  }
  return rc;
}
