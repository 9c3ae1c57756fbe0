// Works around glslang 12 crashing on one HLSL source that holds geometry
// shaders with different output stream types (PointStream<A> and
// TriangleStream<B>): compiling any entry of such a source segfaults.
#pragma once

#include <string>
#include <vector>

namespace fx {

// Returns `hlsl` with the bodies of the functions that take an `inout
// XxxStream<T>` parameter blanked (replaced by spaces, newlines kept, so every
// position glslang reports is unchanged), except the functions in `keep` (the
// entry point and the function it wraps) and other functions streaming the
// same types as those. Returns `hlsl` unchanged when it streams at most one type.
std::string IsolateGeometryShader(const std::string& hlsl, const std::vector<std::string>& keep);

}  // namespace fx
