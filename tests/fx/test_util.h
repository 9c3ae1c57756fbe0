// Helpers shared by the fx front-end tests.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <map>
#include <memory>
#include <string>
#include <variant>
#include <vector>

#include "fx/effect_parser.h"
#include "fx/preprocessor.h"
#include "rhi/d3d11_types.h"

namespace fx::test {

inline std::string FormatErrors(const std::vector<ParseError>& errors) {
  std::string s;
  for (const ParseError& e : errors) s += e.Format() + "\n";
  return s;
}

// Options whose #include reads come from `files` (path -> contents).
inline ParseOptions MemoryFiles(std::map<std::string, std::string> files) {
  ParseOptions o;
  auto shared = std::make_shared<std::map<std::string, std::string>>(std::move(files));
  o.readFile = [shared](const std::string& path) -> std::optional<std::string> {
    auto it = shared->find(path);
    if (it == shared->end()) return std::nullopt;
    return it->second;
  };
  return o;
}

inline EffectAst MustParse(const std::string& source, const ParseOptions& options = {},
                           const std::string& name = "test.fx") {
  Result<EffectAst> r = ParseEffect(source, name, options);
  if (auto* e = std::get_if<std::vector<ParseError>>(&r)) {
    ADD_FAILURE() << "unexpected errors:\n" << FormatErrors(*e);
    return {};
  }
  return std::get<EffectAst>(std::move(r));
}

inline std::vector<ParseError> MustFail(const std::string& source, const ParseOptions& options = {},
                                        const std::string& name = "test.fx") {
  Result<EffectAst> r = ParseEffect(source, name, options);
  if (std::holds_alternative<EffectAst>(r)) {
    ADD_FAILURE() << "expected an error";
    return {ParseError{}};
  }
  return std::get<std::vector<ParseError>>(std::move(r));
}

inline PreprocessedSource MustPreprocess(const std::string& source, const ParseOptions& options = {},
                                         const std::string& name = "main.fx") {
  Result<PreprocessedSource> r = Preprocess(source, name, options);
  if (auto* e = std::get_if<std::vector<ParseError>>(&r)) {
    ADD_FAILURE() << "unexpected errors:\n" << FormatErrors(*e);
    return {};
  }
  return std::get<PreprocessedSource>(std::move(r));
}

inline float FloatAt(const std::vector<uint8_t>& bytes, size_t offset) {
  float f = 0;
  if (offset + 4 <= bytes.size()) std::memcpy(&f, bytes.data() + offset, 4);
  return f;
}

inline uint32_t UIntAt(const std::vector<uint8_t>& bytes, size_t offset) {
  uint32_t u = 0;
  if (offset + 4 <= bytes.size()) std::memcpy(&u, bytes.data() + offset, 4);
  return u;
}

// The token texts joined by single spaces (Pragma tokens included).
inline std::string Spelling(const PreprocessedSource& pp) {
  std::string s;
  for (const Token& t : pp.tokens) s += (s.empty() ? "" : " ") + t.text;
  return s;
}

// 1-based line and column of `offset` in `text`.
inline std::pair<int, int> LineColumn(const std::string& text, size_t offset) {
  int line = 1, column = 1;
  for (size_t i = 0; i < offset && i < text.size(); ++i) {
    if (text[i] == '\n') {
      ++line;
      column = 1;
    } else {
      ++column;
    }
  }
  return {line, column};
}

// Field-by-field desc comparisons (memcmp would compare padding bytes too).
inline ::testing::AssertionResult SameDesc(const rhi::BLEND_DESC& a, const rhi::BLEND_DESC& b) {
  if (a.AlphaToCoverageEnable != b.AlphaToCoverageEnable) return ::testing::AssertionFailure() << "AlphaToCoverageEnable";
  if (a.IndependentBlendEnable != b.IndependentBlendEnable) return ::testing::AssertionFailure() << "IndependentBlendEnable";
  for (int i = 0; i < 8; ++i) {
    const auto &x = a.RenderTarget[i], &y = b.RenderTarget[i];
    if (x.BlendEnable != y.BlendEnable || x.SrcBlend != y.SrcBlend || x.DestBlend != y.DestBlend ||
        x.BlendOp != y.BlendOp || x.SrcBlendAlpha != y.SrcBlendAlpha || x.DestBlendAlpha != y.DestBlendAlpha ||
        x.BlendOpAlpha != y.BlendOpAlpha || x.RenderTargetWriteMask != y.RenderTargetWriteMask) {
      return ::testing::AssertionFailure() << "RenderTarget[" << i << "]";
    }
  }
  return ::testing::AssertionSuccess();
}

inline ::testing::AssertionResult SameDesc(const rhi::DEPTH_STENCIL_DESC& a, const rhi::DEPTH_STENCIL_DESC& b) {
  auto sameOp = [](const rhi::DEPTH_STENCILOP_DESC& x, const rhi::DEPTH_STENCILOP_DESC& y) {
    return x.StencilFailOp == y.StencilFailOp && x.StencilDepthFailOp == y.StencilDepthFailOp &&
           x.StencilPassOp == y.StencilPassOp && x.StencilFunc == y.StencilFunc;
  };
  if (a.DepthEnable != b.DepthEnable || a.DepthWriteMask != b.DepthWriteMask || a.DepthFunc != b.DepthFunc ||
      a.StencilEnable != b.StencilEnable || a.StencilReadMask != b.StencilReadMask ||
      a.StencilWriteMask != b.StencilWriteMask || !sameOp(a.FrontFace, b.FrontFace) || !sameOp(a.BackFace, b.BackFace)) {
    return ::testing::AssertionFailure() << "depth-stencil descs differ";
  }
  return ::testing::AssertionSuccess();
}

inline ::testing::AssertionResult SameDesc(const rhi::RASTERIZER_DESC& a, const rhi::RASTERIZER_DESC& b) {
  if (a.FillMode != b.FillMode || a.CullMode != b.CullMode || a.FrontCounterClockwise != b.FrontCounterClockwise ||
      a.DepthBias != b.DepthBias || a.DepthBiasClamp != b.DepthBiasClamp ||
      a.SlopeScaledDepthBias != b.SlopeScaledDepthBias || a.DepthClipEnable != b.DepthClipEnable ||
      a.ScissorEnable != b.ScissorEnable || a.MultisampleEnable != b.MultisampleEnable ||
      a.AntialiasedLineEnable != b.AntialiasedLineEnable) {
    return ::testing::AssertionFailure() << "rasterizer descs differ";
  }
  return ::testing::AssertionSuccess();
}

inline ::testing::AssertionResult SameDesc(const rhi::SAMPLER_DESC& a, const rhi::SAMPLER_DESC& b) {
  if (a.Filter != b.Filter || a.AddressU != b.AddressU || a.AddressV != b.AddressV || a.AddressW != b.AddressW ||
      a.MipLODBias != b.MipLODBias || a.MaxAnisotropy != b.MaxAnisotropy || a.ComparisonFunc != b.ComparisonFunc ||
      a.MinLOD != b.MinLOD || a.MaxLOD != b.MaxLOD ||
      !std::equal(a.BorderColor, a.BorderColor + 4, b.BorderColor)) {
    return ::testing::AssertionFailure() << "sampler descs differ";
  }
  return ::testing::AssertionSuccess();
}

}  // namespace fx::test
