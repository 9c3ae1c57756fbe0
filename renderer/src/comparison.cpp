#include "renderer/comparison.h"

#include <algorithm>

#include "renderer/image_metrics.h"

namespace renderer {

using oit::Exactness;
using oit::MethodInfo;

const MethodResult* SceneComparison::Find(std::string_view method) const {
  for (const MethodResult& r : methods)
    if (method == r.method->name) return &r;
  return nullptr;
}

namespace {

double Median(std::vector<double> v) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

// A replay of `scene` at its compared frame: the frames up to it drawn with the first
// registered method that accepts the scene (the particles do not depend on the
// method), so that every method can draw that frame again. Null (and `error`) when
// the scene cannot be replayed.
std::unique_ptr<Translucency> ReplayToComparedFrame(rhi::Device* device, rhi::DeviceContext* context,
                                                    const ComparisonSettings& settings, const SceneInfo& scene,
                                                    int frames, uint32_t peelLayers, std::string* error) {
  TranslucencySettings s;
  s.scene = scene.name;
  s.width = settings.width, s.height = settings.height;
  s.timestamps = true;
  s.countParticles = true;  // the sorted methods draw the frame again: its update counts
  if (settings.adjust) settings.adjust(s);
  s.peelLayers = peelLayers;
  auto replay = Translucency::Create(device, context, s, error);
  if (!replay) return nullptr;
  for (const MethodInfo* warmUp : oit::Methods()) {
    if (!replay->RenderFrame(*warmUp)) continue;  // refused: the frame did not advance
    replay->LastTimes();                           // consumes the frame's queries
    while (int(replay->frame()) < frames) {
      if (!replay->RenderFrame(*warmUp)) return *error = replay->error(), nullptr;
      replay->LastTimes();
    }
    return replay;
  }
  return *error = "no method accepts the scene", nullptr;
}

// The scene's depth layers, from the first method exact with enough layers that
// counts them (Method::LayerSamples), peeled to settings.maxLayers.
void CountLayers(Translucency& replay, rhi::DeviceContext* context, SceneComparison* out) {
  for (const MethodInfo* m : oit::Methods()) {
    if (m->exactness != Exactness::kExactWithEnoughLayers || !replay.RenderFrameAgain(*m)) continue;
    replay.LastTimes();
    const std::vector<uint64_t> samples = replay.MethodInstance(*m)->LayerSamples(context);
    if (samples.empty()) continue;
    out->layers = uint32_t(std::count_if(samples.begin(), samples.end(), [](uint64_t n) { return n > 0; }));
    out->layersComplete = samples.back() == 0;
    return;
  }
}

MethodResult Measure(Translucency& replay, const MethodInfo& method, const ComparisonSettings& settings,
                     std::vector<double>* fragments) {
  MethodResult r;
  r.method = &method;
  if (!replay.RenderFrameAgain(method)) return r.refused = true, r.reason = replay.error(), r;
  replay.LastTimes();
  r.image = replay.ReadFrame();
  const oit::Method* instance = replay.MethodInstance(method);
  r.bytesPerPixel = double(instance->MemoryBytes()) / (double(settings.width) * settings.height);
  r.lostFragments = instance->LostFragments();
  std::vector<double> gpu;
  for (int i = 0; i < settings.timedFrames; ++i) {
    if (!replay.RenderFrameAgain(method)) return r.refused = true, r.reason = replay.error(), r;
    const PassTimes times = replay.LastTimes();
    if (!times.valid) continue;
    double ms = 0;
    for (double pass : times.methodPassMs) ms += pass;
    gpu.push_back(ms);
    fragments->push_back(double(times.fragmentPassInvocations));
  }
  r.timed = !gpu.empty();
  r.gpuMs = Median(gpu);
  return r;
}

// The first accepting method of kExact, else of kExactWithEnoughLayers.
const MethodResult* Reference(const SceneComparison& scene) {
  for (Exactness wanted : {Exactness::kExact, Exactness::kExactWithEnoughLayers})
    for (const MethodResult& r : scene.methods)
      if (r.method->exactness == wanted && !r.refused) return &r;
  return nullptr;
}

}  // namespace

bool CompareMethods(rhi::Device* device, rhi::DeviceContext* context, const ComparisonSettings& settings,
                    std::vector<SceneComparison>* results, std::string* error,
                    const std::function<void(const SceneInfo&, const MethodInfo&)>& progress) {
  results->clear();
  for (const SceneInfo* scene : Scenes()) {
    if (!settings.scenes.empty() &&
        std::find(settings.scenes.begin(), settings.scenes.end(), scene->name) == settings.scenes.end())
      continue;
    SceneComparison out;
    out.scene = scene;
    const int frames = settings.frames > 0 ? settings.frames : scene->defaultFrames;
    out.frame = frames - 1;
    auto fail = [&](const std::string& why) { return *error = std::string(scene->name) + ": " + why, false; };
    std::string why;
    auto peeledDeep = ReplayToComparedFrame(device, context, settings, *scene, frames, settings.maxLayers, &why);
    if (!peeledDeep) return fail(why);
    CountLayers(*peeledDeep, context, &out);
    peeledDeep.reset();
    // An even count: dual depth peeling takes the layers in pairs (front and back).
    const uint32_t peelLayers = out.layers == 0 ? oit::kDefaultPeelLayers : out.layers + (out.layers & 1);
    auto replay = ReplayToComparedFrame(device, context, settings, *scene, frames, peelLayers, &why);
    if (!replay) return fail(why);
    std::vector<std::vector<double>> fragments;
    for (const MethodInfo* m : oit::Methods()) {
      if (progress) progress(*scene, *m);
      fragments.emplace_back();
      out.methods.push_back(Measure(*replay, *m, settings, &fragments.back()));
    }
    if (const MethodResult* reference = Reference(out)) {
      out.reference = reference->method;
      out.fragments = uint64_t(Median(fragments[size_t(reference - out.methods.data())]));
      for (MethodResult& r : out.methods) {
        if (r.refused) continue;
        r.rmse = Rmse(r.image, reference->image);
        r.psnr = Psnr(r.rmse);
        r.ssim = Ssim(r.image, reference->image, settings.width, settings.height);
        r.shareOff = ShareOff(r.image, reference->image, kOffSteps);
      }
    }
    results->push_back(std::move(out));
  }
  return true;
}

}  // namespace renderer
