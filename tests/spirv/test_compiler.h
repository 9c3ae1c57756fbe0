// Test-only HLSL -> SPIR-V helper built directly on glslang's C++ API, so these
// tests do not depend on the product compiler module (written in parallel).
// The header exposes no glslang or SPIR-V enum types on purpose: glslang's
// spirv.hpp and SPIRV-Headers' spirv.hpp11 share an include guard.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace spirv_test {

enum class Stage { Vertex, Hull, Domain, Geometry, Pixel, Compute };
enum class Language { Hlsl, Glsl };

// Compiles `source` the way the backend's shaders are compiled (HLSL front end,
// Vulkan 1.3 / SPIR-V 1.5, hlsl_functionality1 decorations, auto-mapped IO).
// Fails the current test (ADD_FAILURE) and returns {} on error.
std::vector<uint32_t> Compile(std::string_view source, Stage stage, std::string_view entry = "main",
                              Language language = Language::Hlsl);

}  // namespace spirv_test
