// How D3D11 shader registers map onto Vulkan descriptor bindings.
//
// D3D11 gives every shader stage its own register files (b#, t#, s#, u#); Vulkan
// has one binding space per descriptor set. The HLSL compiler shifts each
// register into a per-stage window of set 0 so that the backend can push one
// descriptor set holding every stage's bindings without collisions:
//   binding = stage * kStageStride + class base + register index.
#pragma once

#include <cstdint>

namespace rhi {

enum class ShaderStage : uint32_t { Vertex = 0, Hull = 1, Domain = 2, Geometry = 3, Pixel = 4, Compute = 5 };
inline constexpr uint32_t kShaderStageCount = 6;

enum class RegisterClass : uint32_t { ConstantBuffer, ShaderResource, Sampler, UnorderedAccess };

inline constexpr uint32_t kStageStride = 256;
inline constexpr uint32_t kConstantBufferBase = 0;     // b0..b13 (+ 2 spare)
inline constexpr uint32_t kShaderResourceBase = 16;    // t0..t127
inline constexpr uint32_t kSamplerBase = 144;          // s0..s15
inline constexpr uint32_t kUnorderedAccessBase = 160;  // u0..u7 (room for 64)
// The hidden counters of append/consume and counter UAVs: glslang gives each a
// buffer of its own at a free u# register; the backend moves it here, to the
// counted UAV's register + this base, so that the counter follows its UAV's slot.
inline constexpr uint32_t kUnorderedAccessCounterBase = 224;  // counters of u0..u7 (room for 32)

inline constexpr uint32_t RegisterClassBase(RegisterClass c) {
  switch (c) {
    case RegisterClass::ConstantBuffer: return kConstantBufferBase;
    case RegisterClass::ShaderResource: return kShaderResourceBase;
    case RegisterClass::Sampler: return kSamplerBase;
    case RegisterClass::UnorderedAccess: return kUnorderedAccessBase;
  }
  return 0;
}

// The specialization constant (SpecId) through which the backend gives pixel
// shaders the bound render targets' sample count; the HLSL compiler's
// GetRenderTargetSamplePosition reads it (glslang has no such intrinsic).
// glslang takes SpecIds below 2047; D3D11 shaders declare none of their own.
inline constexpr uint32_t kRenderTargetSampleCountSpecId = 2032;

inline constexpr uint32_t BindingFor(ShaderStage stage, RegisterClass c, uint32_t slot) {
  return static_cast<uint32_t>(stage) * kStageStride + RegisterClassBase(c) + slot;
}

}  // namespace rhi
