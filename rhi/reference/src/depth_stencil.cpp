#include "rhi_reference/depth_stencil.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <stdexcept>

namespace rhi::reference {
namespace {

constexpr uint32_t kD24Max = (1u << 24) - 1u;

bool HasStencil(DXGI_FORMAT depthFormat) { return depthFormat == DXGI_FORMAT_D24_UNORM_S8_UINT; }

void RequireDepthFormat(DXGI_FORMAT depthFormat) {
  if (depthFormat != DXGI_FORMAT_D32_FLOAT && depthFormat != DXGI_FORMAT_D24_UNORM_S8_UINT) {
    throw std::invalid_argument("rhi::reference: depth format must be D32_FLOAT or D24_UNORM_S8_UINT");
  }
}

template <typename T>
bool CompareValues(COMPARISON_FUNC func, T left, T right) {
  switch (func) {
    case COMPARISON_NEVER: return false;
    case COMPARISON_LESS: return left < right;
    case COMPARISON_EQUAL: return left == right;
    case COMPARISON_LESS_EQUAL: return left <= right;
    case COMPARISON_GREATER: return left > right;
    case COMPARISON_NOT_EQUAL: return left != right;  // TRUE for NaN, like the FS 3.1 rules
    case COMPARISON_GREATER_EQUAL: return left >= right;
    case COMPARISON_ALWAYS: return true;
  }
  return false;
}

// FS 17.11: z converted to the buffer's precision, then compared with DepthFunc
// (fragment on the left), in the buffer's representation.
bool DepthTest(COMPARISON_FUNC func, DXGI_FORMAT depthFormat, uint32_t fragment, uint32_t stored) {
  if (depthFormat == DXGI_FORMAT_D32_FLOAT) {
    return Compare(func, std::bit_cast<float>(fragment), std::bit_cast<float>(stored));
  }
  return Compare(func, fragment, stored);  // D24: codes order like the depths they encode
}

// `(StencilRef & ReadMask) FUNC (stored & ReadMask)`: the mask applies to both.
bool StencilTest(const DEPTH_STENCILOP_DESC& face, uint8_t readMask, uint8_t ref, uint8_t stored) {
  return Compare(face.StencilFunc, static_cast<uint32_t>(ref & readMask),
                 static_cast<uint32_t>(stored & readMask));
}

// Which of the three ops runs: stencil failed; stencil passed but depth failed; both passed.
STENCIL_OP ChosenOp(const DEPTH_STENCILOP_DESC& face, bool stencilPassed, bool depthPassed) {
  if (!stencilPassed) return face.StencilFailOp;
  return depthPassed ? face.StencilPassOp : face.StencilDepthFailOp;
}

uint8_t WithWriteMask(uint8_t stored, uint8_t updated, uint8_t writeMask) {
  return static_cast<uint8_t>((stored & ~writeMask) | (updated & writeMask));
}

}  // namespace

uint32_t DepthToStored(DXGI_FORMAT depthFormat, float z) {
  RequireDepthFormat(depthFormat);
  if (depthFormat == DXGI_FORMAT_D32_FLOAT) return std::bit_cast<uint32_t>(z);  // "nop if float32"
  if (std::isnan(z)) return 0;
  const double clamped = std::clamp(static_cast<double>(z), 0.0, 1.0);
  return static_cast<uint32_t>(clamped * kD24Max + 0.5);  // "round to nearest (+0.5 and truncate)"
}

float StoredToDepth(DXGI_FORMAT depthFormat, uint32_t stored) {
  RequireDepthFormat(depthFormat);
  if (depthFormat == DXGI_FORMAT_D32_FLOAT) return std::bit_cast<float>(stored);
  return static_cast<float>(static_cast<double>(stored & kD24Max) / kD24Max);
}

bool Compare(COMPARISON_FUNC func, float left, float right) { return CompareValues(func, left, right); }

bool Compare(COMPARISON_FUNC func, uint32_t left, uint32_t right) { return CompareValues(func, left, right); }

uint8_t ApplyStencilOp(STENCIL_OP op, uint8_t stored, uint8_t ref) {
  switch (op) {
    case STENCIL_OP_KEEP: return stored;
    case STENCIL_OP_ZERO: return 0;
    case STENCIL_OP_REPLACE: return ref;
    case STENCIL_OP_INCR_SAT: return stored == 0xFF ? stored : static_cast<uint8_t>(stored + 1);
    case STENCIL_OP_DECR_SAT: return stored == 0 ? stored : static_cast<uint8_t>(stored - 1);
    case STENCIL_OP_INVERT: return static_cast<uint8_t>(~stored);
    case STENCIL_OP_INCR: return static_cast<uint8_t>(stored + 1);  // wraps 255 -> 0
    case STENCIL_OP_DECR: return static_cast<uint8_t>(stored - 1);  // wraps 0 -> 255
  }
  return stored;
}

DepthStencilOutcome DepthStencilResult(const DEPTH_STENCIL_DESC& desc, UINT stencilRef,
                                       bool frontFacing, float fragmentDepth, uint32_t storedDepth,
                                       uint8_t storedStencil, DXGI_FORMAT depthFormat) {
  RequireDepthFormat(depthFormat);
  const uint32_t fragment = DepthToStored(depthFormat, fragmentDepth);
  const uint8_t ref = static_cast<uint8_t>(stencilRef & 0xFFu);
  const DEPTH_STENCILOP_DESC& face = frontFacing ? desc.FrontFace : desc.BackFace;
  // FS 17.9: a disabled test passes and writes nothing; FS 17.12: so does the
  // stencil test on a format without stencil bits.
  const bool depthOn = desc.DepthEnable != FALSE;
  const bool stencilOn = desc.StencilEnable != FALSE && HasStencil(depthFormat);

  DepthStencilOutcome out;
  out.depthPassed = !depthOn || DepthTest(desc.DepthFunc, depthFormat, fragment, storedDepth);
  out.stencilPassed = !stencilOn || StencilTest(face, desc.StencilReadMask, ref, storedStencil);
  out.passed = out.depthPassed && out.stencilPassed;

  const bool writesDepth = depthOn && desc.DepthWriteMask == DEPTH_WRITE_MASK_ALL && out.passed;
  out.depth = writesDepth ? fragment : storedDepth;
  out.stencil = storedStencil;
  if (stencilOn) {
    const uint8_t updated = ApplyStencilOp(ChosenOp(face, out.stencilPassed, out.depthPassed), storedStencil, ref);
    out.stencil = WithWriteMask(storedStencil, updated, desc.StencilWriteMask);
  }
  return out;
}

}  // namespace rhi::reference
