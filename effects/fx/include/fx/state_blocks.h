// FX11 state blocks: the members fxc accepts inside SamplerState, BlendState,
// DepthStencilState and RasterizerState declarations, their values, and the
// descs a block starts from.
//
// Members (case-insensitive, FX11 names; [n] marks members indexed by render target):
//   Blend:        AlphaToCoverageEnable, BlendEnable[8], SrcBlend[8], DestBlend[8],
//                 BlendOp[8], SrcBlendAlpha[8], DestBlendAlpha[8], BlendOpAlpha[8],
//                 RenderTargetWriteMask[8]
//   DepthStencil: DepthEnable, DepthWriteMask, DepthFunc, StencilEnable, StencilReadMask,
//                 StencilWriteMask, FrontFaceStencil{Fail,DepthFail,Pass,Func},
//                 BackFaceStencil{Fail,DepthFail,Pass,Func}
//   Rasterizer:   FillMode, CullMode, FrontCounterClockwise, DepthBias, DepthBiasClamp,
//                 SlopeScaledDepthBias, DepthClipEnable, ScissorEnable,
//                 MultisampleEnable, AntialiasedLineEnable
//   Sampler:      Filter, AddressU, AddressV, AddressW, MipLODBias, MaxAnisotropy,
//                 ComparisonFunc, BorderColor, MinLOD, MaxLOD
// (The sampler's FX10 `Texture = <t>;` binding is not a desc member; the effect
// parser records it.)
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "rhi/d3d11_types.h"

namespace fx {

// FX11's initial descs (its SBlendBlock / SSamplerBlock / ... constructors).
// They equal the D3D11 defaults except in three fields, where FX11 differs and
// this follows FX11: BLEND_DESC::IndependentBlendEnable is TRUE (so `BlendEnable
// = TRUE`, which sets render target 0, leaves targets 1-7 unblended), and
// SAMPLER_DESC has MaxAnisotropy 16 and BorderColor (0,0,0,0).
rhi::BLEND_DESC DefaultBlendDesc();
rhi::DEPTH_STENCIL_DESC DefaultDepthStencilDesc();
rhi::RASTERIZER_DESC DefaultRasterizerDesc();
rhi::SAMPLER_DESC DefaultSamplerDesc();

// The right-hand side of `Member[index] = value;`.
struct StateValue {
  std::string identifier;       // a bare name: TRUE, Wrap, D3D11_BLEND_ONE, ...; empty if numeric
  std::vector<double> numbers;  // the constant-folded components of a numeric value
};

struct StateError {
  enum class Part { Member, Index, Value };
  Part part = Part::Member;  // which part of the assignment the message is about
  std::string message;
};

// Applies one assignment; nullopt on success. Enum values are case-insensitive
// and may carry the D3D11_/D3D10_ prefix and their type prefix
// (D3D11_BLEND_SRC_ALPHA, BLEND_SRC_ALPHA and SRC_ALPHA all work); numbers that
// are valid enum values are accepted too. Booleans are TRUE/FALSE (any case) or
// numbers. An omitted index means 0, as in FX11.
std::optional<StateError> ApplyStateAssignment(rhi::BLEND_DESC& desc, std::string_view member,
                                               std::optional<uint32_t> index, const StateValue& value);
std::optional<StateError> ApplyStateAssignment(rhi::DEPTH_STENCIL_DESC& desc, std::string_view member,
                                               std::optional<uint32_t> index, const StateValue& value);
std::optional<StateError> ApplyStateAssignment(rhi::RASTERIZER_DESC& desc, std::string_view member,
                                               std::optional<uint32_t> index, const StateValue& value);
std::optional<StateError> ApplyStateAssignment(rhi::SAMPLER_DESC& desc, std::string_view member,
                                               std::optional<uint32_t> index, const StateValue& value);

}  // namespace fx
