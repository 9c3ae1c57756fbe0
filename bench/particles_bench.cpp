// particles_bench [--frames N] [--sizes 10000,100000,1000000]
// GPU time of the document 000 particle system per frame (update by stream
// output + DrawAuto billboards into a 1280x720 target), from TIMESTAMP queries
// in a TIMESTAMP_DISJOINT query, for each particle count; then particles
// updated and drawn per second. Each size runs twice: with DrawAuto's default
// GPU-written indirect arguments and with the native
// vkCmdDrawIndirectByteCountEXT; the difference is the cost of the
// indirect-argument step (two tiny compute dispatches per frame).
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <sstream>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "renderer/particle_system.h"
#include "rhi/query_wait.h"

namespace {

using namespace rhi;

struct Timing {
  double updateMs = 0, drawMs = 0;
  uint64_t particles = 0;
};

// Emitters with 10 children per update and lifetimes 50..149: about
// emitters * 1000 particles at steady state.
renderer::ParticleSettings SettingsFor(uint32_t particles) {
  renderer::ParticleSettings settings;
  settings.rule = {std::max(1u, particles / 1000), 10, 50, 100};
  return settings;
}

Timing Measure(bool nativeDrawAuto, uint32_t particles, uint32_t frames) {
  DEVICE_OPTIONS options;
  options.NativeDrawAuto = nativeDrawAuto ? TRUE : FALSE;
  ComPtr<Device> device;
  ComPtr<DeviceContext> context;
  if (FAILED(CreateDevice(&options, device.GetAddressOf(), context.GetAddressOf()))) std::exit(1);
  std::string error;
  auto system = renderer::ParticleSystem::Create(device.Get(), SettingsFor(particles), &error);
  if (!system) {
    std::fprintf(stderr, "%s\n", error.c_str());
    std::exit(1);
  }
  TEXTURE2D_DESC desc{1280, 720, 1, 1, DXGI_FORMAT_R8G8B8A8_UNORM, {1, 0}, USAGE_DEFAULT, BIND_RENDER_TARGET, 0, 0};
  ComPtr<Texture2D> target;
  ComPtr<RenderTargetView> rtv;
  device->CreateTexture2D(&desc, nullptr, target.GetAddressOf());
  device->CreateRenderTargetView(target.Get(), nullptr, rtv.GetAddressOf());
  renderer::Camera camera;
  camera.eye = {0, 3, -8};
  camera.viewProj = glm::perspectiveLH_ZO(glm::radians(60.0f), 1280.0f / 720.0f, 0.1f, 100.0f) *
                    glm::lookAtLH(camera.eye, glm::vec3(0, 2, 0), glm::vec3(0, 1, 0));
  QUERY_DESC disjointDesc{QUERY_TIMESTAMP_DISJOINT, 0}, stampDesc{QUERY_TIMESTAMP, 0};
  ComPtr<Query> disjoint, t0, t1, t2;
  device->CreateQuery(&disjointDesc, disjoint.GetAddressOf());
  device->CreateQuery(&stampDesc, t0.GetAddressOf());
  device->CreateQuery(&stampDesc, t1.GetAddressOf());
  device->CreateQuery(&stampDesc, t2.GetAddressOf());
  // Warm up until the population reaches its steady state (lifetimes < 150).
  std::vector<double> updates, draws;
  for (uint32_t frame = 0; frame < 150 + frames; ++frame) {
    const bool timed = frame >= 150;
    if (timed) {
      context->Begin(disjoint.Get());
      context->End(t0.Get());
    }
    system->Update(context.Get());
    if (timed) context->End(t1.Get());
    float clear[4] = {0.2f, 0.3f, 0.4f, 1};
    context->ClearRenderTargetView(rtv.Get(), clear);
    RenderTargetView* rt = rtv.Get();
    context->OMSetRenderTargets(1, &rt, nullptr);
    VIEWPORT viewport{0, 0, 1280, 720, 0, 1};
    context->RSSetViewports(1, &viewport);
    system->Draw(context.Get(), camera);
    context->OMSetRenderTargets(0, nullptr, nullptr);
    if (!timed) continue;
    context->End(t2.Get());
    context->End(disjoint.Get());
    QUERY_DATA_TIMESTAMP_DISJOINT clock{};
    UINT64 a = 0, b = 0, c = 0;
    if (FAILED(WaitForData(context.Get(), disjoint.Get(), &clock)) || FAILED(WaitForData(context.Get(), t0.Get(), &a)) ||
        FAILED(WaitForData(context.Get(), t1.Get(), &b)) || FAILED(WaitForData(context.Get(), t2.Get(), &c))) {
      std::fprintf(stderr, "particles_bench: GetData failed\n");
      std::exit(1);
    }
    updates.push_back(1e3 * double(b - a) / double(clock.Frequency));
    draws.push_back(1e3 * double(c - b) / double(clock.Frequency));
  }
  auto median = [](std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
  };
  renderer::ParticleCountModel model(SettingsFor(particles).rule);
  uint64_t count = 0;
  for (uint32_t i = 0; i < 150 + frames; ++i) count = model.Step();
  std::printf("  (%s on %s)\n", nativeDrawAuto ? "native byte-count draw" : "GPU-written indirect args",
              device->GetAdapterName());
  return {median(updates), median(draws), count};
}

}  // namespace

int main(int argc, char** argv) {
  uint32_t frames = 20;
  std::vector<uint32_t> sizes = {10000, 100000, 1000000};
  for (int i = 1; i + 1 < argc; i += 2) {
    if (!std::strcmp(argv[i], "--frames")) {
      frames = static_cast<uint32_t>(std::strtoul(argv[i + 1], nullptr, 10));
    } else if (!std::strcmp(argv[i], "--sizes")) {
      sizes.clear();
      std::stringstream list(argv[i + 1]);
      for (std::string item; std::getline(list, item, ',');) sizes.push_back(std::stoul(item));
    }
  }
  std::printf("| particles | update ms | draw ms | frame ms | particles/s (update+draw) | update+draw ms, native DrawAuto | indirect-args step ms |\n");
  std::printf("|---:|---:|---:|---:|---:|---:|---:|\n");
  for (uint32_t size : sizes) {
    Timing viaArgs = Measure(false, size, frames);
    Timing native = Measure(true, size, frames);
    const double frame = viaArgs.updateMs + viaArgs.drawMs;
    const double nativeFrame = native.updateMs + native.drawMs;
    std::printf("| %llu | %.3f | %.3f | %.3f | %.3g | %.3f | %.3f |\n",
                static_cast<unsigned long long>(viaArgs.particles), viaArgs.updateMs, viaArgs.drawMs, frame,
                viaArgs.particles / (frame / 1e3), nativeFrame, frame - nativeFrame);
  }
  return 0;
}
