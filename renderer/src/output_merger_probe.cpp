// The output-merger probe (renderer/output_merger_probe.h): the values of
// shaders_hlsl/oit/blend_probe.fx blended by the device, against both models of each
// target format computed here.
#include "renderer/output_merger_probe.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <vector>

#include "fx/effect.h"
#include "renderer/effect_files.h"

namespace renderer {
namespace {

using rhi::ComPtr;
using Float4 = std::array<float, 4>;
using Unorm4 = std::array<uint32_t, 4>;

constexpr uint32_t kWidth = OutputMergerArithmetic::kProbes;

// blend_probe.fx's values of pixel x.
float Fraction(float v) { return v - std::floor(v); }
Unorm4 UnormDestination(uint32_t x) { return {x * 97 % 256, (x * 53 + 7) % 256, (x * 29 + 101) % 256, (x * 13 + 31) % 256}; }
Float4 UnormSource(uint32_t x) {
  const float k[4] = {0.6180339887f, 0.7548776662f, 0.5698402910f, 0.4142135624f};
  Float4 s;
  for (int c = 0; c < 4; ++c) s[c] = Fraction(float(x) * k[c] + 0.137f);
  return s;
}
float HalfDestination(uint32_t x) { return x < 240 ? 2048.0f + 2.0f * float(x % 16) : 65504.0f; }
Float4 HalfSource(uint32_t x) {
  const float k[4] = {0.0137f, 0.0071f, 0.0113f, 0.0059f};
  Float4 s;
  for (int c = 0; c < 4; ++c) s[c] = x < 240 ? 0.25f + float(x) * k[c] : 100.0f;
  return s;
}

uint32_t ToUnorm8(float v) { return uint32_t(std::floor(std::clamp(v, 0.0f, 1.0f) * 255.0f + 0.5f)); }
uint32_t MulUnorm8(uint32_t a, uint32_t b) {  // round(a * b / 255)
  const uint32_t p = a * b + 128;
  return (p + (p >> 8)) >> 8;
}

// alpha.fxh's Over (colour SRC_ALPHA, INV_SRC_ALPHA; alpha ONE, INV_SRC_ALPHA) in each model.
Unorm4 OverEachTermRounded(const Float4& s, const Unorm4& d) {
  Unorm4 s8, out;
  for (int c = 0; c < 4; ++c) s8[c] = ToUnorm8(s[c]);
  for (int c = 0; c < 3; ++c) out[c] = std::min(MulUnorm8(s8[c], s8[3]) + MulUnorm8(d[c], 255 - s8[3]), 255u);
  out[3] = std::min(s8[3] + MulUnorm8(d[3], 255 - s8[3]), 255u);
  return out;
}
Unorm4 OverRoundedOnce(const Float4& s, const Unorm4& d) {
  Unorm4 s8;
  for (int c = 0; c < 4; ++c) s8[c] = ToUnorm8(s[c]);
  Unorm4 out;  // the exact sum of 8-bit products, rounded
  for (int c = 0; c < 3; ++c) out[c] = ToUnorm8(float(s8[c] * s8[3] + d[c] * (255 - s8[3])) / (255.0f * 255.0f));
  out[3] = ToUnorm8(float(s8[3] * 255 + d[3] * (255 - s8[3])) / (255.0f * 255.0f));
  return out;
}

// A positive float as a half holds it, toward zero or to nearest even; past the
// largest half, the largest (both devices measured hold it there, neither gives infinity).
float ToHalf(float v, bool towardZero) {
  constexpr float kLargest = 65504.0f;
  if (v >= kLargest) return kLargest;
  int exponent = 0;
  std::frexp(v, &exponent);  // v = m * 2^exponent, m in [0.5, 1): a half keeps 11 significant bits
  const double spacing = std::ldexp(1.0, std::max(exponent, -13) - 11);
  const double steps = double(v) / spacing, lower = std::floor(steps), rest = steps - lower;
  if (towardZero || rest < 0.5) return float(lower * spacing);
  if (rest > 0.5) return float((lower + 1) * spacing);
  return float((std::fmod(lower, 2.0) == 0 ? lower : lower + 1) * spacing);
}
float FromHalf(uint16_t h) {
  const uint32_t exponent = (h >> 10) & 0x1F, mantissa = h & 0x3FF;
  const float sign = (h & 0x8000) ? -1.0f : 1.0f;
  if (exponent == 0) return sign * std::ldexp(float(mantissa), -24);
  if (exponent == 31) return mantissa ? std::numeric_limits<float>::quiet_NaN() : sign * INFINITY;
  return sign * std::ldexp(float(mantissa | 0x400), int(exponent) - 25);
}

// Draws the technique's Fill, then its blend pass, into a 256x1 target of `format`;
// the texels read back.
bool BlendProbe(rhi::Device* device, rhi::DeviceContext* ctx, fx::Effect* effect, const char* technique,
                const char* blendPass, rhi::DXGI_FORMAT format, uint32_t texelBytes, std::vector<uint8_t>* texels,
                std::string* error) {
  const rhi::TEXTURE2D_DESC desc{kWidth, 1, 1, 1, format, {1, 0}, rhi::USAGE_DEFAULT, rhi::BIND_RENDER_TARGET, 0, 0};
  rhi::TEXTURE2D_DESC stagingDesc = desc;
  stagingDesc.Usage = rhi::USAGE_STAGING, stagingDesc.BindFlags = 0, stagingDesc.CPUAccessFlags = rhi::CPU_ACCESS_READ;
  ComPtr<rhi::Texture2D> target, staging;
  ComPtr<rhi::RenderTargetView> rtv;
  fx::EffectPass *fill = nullptr, *blend = nullptr;
  if (rhi::FAILED(device->CreateTexture2D(&desc, nullptr, target.GetAddressOf())) ||
      rhi::FAILED(device->CreateTexture2D(&stagingDesc, nullptr, staging.GetAddressOf())) ||
      rhi::FAILED(device->CreateRenderTargetView(target.Get(), nullptr, rtv.GetAddressOf())))
    return *error = "the output-merger probe's targets could not be made", false;
  if (!(fill = FindPass(effect, technique, "Fill", error)) || !(blend = FindPass(effect, technique, blendPass, error)))
    return false;
  ctx->ClearState();
  rhi::RenderTargetView* rtvs[1] = {rtv.Get()};
  ctx->OMSetRenderTargets(1, rtvs, nullptr);
  const rhi::VIEWPORT viewport{0, 0, float(kWidth), 1, 0, 1};
  ctx->RSSetViewports(1, &viewport);
  ctx->IASetPrimitiveTopology(rhi::PRIMITIVE_TOPOLOGY_TRIANGLELIST);
  for (fx::EffectPass* pass : {fill, blend}) {
    pass->Apply(0, ctx);
    ctx->Draw(3, 0);
  }
  ctx->ClearState();
  ctx->CopyResource(staging.Get(), target.Get());
  rhi::MAPPED_SUBRESOURCE mapped{};
  if (rhi::FAILED(ctx->Map(staging.Get(), 0, rhi::MAP_READ, 0, &mapped)))
    return *error = "the output-merger probe could not read its target", false;
  texels->resize(size_t(kWidth) * texelBytes);
  std::memcpy(texels->data(), mapped.pData, texels->size());
  ctx->Unmap(staging.Get(), 0);
  return true;
}

}  // namespace

bool ProbeOutputMergerArithmetic(rhi::Device* device, OutputMergerArithmetic* out, std::string* error) {
  ComPtr<rhi::DeviceContext> ctx;
  device->GetImmediateContext(ctx.GetAddressOf());
  ComPtr<fx::Effect> effect = LoadEffect(device, "oit/blend_probe.fx", {}, error);
  std::vector<uint8_t> unorm, half;
  if (!effect ||
      !BlendProbe(device, ctx.Get(), effect.Get(), "Unorm8", "Over", rhi::DXGI_FORMAT_R8G8B8A8_UNORM, 4, &unorm,
                  error) ||
      !BlendProbe(device, ctx.Get(), effect.Get(), "Half", "Accumulate", rhi::DXGI_FORMAT_R16G16B16A16_FLOAT, 8,
                  &half, error))
    return false;
  uint32_t eachTerm = 0, roundedOnce = 0, towardZero = 0, nearest = 0;
  for (uint32_t x = 0; x < kWidth; ++x) {
    const Unorm4 got{unorm[x * 4], unorm[x * 4 + 1], unorm[x * 4 + 2], unorm[x * 4 + 3]};
    eachTerm += got == OverEachTermRounded(UnormSource(x), UnormDestination(x));
    roundedOnce += got == OverRoundedOnce(UnormSource(x), UnormDestination(x));
    bool zeroward = true, even = true;
    for (int c = 0; c < 4; ++c) {
      uint16_t bits;
      std::memcpy(&bits, &half[(x * 4 + c) * 2], 2);
      const float sum = HalfDestination(x) + HalfSource(x)[c], stored = FromHalf(bits);
      zeroward = zeroward && stored == ToHalf(sum, true);
      even = even && stored == ToHalf(sum, false);
    }
    towardZero += zeroward, nearest += even;
  }
  out->unormRoundsEachTerm = eachTerm > roundedOnce;
  out->unormMatches = std::max(eachTerm, roundedOnce);
  out->halfRoundsTowardZero = towardZero > nearest;
  out->halfMatches = std::max(towardZero, nearest);
  return true;
}

}  // namespace renderer
