// Module patches the D3D11 layer applies before creating Vulkan pipelines.
// Each takes the module's words and returns new words (the input is never
// modified), or an error for a module it cannot patch. All expect modules as
// glslang produces them: one entry point, SPIR-V 1.0-1.6, logical addressing;
// they work on modules before and after SPIRV-Tools legalization.
#pragma once

#include <cstdint>
#include <map>
#include <span>

#include "spirv/result.h"

namespace rhi::spirv {

// The two storage classes RemapLocations works on (values are spv::StorageClass).
enum class StorageClass : uint32_t { Input = 1, Output = 3 };

// Removes what only VK_GOOGLE_hlsl_functionality1 / VK_GOOGLE_user_type
// drivers accept: UserSemantic and UserTypeGOOGLE (OpDecorateString,
// OpMemberDecorateString), CounterBuffer (OpDecorateId), and the
// SPV_GOOGLE_hlsl_functionality1 / SPV_GOOGLE_user_type extensions
// (SPV_GOOGLE_decorate_string too once no OpDecorateString is left).
// Reflect first: reflection needs the semantics this removes.
WordsResult StripHlslDecorations(std::span<const uint32_t> words);

// Rewrites the Location of every variable of `storage` whose location is a
// key of `oldToNew` (OpDecorate, and OpMemberDecorate of IO blocks used only
// by that storage class). Locations not in the map are kept. Used to link
// stages by semantic: give each semantic one location in both stages.
WordsResult RemapLocations(std::span<const uint32_t> words, StorageClass storage,
                           const std::map<uint32_t, uint32_t>& oldToNew);

// D3D's SV_InstanceID counts from 0 in every draw, Vulkan's InstanceIndex
// includes firstInstance: every OpLoad of the InstanceIndex built-in becomes
// InstanceIndex - BaseInstance (a BaseInstance built-in input is added, with
// capability DrawParameters, plus SPV_KHR_shader_draw_parameters below SPIR-V
// 1.3). The device needs the shaderDrawParameters feature (Vulkan 1.1).
// Returns the words unchanged when InstanceIndex is never loaded.
WordsResult RebaseInstanceIndex(std::span<const uint32_t> words);

// Vulkan (without maintenance5) leaves the point size undefined unless the
// last pre-rasterization stage writes PointSize when it draws points; D3D
// always draws 1-pixel points. Adds a PointSize output written with 1.0: for
// VS/DS at the start of the entry function (after its variables), for GS
// before every OpEmitVertex / OpEmitStreamVertex. The output is a member
// appended to the gl_PerVertex-style output block when the module has one
// used by nothing else, else a plain BuiltIn variable; an existing unwritten
// PointSize output is reused. A module that already writes PointSize is
// returned unchanged. Other stages: error.
// GS/DS need the shaderTessellationAndGeometryPointSize feature; without it
// Vulkan draws their points 1 pixel wide anyway and forbids PointSize, so
// apply it to a GS/DS only when that feature is enabled.
WordsResult AddPointSizeOutput(std::span<const uint32_t> words);

// glslang's HLSL front end gives the hidden counter of an Append/Consume or
// counter UAV its own storage buffer ("name@count", the target of a
// CounterBuffer decoration on the UAV) at the lowest free binding. This moves
// every such counter to its UAV's binding + `bindingOffset`, so that a counter
// is found by the slot of the UAV it counts for. Returns the words unchanged
// when the module has no counter.
WordsResult MoveHiddenCounters(std::span<const uint32_t> words, uint32_t bindingOffset);

}  // namespace rhi::spirv
