#include "states/depth_stencil.h"

#include "states/util.h"

namespace rhi::states {
namespace {

constexpr const char* kPrefix = "DEPTH_STENCIL_DESC.";

bool ValidStencilOp(STENCIL_OP op) { return op >= STENCIL_OP_KEEP && op <= STENCIL_OP_DECR; }

std::string CheckFunc(const std::string& field, COMPARISON_FUNC func) {
  if (ComparisonName(func)) return {};
  return kPrefix + field + ": " + std::to_string(func) + " is not a valid D3D11_COMPARISON_FUNC";
}

std::string CheckStencilOp(const std::string& field, STENCIL_OP op) {
  if (ValidStencilOp(op)) return {};
  return kPrefix + field + ": " + std::to_string(op) + " is not a valid D3D11_STENCIL_OP";
}

std::string ValidateFace(const char* face, const DEPTH_STENCILOP_DESC& f) {
  const std::string p = std::string(face) + ".";
  for (const std::string& error : {CheckStencilOp(p + "StencilFailOp", f.StencilFailOp),
                                   CheckStencilOp(p + "StencilDepthFailOp", f.StencilDepthFailOp),
                                   CheckStencilOp(p + "StencilPassOp", f.StencilPassOp),
                                   CheckFunc(p + "StencilFunc", f.StencilFunc)}) {
    if (!error.empty()) return error;
  }
  return {};
}

bool RawEqualFace(const DEPTH_STENCILOP_DESC& a, const DEPTH_STENCILOP_DESC& b) {
  return a.StencilFailOp == b.StencilFailOp && a.StencilDepthFailOp == b.StencilDepthFailOp &&
         a.StencilPassOp == b.StencilPassOp && a.StencilFunc == b.StencilFunc;
}

void HashFace(Fnv1a& h, const DEPTH_STENCILOP_DESC& f) {
  h.Add(f.StencilFailOp);
  h.Add(f.StencilDepthFailOp);
  h.Add(f.StencilPassOp);
  h.Add(f.StencilFunc);
}

VkStencilOpState ToVkStencil(const DEPTH_STENCILOP_DESC& f, const DEPTH_STENCIL_DESC& d) {
  VkStencilOpState s{};
  s.failOp = ToVkStencilOp(f.StencilFailOp);
  s.passOp = ToVkStencilOp(f.StencilPassOp);
  s.depthFailOp = ToVkStencilOp(f.StencilDepthFailOp);
  s.compareOp = ToVkCompareOp(f.StencilFunc);
  s.compareMask = d.StencilReadMask;
  s.writeMask = d.StencilWriteMask;
  s.reference = 0;  // dynamic
  return s;
}

}  // namespace

const char* ComparisonName(COMPARISON_FUNC func) {
  switch (func) {
    case COMPARISON_NEVER: return "D3D11_COMPARISON_NEVER";
    case COMPARISON_LESS: return "D3D11_COMPARISON_LESS";
    case COMPARISON_EQUAL: return "D3D11_COMPARISON_EQUAL";
    case COMPARISON_LESS_EQUAL: return "D3D11_COMPARISON_LESS_EQUAL";
    case COMPARISON_GREATER: return "D3D11_COMPARISON_GREATER";
    case COMPARISON_NOT_EQUAL: return "D3D11_COMPARISON_NOT_EQUAL";
    case COMPARISON_GREATER_EQUAL: return "D3D11_COMPARISON_GREATER_EQUAL";
    case COMPARISON_ALWAYS: return "D3D11_COMPARISON_ALWAYS";
  }
  return nullptr;
}

std::string Validate(const DEPTH_STENCIL_DESC& desc) {
  if (desc.DepthEnable) {
    if (desc.DepthWriteMask != DEPTH_WRITE_MASK_ZERO && desc.DepthWriteMask != DEPTH_WRITE_MASK_ALL)
      return std::string(kPrefix) + "DepthWriteMask: " + std::to_string(desc.DepthWriteMask) +
             " is not a valid D3D11_DEPTH_WRITE_MASK";
    if (std::string error = CheckFunc("DepthFunc", desc.DepthFunc); !error.empty()) return error;
  }
  if (desc.StencilEnable) {
    if (std::string error = ValidateFace("FrontFace", desc.FrontFace); !error.empty()) return error;
    if (std::string error = ValidateFace("BackFace", desc.BackFace); !error.empty()) return error;
  }
  return {};
}

DEPTH_STENCIL_DESC Normalize(const DEPTH_STENCIL_DESC& desc) {
  DEPTH_STENCIL_DESC out;  // member defaults are the D3D11 defaults
  out.DepthEnable = CanonicalBool(desc.DepthEnable);
  out.StencilEnable = CanonicalBool(desc.StencilEnable);
  if (out.DepthEnable) {
    out.DepthWriteMask = desc.DepthWriteMask;
    out.DepthFunc = desc.DepthFunc;
  }
  if (out.StencilEnable) {
    out.StencilReadMask = desc.StencilReadMask;
    out.StencilWriteMask = desc.StencilWriteMask;
    out.FrontFace = desc.FrontFace;
    out.BackFace = desc.BackFace;
  }
  return out;
}

bool RawEqual(const DEPTH_STENCIL_DESC& a, const DEPTH_STENCIL_DESC& b) {
  return a.DepthEnable == b.DepthEnable && a.DepthWriteMask == b.DepthWriteMask && a.DepthFunc == b.DepthFunc &&
         a.StencilEnable == b.StencilEnable && a.StencilReadMask == b.StencilReadMask &&
         a.StencilWriteMask == b.StencilWriteMask && RawEqualFace(a.FrontFace, b.FrontFace) &&
         RawEqualFace(a.BackFace, b.BackFace);
}

uint64_t RawHash(const DEPTH_STENCIL_DESC& desc) {
  Fnv1a h;
  h.Add(desc.DepthEnable);
  h.Add(desc.DepthWriteMask);
  h.Add(desc.DepthFunc);
  h.Add(desc.StencilEnable);
  h.Add(desc.StencilReadMask);
  h.Add(desc.StencilWriteMask);
  HashFace(h, desc.FrontFace);
  HashFace(h, desc.BackFace);
  return h.value();
}

bool KeyEqual(const DEPTH_STENCIL_DESC& a, const DEPTH_STENCIL_DESC& b) { return RawEqual(Normalize(a), Normalize(b)); }
uint64_t KeyHash(const DEPTH_STENCIL_DESC& desc) { return RawHash(Normalize(desc)); }

VkPipelineDepthStencilStateCreateInfo ToVulkan(const DEPTH_STENCIL_DESC& desc) {
  const DEPTH_STENCIL_DESC n = Normalize(desc);
  VkPipelineDepthStencilStateCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO;
  info.depthTestEnable = n.DepthEnable ? VK_TRUE : VK_FALSE;
  // D3D11: DepthEnable FALSE turns depth writes off too. Vulkan already ignores
  // depthWriteEnable without the test; clearing it keeps keys canonical.
  info.depthWriteEnable = (n.DepthEnable && n.DepthWriteMask == DEPTH_WRITE_MASK_ALL) ? VK_TRUE : VK_FALSE;
  info.depthCompareOp = ToVkCompareOp(n.DepthFunc);
  info.depthBoundsTestEnable = VK_FALSE;  // D3D11 has no depth bounds test
  info.stencilTestEnable = n.StencilEnable ? VK_TRUE : VK_FALSE;
  info.front = ToVkStencil(n.FrontFace, n);
  info.back = ToVkStencil(n.BackFace, n);
  info.minDepthBounds = 0.0f;
  info.maxDepthBounds = 1.0f;
  return info;
}

VkCompareOp ToVkCompareOp(COMPARISON_FUNC func) {
  switch (func) {
    case COMPARISON_NEVER: return VK_COMPARE_OP_NEVER;
    case COMPARISON_LESS: return VK_COMPARE_OP_LESS;
    case COMPARISON_EQUAL: return VK_COMPARE_OP_EQUAL;
    case COMPARISON_LESS_EQUAL: return VK_COMPARE_OP_LESS_OR_EQUAL;
    case COMPARISON_GREATER: return VK_COMPARE_OP_GREATER;
    case COMPARISON_NOT_EQUAL: return VK_COMPARE_OP_NOT_EQUAL;
    case COMPARISON_GREATER_EQUAL: return VK_COMPARE_OP_GREATER_OR_EQUAL;
    case COMPARISON_ALWAYS: return VK_COMPARE_OP_ALWAYS;
  }
  return VK_COMPARE_OP_NEVER;
}

VkStencilOp ToVkStencilOp(STENCIL_OP op) {
  switch (op) {
    case STENCIL_OP_KEEP: return VK_STENCIL_OP_KEEP;
    case STENCIL_OP_ZERO: return VK_STENCIL_OP_ZERO;
    case STENCIL_OP_REPLACE: return VK_STENCIL_OP_REPLACE;
    case STENCIL_OP_INCR_SAT: return VK_STENCIL_OP_INCREMENT_AND_CLAMP;
    case STENCIL_OP_DECR_SAT: return VK_STENCIL_OP_DECREMENT_AND_CLAMP;
    case STENCIL_OP_INVERT: return VK_STENCIL_OP_INVERT;
    case STENCIL_OP_INCR: return VK_STENCIL_OP_INCREMENT_AND_WRAP;
    case STENCIL_OP_DECR: return VK_STENCIL_OP_DECREMENT_AND_WRAP;
  }
  return VK_STENCIL_OP_KEEP;
}

}  // namespace rhi::states
