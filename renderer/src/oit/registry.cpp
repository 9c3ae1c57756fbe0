// The registry of transparency methods: one line per method. Each MethodInfo
// (name, effect include, needs, factory) is defined beside its Method, in this folder.
#include "renderer/oit/method.h"

namespace renderer::oit {

#define RENDERER_OIT_METHODS(X) \
  X(kAlpha)                     \
  X(kSorted)                    \
  X(kWboit)                     \
  X(kColored)                   \
  X(kColoredLiteral)            \
  X(kWboitMsaa)                 \
  X(kWboitMsaaPerPixel)         \
  X(kWboitMsaaAdditive)         \
  X(kWboitMsaaLinear)           \
  X(kWboitMsaaExposure)         \
  X(kDepthPeeling)              \
  X(kDualDepthPeeling)          \
  X(kPrefixSum)                 \
  X(kLinkedList)                \
  X(kMboit)                     \
  X(kMomentTransparency)        \
  X(kMomentTransparencyMinDepth) \
  X(kMomentTransparencyMinDepth16) \
  X(kComputeSorted)              \
  X(kComputeWboit)

#define RENDERER_OIT_DECLARE(info) extern const MethodInfo info;
RENDERER_OIT_METHODS(RENDERER_OIT_DECLARE)

const std::vector<const MethodInfo*>& Methods() {
#define RENDERER_OIT_ENTRY(info) &info,
  static const std::vector<const MethodInfo*> methods = {RENDERER_OIT_METHODS(RENDERER_OIT_ENTRY)};
  return methods;
}

const MethodInfo* FindMethod(std::string_view name) {
  for (const MethodInfo* m : Methods())
    if (name == m->name) return m;
  return nullptr;
}

std::string MethodNames() {
  std::string names;
  for (const MethodInfo* m : Methods()) names += (names.empty() ? "" : ", ") + std::string(m->name);
  return names;
}

std::string DescribeNeeds(uint32_t needs) {
  static constexpr struct {
    Need need;
    const char* text;
  } kNames[] = {{kNeedsPixelShaderUavs, "pixel-shader UAVs"},
                {kNeedsMsaa, "MSAA"},
                {kNeedsFloat32Blend, "float32 blending"},
                {kNeedsCompute, "compute"},
                {kNeedsDualSourceBlend, "dual-source blending"},
                {kNeedsQuadObjects, "particle objects"}};
  std::string text;
  for (const auto& n : kNames)
    if (needs & n.need) text += (text.empty() ? "" : ", ") + std::string(n.text);
  return text.empty() ? "nothing beyond D3D11.0" : text;
}

}  // namespace renderer::oit
