// fxtool: names of D3D11 enums and the non-default fields of state descs.
#pragma once

#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "fx/effect_ast.h"
#include "rhi/d3d11_types.h"
#include "rhi/format_info.h"
#include "rhi_reference/formats.h"

namespace fxtool {

inline const char* BlendName(rhi::BLEND b) {
  switch (b) {
    case rhi::BLEND_ZERO: return "ZERO";
    case rhi::BLEND_ONE: return "ONE";
    case rhi::BLEND_SRC_COLOR: return "SRC_COLOR";
    case rhi::BLEND_INV_SRC_COLOR: return "INV_SRC_COLOR";
    case rhi::BLEND_SRC_ALPHA: return "SRC_ALPHA";
    case rhi::BLEND_INV_SRC_ALPHA: return "INV_SRC_ALPHA";
    case rhi::BLEND_DEST_ALPHA: return "DEST_ALPHA";
    case rhi::BLEND_INV_DEST_ALPHA: return "INV_DEST_ALPHA";
    case rhi::BLEND_DEST_COLOR: return "DEST_COLOR";
    case rhi::BLEND_INV_DEST_COLOR: return "INV_DEST_COLOR";
    case rhi::BLEND_SRC_ALPHA_SAT: return "SRC_ALPHA_SAT";
    case rhi::BLEND_BLEND_FACTOR: return "BLEND_FACTOR";
    case rhi::BLEND_INV_BLEND_FACTOR: return "INV_BLEND_FACTOR";
    case rhi::BLEND_SRC1_COLOR: return "SRC1_COLOR";
    case rhi::BLEND_INV_SRC1_COLOR: return "INV_SRC1_COLOR";
    case rhi::BLEND_SRC1_ALPHA: return "SRC1_ALPHA";
    case rhi::BLEND_INV_SRC1_ALPHA: return "INV_SRC1_ALPHA";
  }
  return "?";
}

inline const char* BlendOpName(rhi::BLEND_OP op) {
  switch (op) {
    case rhi::BLEND_OP_ADD: return "ADD";
    case rhi::BLEND_OP_SUBTRACT: return "SUBTRACT";
    case rhi::BLEND_OP_REV_SUBTRACT: return "REV_SUBTRACT";
    case rhi::BLEND_OP_MIN: return "MIN";
    case rhi::BLEND_OP_MAX: return "MAX";
  }
  return "?";
}

inline const char* ComparisonName(rhi::COMPARISON_FUNC f) {
  static const char* names[] = {"?", "NEVER", "LESS", "EQUAL", "LESS_EQUAL", "GREATER", "NOT_EQUAL", "GREATER_EQUAL", "ALWAYS"};
  return f >= 1 && f <= 8 ? names[f] : "?";
}

inline const char* StencilOpName(rhi::STENCIL_OP op) {
  static const char* names[] = {"?", "KEEP", "ZERO", "REPLACE", "INCR_SAT", "DECR_SAT", "INVERT", "INCR", "DECR"};
  return op >= 1 && op <= 8 ? names[op] : "?";
}

inline const char* StageName(fx::ShaderStage s) {
  static const char* names[] = {"vs", "hs", "ds", "gs", "ps", "cs"};
  return names[static_cast<int>(s)];
}

inline std::string Bool(rhi::BOOL b) { return b ? "TRUE" : "FALSE"; }
inline std::string Hex(unsigned v) {
  char buf[16];
  std::snprintf(buf, sizeof buf, "0x%02X", v);
  return buf;
}
inline std::string Num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

// "Field=VALUE" for every field that differs from the D3D11 default.
inline std::vector<std::string> NonDefault(const rhi::BLEND_DESC& d) {
  std::vector<std::string> out;
  const rhi::BLEND_DESC def;
  if (d.AlphaToCoverageEnable != def.AlphaToCoverageEnable) out.push_back("AlphaToCoverageEnable=" + Bool(d.AlphaToCoverageEnable));
  if (d.IndependentBlendEnable != def.IndependentBlendEnable) out.push_back("IndependentBlendEnable=" + Bool(d.IndependentBlendEnable));
  const unsigned n = d.IndependentBlendEnable ? rhi::SIMULTANEOUS_RENDER_TARGET_COUNT : 1;
  for (unsigned i = 0; i < n; ++i) {
    const auto& r = d.RenderTarget[i];
    const auto& e = def.RenderTarget[i];
    const std::string p = "RenderTarget[" + std::to_string(i) + "].";
    if (r.BlendEnable != e.BlendEnable) out.push_back(p + "BlendEnable=" + Bool(r.BlendEnable));
    if (r.SrcBlend != e.SrcBlend) out.push_back(p + "SrcBlend=" + BlendName(r.SrcBlend));
    if (r.DestBlend != e.DestBlend) out.push_back(p + "DestBlend=" + BlendName(r.DestBlend));
    if (r.BlendOp != e.BlendOp) out.push_back(p + "BlendOp=" + BlendOpName(r.BlendOp));
    if (r.SrcBlendAlpha != e.SrcBlendAlpha) out.push_back(p + "SrcBlendAlpha=" + BlendName(r.SrcBlendAlpha));
    if (r.DestBlendAlpha != e.DestBlendAlpha) out.push_back(p + "DestBlendAlpha=" + BlendName(r.DestBlendAlpha));
    if (r.BlendOpAlpha != e.BlendOpAlpha) out.push_back(p + "BlendOpAlpha=" + BlendOpName(r.BlendOpAlpha));
    if (r.RenderTargetWriteMask != e.RenderTargetWriteMask) out.push_back(p + "RenderTargetWriteMask=" + Hex(r.RenderTargetWriteMask));
  }
  return out;
}

inline void StencilFace(std::vector<std::string>& out, const char* face, const rhi::DEPTH_STENCILOP_DESC& f) {
  const rhi::DEPTH_STENCILOP_DESC e;
  const std::string p = std::string(face) + ".";
  if (f.StencilFailOp != e.StencilFailOp) out.push_back(p + "StencilFailOp=" + StencilOpName(f.StencilFailOp));
  if (f.StencilDepthFailOp != e.StencilDepthFailOp) out.push_back(p + "StencilDepthFailOp=" + StencilOpName(f.StencilDepthFailOp));
  if (f.StencilPassOp != e.StencilPassOp) out.push_back(p + "StencilPassOp=" + StencilOpName(f.StencilPassOp));
  if (f.StencilFunc != e.StencilFunc) out.push_back(p + "StencilFunc=" + ComparisonName(f.StencilFunc));
}

inline std::vector<std::string> NonDefault(const rhi::DEPTH_STENCIL_DESC& d) {
  std::vector<std::string> out;
  const rhi::DEPTH_STENCIL_DESC def;
  if (d.DepthEnable != def.DepthEnable) out.push_back("DepthEnable=" + Bool(d.DepthEnable));
  if (d.DepthWriteMask != def.DepthWriteMask) out.push_back(std::string("DepthWriteMask=") + (d.DepthWriteMask ? "ALL" : "ZERO"));
  if (d.DepthFunc != def.DepthFunc) out.push_back(std::string("DepthFunc=") + ComparisonName(d.DepthFunc));
  if (d.StencilEnable != def.StencilEnable) out.push_back("StencilEnable=" + Bool(d.StencilEnable));
  if (d.StencilReadMask != def.StencilReadMask) out.push_back("StencilReadMask=" + Hex(d.StencilReadMask));
  if (d.StencilWriteMask != def.StencilWriteMask) out.push_back("StencilWriteMask=" + Hex(d.StencilWriteMask));
  StencilFace(out, "FrontFace", d.FrontFace);
  StencilFace(out, "BackFace", d.BackFace);
  return out;
}

inline std::vector<std::string> NonDefault(const rhi::RASTERIZER_DESC& d) {
  std::vector<std::string> out;
  const rhi::RASTERIZER_DESC def;
  if (d.FillMode != def.FillMode) out.push_back(std::string("FillMode=") + (d.FillMode == rhi::FILL_WIREFRAME ? "WIREFRAME" : "SOLID"));
  if (d.CullMode != def.CullMode)
    out.push_back(std::string("CullMode=") + (d.CullMode == rhi::CULL_NONE ? "NONE" : d.CullMode == rhi::CULL_FRONT ? "FRONT" : "BACK"));
  if (d.FrontCounterClockwise != def.FrontCounterClockwise) out.push_back("FrontCounterClockwise=" + Bool(d.FrontCounterClockwise));
  if (d.DepthBias != def.DepthBias) out.push_back("DepthBias=" + std::to_string(d.DepthBias));
  if (d.DepthBiasClamp != def.DepthBiasClamp) out.push_back("DepthBiasClamp=" + Num(d.DepthBiasClamp));
  if (d.SlopeScaledDepthBias != def.SlopeScaledDepthBias) out.push_back("SlopeScaledDepthBias=" + Num(d.SlopeScaledDepthBias));
  if (d.DepthClipEnable != def.DepthClipEnable) out.push_back("DepthClipEnable=" + Bool(d.DepthClipEnable));
  if (d.ScissorEnable != def.ScissorEnable) out.push_back("ScissorEnable=" + Bool(d.ScissorEnable));
  if (d.MultisampleEnable != def.MultisampleEnable) out.push_back("MultisampleEnable=" + Bool(d.MultisampleEnable));
  if (d.AntialiasedLineEnable != def.AntialiasedLineEnable) out.push_back("AntialiasedLineEnable=" + Bool(d.AntialiasedLineEnable));
  return out;
}

struct FormatName {
  const char* name;
  rhi::DXGI_FORMAT format;
};

// The render-target formats fxtool accepts: every typed format the RHI's format table
// lets one render to (rhi::FormatBindFlags) that rhi::reference can decode for printing.
inline const std::vector<FormatName>& TargetFormats() {
  static const std::vector<FormatName> formats = [] {
    std::vector<FormatName> list;
    for (rhi::UINT value = 1; value < 256; ++value) {
      const auto format = static_cast<rhi::DXGI_FORMAT>(value);
      if (!(rhi::FormatBindFlags(format) & rhi::BIND_RENDER_TARGET) || rhi::IsTypeless(format) ||
          !rhi::reference::IsReferenceFormat(format))
        continue;
      list.push_back({rhi::FormatName(format) + std::strlen("DXGI_FORMAT_"), format});
    }
    return list;
  }();
  return formats;
}

}  // namespace fxtool
