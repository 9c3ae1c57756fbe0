#include "fx/state_blocks.h"

#include <cmath>
#include <span>

namespace fx {
namespace {

using namespace rhi;

bool EqualsIgnoreCase(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (size_t i = 0; i < a.size(); ++i) {
    char x = a[i], y = b[i];
    if (x >= 'a' && x <= 'z') x = static_cast<char>(x - 'a' + 'A');
    if (y >= 'a' && y <= 'z') y = static_cast<char>(y - 'a' + 'A');
    if (x != y) return false;
  }
  return true;
}

// ---- enum values (FX11's late-resolve lists) ----

struct EnumValue {
  std::string_view name;
  UINT value;
};

struct EnumType {
  std::string_view name;    // for messages
  std::string_view prefix;  // the D3D11 name's type prefix, e.g. "BLEND_"
  std::span<const EnumValue> values;
};

constexpr EnumValue kBlendValues[] = {
    {"ZERO", BLEND_ZERO},
    {"ONE", BLEND_ONE},
    {"SRC_COLOR", BLEND_SRC_COLOR},
    {"INV_SRC_COLOR", BLEND_INV_SRC_COLOR},
    {"SRC_ALPHA", BLEND_SRC_ALPHA},
    {"INV_SRC_ALPHA", BLEND_INV_SRC_ALPHA},
    {"DEST_ALPHA", BLEND_DEST_ALPHA},
    {"INV_DEST_ALPHA", BLEND_INV_DEST_ALPHA},
    {"DEST_COLOR", BLEND_DEST_COLOR},
    {"INV_DEST_COLOR", BLEND_INV_DEST_COLOR},
    {"SRC_ALPHA_SAT", BLEND_SRC_ALPHA_SAT},
    {"BLEND_FACTOR", BLEND_BLEND_FACTOR},
    {"INV_BLEND_FACTOR", BLEND_INV_BLEND_FACTOR},
    {"SRC1_COLOR", BLEND_SRC1_COLOR},
    {"INV_SRC1_COLOR", BLEND_INV_SRC1_COLOR},
    {"SRC1_ALPHA", BLEND_SRC1_ALPHA},
    {"INV_SRC1_ALPHA", BLEND_INV_SRC1_ALPHA},
};
constexpr EnumValue kBlendOpValues[] = {
    {"ADD", BLEND_OP_ADD},  {"SUBTRACT", BLEND_OP_SUBTRACT}, {"REV_SUBTRACT", BLEND_OP_REV_SUBTRACT},
    {"MIN", BLEND_OP_MIN},  {"MAX", BLEND_OP_MAX},
};
constexpr EnumValue kComparisonValues[] = {
    {"NEVER", COMPARISON_NEVER},     {"LESS", COMPARISON_LESS},
    {"EQUAL", COMPARISON_EQUAL},     {"LESS_EQUAL", COMPARISON_LESS_EQUAL},
    {"GREATER", COMPARISON_GREATER}, {"NOT_EQUAL", COMPARISON_NOT_EQUAL},
    {"GREATER_EQUAL", COMPARISON_GREATER_EQUAL}, {"ALWAYS", COMPARISON_ALWAYS},
};
constexpr EnumValue kStencilOpValues[] = {
    {"KEEP", STENCIL_OP_KEEP},         {"ZERO", STENCIL_OP_ZERO},         {"REPLACE", STENCIL_OP_REPLACE},
    {"INCR_SAT", STENCIL_OP_INCR_SAT}, {"DECR_SAT", STENCIL_OP_DECR_SAT}, {"INVERT", STENCIL_OP_INVERT},
    {"INCR", STENCIL_OP_INCR},         {"DECR", STENCIL_OP_DECR},
};
constexpr EnumValue kDepthWriteMaskValues[] = {
    {"ZERO", DEPTH_WRITE_MASK_ZERO},
    {"ALL", DEPTH_WRITE_MASK_ALL},
};
constexpr EnumValue kFillValues[] = {{"WIREFRAME", FILL_WIREFRAME}, {"SOLID", FILL_SOLID}};
constexpr EnumValue kCullValues[] = {{"NONE", CULL_NONE}, {"FRONT", CULL_FRONT}, {"BACK", CULL_BACK}};
constexpr EnumValue kAddressValues[] = {
    {"CLAMP", TEXTURE_ADDRESS_CLAMP},   {"WRAP", TEXTURE_ADDRESS_WRAP},
    {"MIRROR", TEXTURE_ADDRESS_MIRROR}, {"BORDER", TEXTURE_ADDRESS_BORDER},
    {"MIRROR_ONCE", TEXTURE_ADDRESS_MIRROR_ONCE},
};
constexpr EnumValue kFilterValues[] = {
    {"MIN_MAG_MIP_POINT", FILTER_MIN_MAG_MIP_POINT},
    {"MIN_MAG_POINT_MIP_LINEAR", FILTER_MIN_MAG_POINT_MIP_LINEAR},
    {"MIN_POINT_MAG_LINEAR_MIP_POINT", FILTER_MIN_POINT_MAG_LINEAR_MIP_POINT},
    {"MIN_POINT_MAG_MIP_LINEAR", FILTER_MIN_POINT_MAG_MIP_LINEAR},
    {"MIN_LINEAR_MAG_MIP_POINT", FILTER_MIN_LINEAR_MAG_MIP_POINT},
    {"MIN_LINEAR_MAG_POINT_MIP_LINEAR", FILTER_MIN_LINEAR_MAG_POINT_MIP_LINEAR},
    {"MIN_MAG_LINEAR_MIP_POINT", FILTER_MIN_MAG_LINEAR_MIP_POINT},
    {"MIN_MAG_MIP_LINEAR", FILTER_MIN_MAG_MIP_LINEAR},
    {"ANISOTROPIC", FILTER_ANISOTROPIC},
    {"COMPARISON_MIN_MAG_MIP_POINT", FILTER_COMPARISON_MIN_MAG_MIP_POINT},
    {"COMPARISON_MIN_MAG_POINT_MIP_LINEAR", FILTER_COMPARISON_MIN_MAG_POINT_MIP_LINEAR},
    {"COMPARISON_MIN_POINT_MAG_LINEAR_MIP_POINT", FILTER_COMPARISON_MIN_POINT_MAG_LINEAR_MIP_POINT},
    {"COMPARISON_MIN_POINT_MAG_MIP_LINEAR", FILTER_COMPARISON_MIN_POINT_MAG_MIP_LINEAR},
    {"COMPARISON_MIN_LINEAR_MAG_MIP_POINT", FILTER_COMPARISON_MIN_LINEAR_MAG_MIP_POINT},
    {"COMPARISON_MIN_LINEAR_MAG_POINT_MIP_LINEAR", FILTER_COMPARISON_MIN_LINEAR_MAG_POINT_MIP_LINEAR},
    {"COMPARISON_MIN_MAG_LINEAR_MIP_POINT", FILTER_COMPARISON_MIN_MAG_LINEAR_MIP_POINT},
    {"COMPARISON_MIN_MAG_MIP_LINEAR", FILTER_COMPARISON_MIN_MAG_MIP_LINEAR},
    {"COMPARISON_ANISOTROPIC", FILTER_COMPARISON_ANISOTROPIC},
};

constexpr EnumType kBlend{"blend", "BLEND_", kBlendValues};
constexpr EnumType kBlendOp{"blend operation", "BLEND_OP_", kBlendOpValues};
constexpr EnumType kComparison{"comparison", "COMPARISON_", kComparisonValues};
constexpr EnumType kStencilOp{"stencil operation", "STENCIL_OP_", kStencilOpValues};
constexpr EnumType kDepthWriteMask{"depth write mask", "DEPTH_WRITE_MASK_", kDepthWriteMaskValues};
constexpr EnumType kFill{"fill mode", "FILL_", kFillValues};
constexpr EnumType kCull{"cull mode", "CULL_", kCullValues};
constexpr EnumType kAddress{"texture address mode", "TEXTURE_ADDRESS_", kAddressValues};
constexpr EnumType kFilter{"filter", "FILTER_", kFilterValues};

// VALUE, TYPE_VALUE, D3D11_TYPE_VALUE or D3D10_TYPE_VALUE, in any case.
bool MatchesEnumName(std::string_view id, const EnumType& type, std::string_view value) {
  if (EqualsIgnoreCase(id, value)) return true;
  for (std::string_view api : {std::string_view(""), std::string_view("D3D11_"), std::string_view("D3D10_")}) {
    size_t prefix = api.size() + type.prefix.size();
    if (id.size() == prefix + value.size() && EqualsIgnoreCase(id.substr(0, api.size()), api) &&
        EqualsIgnoreCase(id.substr(api.size(), type.prefix.size()), type.prefix) &&
        EqualsIgnoreCase(id.substr(prefix), value)) {
      return true;
    }
  }
  return false;
}

// ---- members ----

enum class ValueKind { Bool, Enum, UInt, UInt8, Int, Float, Float4 };

struct Resolved {
  UINT u = 0;
  INT i = 0;
  float f = 0;
  float f4[4] = {};
};

template <class Desc>
struct Member {
  std::string_view name;
  ValueKind kind;
  const EnumType* type;  // Enum only
  UINT count;            // 8 for per-render-target members, else 1
  void (*set)(Desc&, UINT index, const Resolved&);
};

using BD = BLEND_DESC;
using DSD = DEPTH_STENCIL_DESC;
using RD = RASTERIZER_DESC;
using SD = SAMPLER_DESC;
using V = const Resolved&;
constexpr UINT kRT = SIMULTANEOUS_RENDER_TARGET_COUNT;

const Member<BD> kBlendMembers[] = {
    {"AlphaToCoverageEnable", ValueKind::Bool, nullptr, 1, [](BD& d, UINT, V v) { d.AlphaToCoverageEnable = v.i; }},
    {"BlendEnable", ValueKind::Bool, nullptr, kRT, [](BD& d, UINT n, V v) { d.RenderTarget[n].BlendEnable = v.i; }},
    {"SrcBlend", ValueKind::Enum, &kBlend, kRT, [](BD& d, UINT n, V v) { d.RenderTarget[n].SrcBlend = BLEND(v.u); }},
    {"DestBlend", ValueKind::Enum, &kBlend, kRT, [](BD& d, UINT n, V v) { d.RenderTarget[n].DestBlend = BLEND(v.u); }},
    {"BlendOp", ValueKind::Enum, &kBlendOp, kRT, [](BD& d, UINT n, V v) { d.RenderTarget[n].BlendOp = BLEND_OP(v.u); }},
    {"SrcBlendAlpha", ValueKind::Enum, &kBlend, kRT,
     [](BD& d, UINT n, V v) { d.RenderTarget[n].SrcBlendAlpha = BLEND(v.u); }},
    {"DestBlendAlpha", ValueKind::Enum, &kBlend, kRT,
     [](BD& d, UINT n, V v) { d.RenderTarget[n].DestBlendAlpha = BLEND(v.u); }},
    {"BlendOpAlpha", ValueKind::Enum, &kBlendOp, kRT,
     [](BD& d, UINT n, V v) { d.RenderTarget[n].BlendOpAlpha = BLEND_OP(v.u); }},
    {"RenderTargetWriteMask", ValueKind::UInt8, nullptr, kRT,
     [](BD& d, UINT n, V v) { d.RenderTarget[n].RenderTargetWriteMask = UINT8(v.u); }},
};

const Member<DSD> kDepthStencilMembers[] = {
    {"DepthEnable", ValueKind::Bool, nullptr, 1, [](DSD& d, UINT, V v) { d.DepthEnable = v.i; }},
    {"DepthWriteMask", ValueKind::Enum, &kDepthWriteMask, 1,
     [](DSD& d, UINT, V v) { d.DepthWriteMask = DEPTH_WRITE_MASK(v.u); }},
    {"DepthFunc", ValueKind::Enum, &kComparison, 1, [](DSD& d, UINT, V v) { d.DepthFunc = COMPARISON_FUNC(v.u); }},
    {"StencilEnable", ValueKind::Bool, nullptr, 1, [](DSD& d, UINT, V v) { d.StencilEnable = v.i; }},
    {"StencilReadMask", ValueKind::UInt8, nullptr, 1, [](DSD& d, UINT, V v) { d.StencilReadMask = UINT8(v.u); }},
    {"StencilWriteMask", ValueKind::UInt8, nullptr, 1, [](DSD& d, UINT, V v) { d.StencilWriteMask = UINT8(v.u); }},
    {"FrontFaceStencilFail", ValueKind::Enum, &kStencilOp, 1,
     [](DSD& d, UINT, V v) { d.FrontFace.StencilFailOp = STENCIL_OP(v.u); }},
    {"FrontFaceStencilDepthFail", ValueKind::Enum, &kStencilOp, 1,
     [](DSD& d, UINT, V v) { d.FrontFace.StencilDepthFailOp = STENCIL_OP(v.u); }},
    {"FrontFaceStencilPass", ValueKind::Enum, &kStencilOp, 1,
     [](DSD& d, UINT, V v) { d.FrontFace.StencilPassOp = STENCIL_OP(v.u); }},
    {"FrontFaceStencilFunc", ValueKind::Enum, &kComparison, 1,
     [](DSD& d, UINT, V v) { d.FrontFace.StencilFunc = COMPARISON_FUNC(v.u); }},
    {"BackFaceStencilFail", ValueKind::Enum, &kStencilOp, 1,
     [](DSD& d, UINT, V v) { d.BackFace.StencilFailOp = STENCIL_OP(v.u); }},
    {"BackFaceStencilDepthFail", ValueKind::Enum, &kStencilOp, 1,
     [](DSD& d, UINT, V v) { d.BackFace.StencilDepthFailOp = STENCIL_OP(v.u); }},
    {"BackFaceStencilPass", ValueKind::Enum, &kStencilOp, 1,
     [](DSD& d, UINT, V v) { d.BackFace.StencilPassOp = STENCIL_OP(v.u); }},
    {"BackFaceStencilFunc", ValueKind::Enum, &kComparison, 1,
     [](DSD& d, UINT, V v) { d.BackFace.StencilFunc = COMPARISON_FUNC(v.u); }},
};

const Member<RD> kRasterizerMembers[] = {
    {"FillMode", ValueKind::Enum, &kFill, 1, [](RD& d, UINT, V v) { d.FillMode = FILL_MODE(v.u); }},
    {"CullMode", ValueKind::Enum, &kCull, 1, [](RD& d, UINT, V v) { d.CullMode = CULL_MODE(v.u); }},
    {"FrontCounterClockwise", ValueKind::Bool, nullptr, 1, [](RD& d, UINT, V v) { d.FrontCounterClockwise = v.i; }},
    {"DepthBias", ValueKind::Int, nullptr, 1, [](RD& d, UINT, V v) { d.DepthBias = v.i; }},
    {"DepthBiasClamp", ValueKind::Float, nullptr, 1, [](RD& d, UINT, V v) { d.DepthBiasClamp = v.f; }},
    {"SlopeScaledDepthBias", ValueKind::Float, nullptr, 1, [](RD& d, UINT, V v) { d.SlopeScaledDepthBias = v.f; }},
    {"DepthClipEnable", ValueKind::Bool, nullptr, 1, [](RD& d, UINT, V v) { d.DepthClipEnable = v.i; }},
    {"ScissorEnable", ValueKind::Bool, nullptr, 1, [](RD& d, UINT, V v) { d.ScissorEnable = v.i; }},
    {"MultisampleEnable", ValueKind::Bool, nullptr, 1, [](RD& d, UINT, V v) { d.MultisampleEnable = v.i; }},
    {"AntialiasedLineEnable", ValueKind::Bool, nullptr, 1, [](RD& d, UINT, V v) { d.AntialiasedLineEnable = v.i; }},
};

const Member<SD> kSamplerMembers[] = {
    {"Filter", ValueKind::Enum, &kFilter, 1, [](SD& d, UINT, V v) { d.Filter = FILTER(v.u); }},
    {"AddressU", ValueKind::Enum, &kAddress, 1, [](SD& d, UINT, V v) { d.AddressU = TEXTURE_ADDRESS_MODE(v.u); }},
    {"AddressV", ValueKind::Enum, &kAddress, 1, [](SD& d, UINT, V v) { d.AddressV = TEXTURE_ADDRESS_MODE(v.u); }},
    {"AddressW", ValueKind::Enum, &kAddress, 1, [](SD& d, UINT, V v) { d.AddressW = TEXTURE_ADDRESS_MODE(v.u); }},
    {"MipLODBias", ValueKind::Float, nullptr, 1, [](SD& d, UINT, V v) { d.MipLODBias = v.f; }},
    {"MaxAnisotropy", ValueKind::UInt, nullptr, 1, [](SD& d, UINT, V v) { d.MaxAnisotropy = v.u; }},
    {"ComparisonFunc", ValueKind::Enum, &kComparison, 1,
     [](SD& d, UINT, V v) { d.ComparisonFunc = COMPARISON_FUNC(v.u); }},
    {"BorderColor", ValueKind::Float4, nullptr, 1,
     [](SD& d, UINT, V v) { std::copy(v.f4, v.f4 + 4, d.BorderColor); }},
    {"MinLOD", ValueKind::Float, nullptr, 1, [](SD& d, UINT, V v) { d.MinLOD = v.f; }},
    {"MaxLOD", ValueKind::Float, nullptr, 1, [](SD& d, UINT, V v) { d.MaxLOD = v.f; }},
};

StateError ValueError(std::string message) { return StateError{StateError::Part::Value, std::move(message)}; }

std::string Describe(const StateValue& v) {
  if (!v.identifier.empty()) return "'" + v.identifier + "'";
  std::string s;
  for (double d : v.numbers) {
    if (!s.empty()) s += ", ";
    char buf[32];
    snprintf(buf, sizeof buf, "%g", d);
    s += buf;
  }
  return v.numbers.size() == 1 ? s : "(" + s + ")";
}

// A single integral number within [lo, hi].
std::optional<int64_t> Integral(const StateValue& v, int64_t lo, int64_t hi) {
  if (!v.identifier.empty() || v.numbers.size() != 1) return std::nullopt;
  double d = v.numbers[0];
  if (!(d >= static_cast<double>(lo) && d <= static_cast<double>(hi)) || d != std::floor(d)) return std::nullopt;
  return static_cast<int64_t>(d);
}

template <class Desc>
std::optional<StateError> Resolve(const Member<Desc>& m, const StateValue& v, Resolved& out) {
  std::string name(m.name);
  switch (m.kind) {
    case ValueKind::Bool:
      if (EqualsIgnoreCase(v.identifier, "TRUE") || EqualsIgnoreCase(v.identifier, "FALSE")) {
        out.i = EqualsIgnoreCase(v.identifier, "TRUE") ? TRUE : FALSE;
      } else if (v.identifier.empty() && v.numbers.size() == 1) {
        out.i = v.numbers[0] != 0 ? TRUE : FALSE;
      } else {
        return ValueError("invalid value " + Describe(v) + " for " + name + " (expected TRUE or FALSE)");
      }
      return std::nullopt;
    case ValueKind::Enum: {
      for (const EnumValue& e : m.type->values) {
        bool numberMatch = v.identifier.empty() && Integral(v, 0, UINT32_MAX) == static_cast<int64_t>(e.value);
        if (numberMatch || (!v.identifier.empty() && MatchesEnumName(v.identifier, *m.type, e.name))) {
          out.u = e.value;
          return std::nullopt;
        }
      }
      return ValueError("invalid value " + Describe(v) + " for " + name + " (not a " +
                        std::string(m.type->name) + " value)");
    }
    case ValueKind::UInt:
    case ValueKind::UInt8:
    case ValueKind::Int: {
      int64_t lo = m.kind == ValueKind::Int ? INT32_MIN : 0;
      int64_t hi = m.kind == ValueKind::UInt8 ? 255 : m.kind == ValueKind::Int ? INT32_MAX : UINT32_MAX;
      std::optional<int64_t> n = Integral(v, lo, hi);
      if (!n) {
        return ValueError("invalid value " + Describe(v) + " for " + name + " (expected an integer in " +
                          std::to_string(lo) + ".." + std::to_string(hi) + ")");
      }
      out.u = static_cast<UINT>(*n);
      out.i = static_cast<INT>(*n);
      return std::nullopt;
    }
    case ValueKind::Float:
      if (!v.identifier.empty() || v.numbers.size() != 1) {
        return ValueError("invalid value " + Describe(v) + " for " + name + " (expected a number)");
      }
      out.f = static_cast<float>(v.numbers[0]);
      return std::nullopt;
    case ValueKind::Float4:
      if (!v.identifier.empty() || (v.numbers.size() != 4 && v.numbers.size() != 1)) {
        return ValueError("invalid value " + Describe(v) + " for " + name + " (expected a float4)");
      }
      for (int i = 0; i < 4; ++i) out.f4[i] = static_cast<float>(v.numbers[v.numbers.size() == 1 ? 0 : i]);
      return std::nullopt;
  }
  return ValueError("unsupported value");
}

template <class Desc, size_t N>
std::optional<StateError> Apply(const Member<Desc> (&members)[N], std::string_view block, Desc& desc,
                                std::string_view member, std::optional<uint32_t> index, const StateValue& value) {
  for (const Member<Desc>& m : members) {
    if (!EqualsIgnoreCase(m.name, member)) continue;
    UINT i = index.value_or(0);
    if (i >= m.count) {
      return StateError{StateError::Part::Index, "index " + std::to_string(i) + " out of range for " +
                                                     std::string(m.name) + " (0.." + std::to_string(m.count - 1) + ")"};
    }
    Resolved r;
    if (std::optional<StateError> e = Resolve(m, value, r)) return e;
    m.set(desc, i, r);
    return std::nullopt;
  }
  return StateError{StateError::Part::Member, "unknown " + std::string(block) + " member '" + std::string(member) + "'"};
}

}  // namespace

BLEND_DESC DefaultBlendDesc() {
  BLEND_DESC d;
  d.IndependentBlendEnable = TRUE;
  return d;
}

DEPTH_STENCIL_DESC DefaultDepthStencilDesc() { return DEPTH_STENCIL_DESC{}; }

RASTERIZER_DESC DefaultRasterizerDesc() { return RASTERIZER_DESC{}; }

SAMPLER_DESC DefaultSamplerDesc() {
  SAMPLER_DESC d;
  d.MaxAnisotropy = 16;  // D3D11_DEFAULT_MAX_ANISOTROPY
  std::fill(d.BorderColor, d.BorderColor + 4, 0.0f);  // D3D11_DEFAULT_BORDER_COLOR_COMPONENT
  return d;
}

std::optional<StateError> ApplyStateAssignment(BLEND_DESC& desc, std::string_view member,
                                               std::optional<uint32_t> index, const StateValue& value) {
  return Apply(kBlendMembers, "BlendState", desc, member, index, value);
}

std::optional<StateError> ApplyStateAssignment(DEPTH_STENCIL_DESC& desc, std::string_view member,
                                               std::optional<uint32_t> index, const StateValue& value) {
  return Apply(kDepthStencilMembers, "DepthStencilState", desc, member, index, value);
}

std::optional<StateError> ApplyStateAssignment(RASTERIZER_DESC& desc, std::string_view member,
                                               std::optional<uint32_t> index, const StateValue& value) {
  return Apply(kRasterizerMembers, "RasterizerState", desc, member, index, value);
}

std::optional<StateError> ApplyStateAssignment(SAMPLER_DESC& desc, std::string_view member,
                                               std::optional<uint32_t> index, const StateValue& value) {
  // D3D9 effects' sampler states, which fx_5_0 (FX11's state table) does not know.
  for (std::string_view d3d9 : {"MinFilter", "MagFilter", "MipFilter", "MipMapLodBias", "MaxMipLevel", "SRGBTexture"}) {
    if (EqualsIgnoreCase(d3d9, member)) {
      return StateError{StateError::Part::Member,
                        "'" + std::string(member) + "' is a D3D9 sampler state, not fx_5_0's: write Filter = " +
                            "MIN_MAG_MIP_LINEAR (etc.), MipLODBias, MaxLOD as D3D11 names them"};
    }
  }
  return Apply(kSamplerMembers, "SamplerState", desc, member, index, value);
}

}  // namespace fx
