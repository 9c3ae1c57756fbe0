// D3D11 stream output (CreateGeometryShaderWithStreamOutput) over Vulkan
// transform feedback (VK_EXT_transform_feedback): validation of the SO
// declaration with D3D11's rules, and the SPIR-V rewrite that makes a VS, DS
// or GS capture what the declaration names.
#pragma once

#include <array>
#include <rhi/d3d11_types.h>
#include <span>
#include <string>

#include "spirv/reflection.h"
#include "spirv/result.h"

namespace rhi::spirv {

// D3D11 limits not in d3d11_types.h (values of the D3D11_ constants).
inline constexpr UINT kSoOutputComponentCount = 128;  // D3D11_SO_OUTPUT_COMPONENT_COUNT
inline constexpr UINT kSoMaxEntries = SO_STREAM_COUNT * kSoOutputComponentCount;  // NumEntries limit: 512
inline constexpr UINT kSoBufferMaxStrideInBytes = 2048;  // D3D11_SO_BUFFER_MAX_STRIDE_IN_BYTES

// Checks a declaration against the shader's outputs the way the D3D11
// runtime does; returns "" when valid, else one message naming the entry
// index and field, e.g.
//   SO declaration entry 2: unknown semantic "FOO1" (not an output of the GS)
// Rules: NumEntries <= 512 (D3D11_SO_STREAM_COUNT * D3D11_SO_OUTPUT_COMPONENT_COUNT),
// NumStrides <= 4; Stream < 4 (Stream > 0 only in a GS; whether the device
// has that many streams is decided elsewhere); OutputSlot < 4; a gap
// (SemanticName NULL) has SemanticIndex 0, StartComponent 0 and
// ComponentCount >= 1 (it may exceed 4); otherwise ComponentCount 1..4,
// StartComponent + ComponentCount <= 4 and within the output's components,
// the semantic must be an output of that stream, no output component is
// captured twice in a stream, a slot takes one stream and not only gaps;
// with NumStrides > 0 every used slot needs a stride, each stride is a
// multiple of 4, <= 2048 and >= the bytes the slot's entries take;
// RasterizedStream < 4 or SO_NO_RASTERIZED_STREAM. Array and matrix outputs
// and non-32-bit outputs are refused (this backend cannot capture them).
std::string ValidateSoDeclaration(const SO_DECLARATION_ENTRY* entries, UINT numEntries, const UINT* bufferStrides,
                                  UINT numStrides, UINT rasterizedStream, const Reflection& shader);

// The vertex stride of each output slot: bufferStrides[slot] when given,
// otherwise (D3D11 with NumStrides 0) the packed size of the slot's entries.
// Unused slots get 0. Use these for the transform-feedback buffer bindings
// and vkCmdDrawIndirectByteCountEXT (DrawAuto).
std::array<UINT, SO_BUFFER_SLOT_COUNT> SoBufferStrides(std::span<const SO_DECLARATION_ENTRY> entries,
                                                       std::span<const UINT> bufferStrides);

// Rewrites `words` (reflected as `reflection`) into a transform-feedback
// shader: capability TransformFeedback (+ GeometryStreams when an entry has
// Stream > 0), ExecutionMode Xfb, and for every non-gap entry a new Output
// variable holding exactly the captured components (scalar or vecN of the
// output's type), at a Location past every output location in use, decorated
// XfbBuffer = OutputSlot, XfbStride = that slot's stride, Offset = the
// entry's byte offset in the slot's vertex record (gaps advance it), and
// Stream when > 0. The components are copied from the original output before
// every OpEmitVertex / OpEmitStreamVertex of the entry's stream (GS), or
// before every OpReturn of the entry function (VS, DS). Original outputs
// stay, so rasterization is unaffected. Runs ValidateSoDeclaration first.
// No entries: the words come back unchanged. Apply after RemapLocations
// (the new locations are chosen past those in use at this point).
WordsResult ApplyStreamOutput(std::span<const uint32_t> words, const Reflection& reflection,
                              std::span<const SO_DECLARATION_ENTRY> entries, std::span<const UINT> bufferStrides);

}  // namespace rhi::spirv
