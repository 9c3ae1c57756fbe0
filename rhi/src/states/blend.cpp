#include "states/blend.h"

#include <iterator>

#include "states/util.h"

namespace rhi::states {
namespace {

// Indexed by value. 12 and 13 are holes (D3D9's BOTHSRCALPHA/BOTHINVSRCALPHA,
// not part of D3D11_BLEND), so they are refused like any other unknown value.
constexpr const char* kBlendNames[] = {
    nullptr,
    "D3D11_BLEND_ZERO",
    "D3D11_BLEND_ONE",
    "D3D11_BLEND_SRC_COLOR",
    "D3D11_BLEND_INV_SRC_COLOR",
    "D3D11_BLEND_SRC_ALPHA",
    "D3D11_BLEND_INV_SRC_ALPHA",
    "D3D11_BLEND_DEST_ALPHA",
    "D3D11_BLEND_INV_DEST_ALPHA",
    "D3D11_BLEND_DEST_COLOR",
    "D3D11_BLEND_INV_DEST_COLOR",
    "D3D11_BLEND_SRC_ALPHA_SAT",
    nullptr,
    nullptr,
    "D3D11_BLEND_BLEND_FACTOR",
    "D3D11_BLEND_INV_BLEND_FACTOR",
    "D3D11_BLEND_SRC1_COLOR",
    "D3D11_BLEND_INV_SRC1_COLOR",
    "D3D11_BLEND_SRC1_ALPHA",
    "D3D11_BLEND_INV_SRC1_ALPHA",
};

// D3D11_BLEND docs: the *_COLOR factors are not allowed in the alpha equation.
bool IsColorFactor(BLEND f) {
  switch (f) {
    case BLEND_SRC_COLOR:
    case BLEND_INV_SRC_COLOR:
    case BLEND_DEST_COLOR:
    case BLEND_INV_DEST_COLOR:
    case BLEND_SRC1_COLOR:
    case BLEND_INV_SRC1_COLOR:
      return true;
    default:
      return false;
  }
}

bool IsDualSource(BLEND f) { return f >= BLEND_SRC1_COLOR && f <= BLEND_INV_SRC1_ALPHA; }
bool IsConstant(BLEND f) { return f == BLEND_BLEND_FACTOR || f == BLEND_INV_BLEND_FACTOR; }

std::string FieldName(UINT rt, const char* field) {
  return "BLEND_DESC.RenderTarget[" + std::to_string(rt) + "]." + field;
}

std::string CheckFactor(UINT rt, const char* field, BLEND f, bool alpha) {
  if (!BlendName(f)) return FieldName(rt, field) + ": " + std::to_string(f) + " is not a valid D3D11_BLEND";
  if (alpha && IsColorFactor(f))
    return FieldName(rt, field) + ": " + BlendName(f) +
           " is not allowed for alpha (colour factors are invalid in alpha blend)";
  return {};
}

std::string CheckOp(UINT rt, const char* field, BLEND_OP op) {
  if (op >= BLEND_OP_ADD && op <= BLEND_OP_MAX) return {};
  return FieldName(rt, field) + ": " + std::to_string(op) + " is not a valid D3D11_BLEND_OP";
}

std::string ValidateTarget(UINT i, const RENDER_TARGET_BLEND_DESC& rt) {
  // The runtime ignores (and GetDesc resets) factors and ops while blending is off.
  if (rt.BlendEnable) {
    for (const std::string& error : {CheckFactor(i, "SrcBlend", rt.SrcBlend, false),
                                     CheckFactor(i, "DestBlend", rt.DestBlend, false),
                                     CheckOp(i, "BlendOp", rt.BlendOp),
                                     CheckFactor(i, "SrcBlendAlpha", rt.SrcBlendAlpha, true),
                                     CheckFactor(i, "DestBlendAlpha", rt.DestBlendAlpha, true),
                                     CheckOp(i, "BlendOpAlpha", rt.BlendOpAlpha)}) {
      if (!error.empty()) return error;
    }
  }
  if (rt.RenderTargetWriteMask > COLOR_WRITE_ENABLE_ALL)
    return FieldName(i, "RenderTargetWriteMask") + ": " + HexText(rt.RenderTargetWriteMask) +
           " has bits outside D3D11_COLOR_WRITE_ENABLE_ALL (0xF)";
  return {};
}

RENDER_TARGET_BLEND_DESC NormalizeTarget(const RENDER_TARGET_BLEND_DESC& rt) {
  RENDER_TARGET_BLEND_DESC out;  // defaults: ONE/ZERO/ADD for colour and alpha
  out.BlendEnable = CanonicalBool(rt.BlendEnable);
  out.RenderTargetWriteMask = rt.RenderTargetWriteMask;
  if (out.BlendEnable) {
    out.SrcBlend = rt.SrcBlend;
    out.DestBlend = rt.DestBlend;
    out.BlendOp = rt.BlendOp;
    out.SrcBlendAlpha = rt.SrcBlendAlpha;
    out.DestBlendAlpha = rt.DestBlendAlpha;
    out.BlendOpAlpha = rt.BlendOpAlpha;
  }
  return out;
}

bool RawEqualTarget(const RENDER_TARGET_BLEND_DESC& a, const RENDER_TARGET_BLEND_DESC& b) {
  return a.BlendEnable == b.BlendEnable && a.SrcBlend == b.SrcBlend && a.DestBlend == b.DestBlend &&
         a.BlendOp == b.BlendOp && a.SrcBlendAlpha == b.SrcBlendAlpha && a.DestBlendAlpha == b.DestBlendAlpha &&
         a.BlendOpAlpha == b.BlendOpAlpha && a.RenderTargetWriteMask == b.RenderTargetWriteMask;
}

VkPipelineColorBlendAttachmentState ToVkAttachment(const RENDER_TARGET_BLEND_DESC& rt) {
  VkPipelineColorBlendAttachmentState a{};
  a.blendEnable = rt.BlendEnable ? VK_TRUE : VK_FALSE;
  a.srcColorBlendFactor = ToVkBlendFactor(rt.SrcBlend, false);
  a.dstColorBlendFactor = ToVkBlendFactor(rt.DestBlend, false);
  a.colorBlendOp = ToVkBlendOp(rt.BlendOp);
  a.srcAlphaBlendFactor = ToVkBlendFactor(rt.SrcBlendAlpha, true);
  a.dstAlphaBlendFactor = ToVkBlendFactor(rt.DestBlendAlpha, true);
  a.alphaBlendOp = ToVkBlendOp(rt.BlendOpAlpha);
  a.colorWriteMask = ToVkColorWriteMask(rt.RenderTargetWriteMask);
  return a;
}

bool SameAttachment(const VkPipelineColorBlendAttachmentState& a, const VkPipelineColorBlendAttachmentState& b) {
  return a.blendEnable == b.blendEnable && a.srcColorBlendFactor == b.srcColorBlendFactor &&
         a.dstColorBlendFactor == b.dstColorBlendFactor && a.colorBlendOp == b.colorBlendOp &&
         a.srcAlphaBlendFactor == b.srcAlphaBlendFactor && a.dstAlphaBlendFactor == b.dstAlphaBlendFactor &&
         a.alphaBlendOp == b.alphaBlendOp && a.colorWriteMask == b.colorWriteMask;
}

}  // namespace

const char* BlendName(BLEND factor) {
  return factor < std::size(kBlendNames) ? kBlendNames[factor] : nullptr;
}

std::string Validate(const BLEND_DESC& desc) {
  const UINT count = desc.IndependentBlendEnable ? SIMULTANEOUS_RENDER_TARGET_COUNT : 1;
  for (UINT i = 0; i < count; ++i) {
    if (std::string error = ValidateTarget(i, desc.RenderTarget[i]); !error.empty()) return error;
  }
  return {};
}

BLEND_DESC Normalize(const BLEND_DESC& desc) {
  BLEND_DESC out;
  out.AlphaToCoverageEnable = CanonicalBool(desc.AlphaToCoverageEnable);
  out.IndependentBlendEnable = CanonicalBool(desc.IndependentBlendEnable);
  for (UINT i = 0; i < SIMULTANEOUS_RENDER_TARGET_COUNT; ++i)
    out.RenderTarget[i] = NormalizeTarget(desc.RenderTarget[out.IndependentBlendEnable ? i : 0]);
  return out;
}

bool RawEqual(const BLEND_DESC& a, const BLEND_DESC& b) {
  if (a.AlphaToCoverageEnable != b.AlphaToCoverageEnable || a.IndependentBlendEnable != b.IndependentBlendEnable)
    return false;
  for (UINT i = 0; i < SIMULTANEOUS_RENDER_TARGET_COUNT; ++i) {
    if (!RawEqualTarget(a.RenderTarget[i], b.RenderTarget[i])) return false;
  }
  return true;
}

uint64_t RawHash(const BLEND_DESC& desc) {
  Fnv1a h;
  h.Add(desc.AlphaToCoverageEnable);
  h.Add(desc.IndependentBlendEnable);
  for (const RENDER_TARGET_BLEND_DESC& rt : desc.RenderTarget) {
    h.Add(rt.BlendEnable);
    h.Add(rt.SrcBlend);
    h.Add(rt.DestBlend);
    h.Add(rt.BlendOp);
    h.Add(rt.SrcBlendAlpha);
    h.Add(rt.DestBlendAlpha);
    h.Add(rt.BlendOpAlpha);
    h.Add(rt.RenderTargetWriteMask);
  }
  return h.value();
}

bool KeyEqual(const BLEND_DESC& a, const BLEND_DESC& b) { return RawEqual(Normalize(a), Normalize(b)); }
uint64_t KeyHash(const BLEND_DESC& desc) { return RawHash(Normalize(desc)); }

BlendVk ToVulkan(const BLEND_DESC& desc) {
  const BLEND_DESC n = Normalize(desc);
  BlendVk out;
  out.alphaToCoverageEnable = n.AlphaToCoverageEnable ? VK_TRUE : VK_FALSE;
  for (UINT i = 0; i < SIMULTANEOUS_RENDER_TARGET_COUNT; ++i) {
    const RENDER_TARGET_BLEND_DESC& rt = n.RenderTarget[i];
    out.attachments[i] = ToVkAttachment(rt);
    if (!rt.BlendEnable) continue;
    for (BLEND f : {rt.SrcBlend, rt.DestBlend, rt.SrcBlendAlpha, rt.DestBlendAlpha}) {
      out.usesDualSource |= IsDualSource(f);
      out.usesBlendConstants |= IsConstant(f);
    }
  }
  for (UINT i = 1; i < SIMULTANEOUS_RENDER_TARGET_COUNT; ++i)
    out.needsIndependentBlend |= !SameAttachment(out.attachments[i], out.attachments[0]);
  return out;
}

VkBlendFactor ToVkBlendFactor(BLEND factor, bool alpha) {
  switch (factor) {
    case BLEND_ZERO: return VK_BLEND_FACTOR_ZERO;
    case BLEND_ONE: return VK_BLEND_FACTOR_ONE;
    case BLEND_SRC_COLOR: return VK_BLEND_FACTOR_SRC_COLOR;
    case BLEND_INV_SRC_COLOR: return VK_BLEND_FACTOR_ONE_MINUS_SRC_COLOR;
    case BLEND_SRC_ALPHA: return VK_BLEND_FACTOR_SRC_ALPHA;
    case BLEND_INV_SRC_ALPHA: return VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA;
    case BLEND_DEST_ALPHA: return VK_BLEND_FACTOR_DST_ALPHA;
    case BLEND_INV_DEST_ALPHA: return VK_BLEND_FACTOR_ONE_MINUS_DST_ALPHA;
    case BLEND_DEST_COLOR: return VK_BLEND_FACTOR_DST_COLOR;
    case BLEND_INV_DEST_COLOR: return VK_BLEND_FACTOR_ONE_MINUS_DST_COLOR;
    // D3D: (f, f, f, 1) with f = min(As, 1 - Ad); Vulkan's factor is the same.
    case BLEND_SRC_ALPHA_SAT: return VK_BLEND_FACTOR_SRC_ALPHA_SATURATE;
    // The blend factor's alpha is what D3D applies to the alpha channel; both
    // CONSTANT_COLOR and CONSTANT_ALPHA give that, CONSTANT_ALPHA says it plainly.
    case BLEND_BLEND_FACTOR: return alpha ? VK_BLEND_FACTOR_CONSTANT_ALPHA : VK_BLEND_FACTOR_CONSTANT_COLOR;
    case BLEND_INV_BLEND_FACTOR:
      return alpha ? VK_BLEND_FACTOR_ONE_MINUS_CONSTANT_ALPHA : VK_BLEND_FACTOR_ONE_MINUS_CONSTANT_COLOR;
    case BLEND_SRC1_COLOR: return VK_BLEND_FACTOR_SRC1_COLOR;
    case BLEND_INV_SRC1_COLOR: return VK_BLEND_FACTOR_ONE_MINUS_SRC1_COLOR;
    case BLEND_SRC1_ALPHA: return VK_BLEND_FACTOR_SRC1_ALPHA;
    case BLEND_INV_SRC1_ALPHA: return VK_BLEND_FACTOR_ONE_MINUS_SRC1_ALPHA;
  }
  return VK_BLEND_FACTOR_ZERO;  // only for descs that failed Validate
}

VkBlendOp ToVkBlendOp(BLEND_OP op) {
  switch (op) {
    case BLEND_OP_ADD: return VK_BLEND_OP_ADD;
    case BLEND_OP_SUBTRACT: return VK_BLEND_OP_SUBTRACT;
    case BLEND_OP_REV_SUBTRACT: return VK_BLEND_OP_REVERSE_SUBTRACT;
    // D3D and Vulkan both ignore the factors for MIN/MAX.
    case BLEND_OP_MIN: return VK_BLEND_OP_MIN;
    case BLEND_OP_MAX: return VK_BLEND_OP_MAX;
  }
  return VK_BLEND_OP_ADD;
}

VkColorComponentFlags ToVkColorWriteMask(UINT8 mask) {
  // D3D11_COLOR_WRITE_ENABLE and VkColorComponentFlagBits share R=1, G=2, B=4, A=8.
  static_assert(UINT(COLOR_WRITE_ENABLE_RED) == UINT(VK_COLOR_COMPONENT_R_BIT) &&
                UINT(COLOR_WRITE_ENABLE_GREEN) == UINT(VK_COLOR_COMPONENT_G_BIT) &&
                UINT(COLOR_WRITE_ENABLE_BLUE) == UINT(VK_COLOR_COMPONENT_B_BIT) &&
                UINT(COLOR_WRITE_ENABLE_ALPHA) == UINT(VK_COLOR_COMPONENT_A_BIT));
  return mask & COLOR_WRITE_ENABLE_ALL;
}

std::string CheckBlendable(UINT slot, const char* formatName, const VkPipelineColorBlendAttachmentState& attachment,
                           bool formatBlends, const std::string& adapter) {
  if (!attachment.blendEnable || formatBlends) return {};
  return "render target " + std::to_string(slot) + " (" + formatName + ") has blending enabled, but " + adapter +
         " cannot blend that format (no VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BLEND_BIT)";
}

void AdjustForMissingAlpha(VkPipelineColorBlendAttachmentState& a) {
  auto fix = [](VkBlendFactor f, bool color) {
    switch (f) {
      case VK_BLEND_FACTOR_DST_ALPHA: return VK_BLEND_FACTOR_ONE;
      case VK_BLEND_FACTOR_ONE_MINUS_DST_ALPHA: return VK_BLEND_FACTOR_ZERO;
      // min(As, 1 - 1) = 0 (source alpha is clamped to [0, 1] for UNORM targets).
      case VK_BLEND_FACTOR_SRC_ALPHA_SATURATE: return color ? VK_BLEND_FACTOR_ZERO : f;
      default: return f;
    }
  };
  a.srcColorBlendFactor = fix(a.srcColorBlendFactor, true);
  a.dstColorBlendFactor = fix(a.dstColorBlendFactor, true);
  a.srcAlphaBlendFactor = fix(a.srcAlphaBlendFactor, false);
  a.dstAlphaBlendFactor = fix(a.dstAlphaBlendFactor, false);
  a.colorWriteMask &= ~VkColorComponentFlags(VK_COLOR_COMPONENT_A_BIT);
}

}  // namespace rhi::states
