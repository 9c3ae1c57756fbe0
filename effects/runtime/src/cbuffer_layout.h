// Constant buffers exist twice: in FX11 packing (what the front end computed,
// what Set*/GetRawValue read and write, what the defaults are in) and in the
// layout glslang gave the compiled SPIR-V, which can differ for arrays,
// matrices and $Globals. Uploads copy variable by variable from one to the other.
#pragma once

#include <cstdint>
#include <vector>

#include "fx/effect_ast.h"
#include "hlsl/hlsl_compiler.h"

namespace fx::detail {

struct CopyRange {
  uint32_t fxOffset = 0;
  uint32_t gpuOffset = 0;
  uint32_t size = 0;
  bool operator==(const CopyRange&) const = default;
};

// The copies that turn `cb`'s FX11 bytes into `compiled`'s layout: one per
// register-sized piece of every variable the compiled buffer has (a matrix is
// one piece per column, or per row when row_major, as both layouts store it).
std::vector<CopyRange> BuildCopyPlan(const ConstantBuffer& cb, const hlsl::ConstantBufferInfo& compiled);

// Applies a plan: `gpu` (compiled layout, `gpuSize` bytes) from `fx`.
void ApplyCopyPlan(const std::vector<CopyRange>& plan, const std::vector<uint8_t>& fx, std::vector<uint8_t>& gpu);

// Bytes of one array element of `type` (array dims ignored) under HLSL packing.
uint32_t PackedElementSize(const VariableType& type);

}  // namespace fx::detail
