// The output-merger probe (renderer/output_merger_probe.h): shaders_hlsl/oit/
// blend_probe.fx's values blended by the device, against both models of each target
// format, which the same effect computes from oit/output_merger.hlsli (the arithmetic
// the compute-tile methods replay): the probe compares the stored texels.
#include "renderer/output_merger_probe.h"

#include <algorithm>
#include <cstring>
#include <initializer_list>
#include <vector>

#include "fx/effect.h"
#include "renderer/effect_files.h"

namespace renderer {
namespace {

using rhi::ComPtr;

constexpr uint32_t kWidth = OutputMergerArithmetic::kProbes;

// The technique's passes `passes` drawn in order into a fresh 256x1 target of
// `format`; its texels read back.
bool DrawProbe(rhi::Device* device, rhi::DeviceContext* ctx, fx::Effect* effect, const char* technique,
               std::initializer_list<const char*> passes, rhi::DXGI_FORMAT format, uint32_t texelBytes,
               std::vector<uint8_t>* texels, std::string* error) {
  const rhi::TEXTURE2D_DESC desc{kWidth, 1, 1, 1, format, {1, 0}, rhi::USAGE_DEFAULT, rhi::BIND_RENDER_TARGET, 0, 0};
  rhi::TEXTURE2D_DESC stagingDesc = desc;
  stagingDesc.Usage = rhi::USAGE_STAGING, stagingDesc.BindFlags = 0, stagingDesc.CPUAccessFlags = rhi::CPU_ACCESS_READ;
  ComPtr<rhi::Texture2D> target, staging;
  ComPtr<rhi::RenderTargetView> rtv;
  if (rhi::FAILED(device->CreateTexture2D(&desc, nullptr, target.GetAddressOf())) ||
      rhi::FAILED(device->CreateTexture2D(&stagingDesc, nullptr, staging.GetAddressOf())) ||
      rhi::FAILED(device->CreateRenderTargetView(target.Get(), nullptr, rtv.GetAddressOf())))
    return *error = "the output-merger probe's targets could not be made", false;
  ctx->ClearState();
  rhi::RenderTargetView* rtvs[1] = {rtv.Get()};
  ctx->OMSetRenderTargets(1, rtvs, nullptr);
  const rhi::VIEWPORT viewport{0, 0, float(kWidth), 1, 0, 1};
  ctx->RSSetViewports(1, &viewport);
  ctx->IASetPrimitiveTopology(rhi::PRIMITIVE_TOPOLOGY_TRIANGLELIST);
  for (const char* name : passes) {
    fx::EffectPass* pass = FindPass(effect, technique, name, error);
    if (!pass) return false;
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

// Of the pixels of `device`, how many `model` stored alike.
uint32_t Matches(const std::vector<uint8_t>& device, const std::vector<uint8_t>& model, uint32_t texelBytes) {
  uint32_t n = 0;
  for (uint32_t x = 0; x < kWidth; ++x)
    n += std::equal(&device[x * texelBytes], &device[(x + 1) * texelBytes], &model[x * texelBytes]);
  return n;
}

}  // namespace

bool ProbeOutputMergerArithmetic(rhi::Device* device, OutputMergerArithmetic* out, std::string* error) {
  ComPtr<rhi::DeviceContext> ctx;
  device->GetImmediateContext(ctx.GetAddressOf());
  ComPtr<fx::Effect> effect = LoadEffect(device, "oit/blend_probe.fx", {}, error);
  if (!effect) return false;
  constexpr auto kUnorm = rhi::DXGI_FORMAT_R8G8B8A8_UNORM;
  constexpr auto kHalf = rhi::DXGI_FORMAT_R16G16B16A16_FLOAT;
  std::vector<uint8_t> unorm, eachTerm, roundedOnce, half, towardZero, nearest;
  fx::Effect* e = effect.Get();
  rhi::DeviceContext* c = ctx.Get();
  if (!DrawProbe(device, c, e, "Unorm8", {"Fill", "Over"}, kUnorm, 4, &unorm, error) ||
      !DrawProbe(device, c, e, "Unorm8", {"EachTerm"}, kUnorm, 4, &eachTerm, error) ||
      !DrawProbe(device, c, e, "Unorm8", {"RoundedOnce"}, kUnorm, 4, &roundedOnce, error) ||
      !DrawProbe(device, c, e, "Half", {"Fill", "Accumulate"}, kHalf, 8, &half, error) ||
      !DrawProbe(device, c, e, "Half", {"TowardZero"}, kHalf, 8, &towardZero, error) ||
      !DrawProbe(device, c, e, "Half", {"Nearest"}, kHalf, 8, &nearest, error))
    return false;
  const uint32_t eachTermMatches = Matches(unorm, eachTerm, 4), onceMatches = Matches(unorm, roundedOnce, 4);
  const uint32_t zerowardMatches = Matches(half, towardZero, 8), nearestMatches = Matches(half, nearest, 8);
  out->unormRoundsEachTerm = eachTermMatches > onceMatches;
  out->unormMatches = std::max(eachTermMatches, onceMatches);
  out->halfRoundsTowardZero = zerowardMatches > nearestMatches;
  out->halfMatches = std::max(zerowardMatches, nearestMatches);
  return true;
}

}  // namespace renderer
