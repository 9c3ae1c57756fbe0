// Parses an fx_5_0 effect (.fx), as fxc accepts it, into an EffectAst.
//
// Not supported (each is reported as an error at its position): interfaces and
// classes (dynamic shader linkage, BindInterfaces), shader arrays indexed by a
// variable in a pass, state values that depend on non-constant variables,
// FX9-style pass assignments (`VertexShader = compile vs_2_0 VS();` - write
// SetVertexShader(...); the `compile profile F()` expression itself is
// accepted), RenderTargetView / DepthStencilView / GenerateMips pass states,
// nested struct definitions, and D3D9 sampling: D3D9 sampler states
// (MinFilter, ...) and tex2D-style functions (fxc takes them in shader model 4
// and 5 only under /Gec, and D3D11 cannot bind the combined samplers).
//
// What fxc accepts and glslang does not is rewritten in the HLSL it gets:
// static declarations inside a cbuffer move before it, object types spelled
// in another case (texture2D) get glslang's spelling, and an entry point with
// uniform parameters or overloads is reached through a generated wrapper.
#pragma once

#include <string>

#include "fx/diagnostics.h"
#include "fx/effect_ast.h"
#include "fx/preprocessor.h"

namespace fx {

// `fileName` names the source in positions and anchors relative #includes
// (read with options.readFile, or from disk).
Result<EffectAst> ParseEffect(const std::string& source, const std::string& fileName, const ParseOptions& options);

// Reads `path` (with options.readFile when set) and parses it.
Result<EffectAst> ParseEffectFile(const std::string& path, const ParseOptions& options);

}  // namespace fx
