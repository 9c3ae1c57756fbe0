// Where the project's effect files (shaders_hlsl/) are, found at run time so that a
// program works from the build tree, from an install prefix and after being moved.
#pragma once

#include <string>

namespace fx {

// The environment variable that, when set, names the effect folder outright.
inline constexpr const char* kShaderDirectoryVariable = "D3D11VK_SHADER_DIR";

// The folder holding the project's effect files, first of:
//  1. $D3D11VK_SHADER_DIR;
//  2. <ancestor>/share/d3d11_on_vulkan/shaders_hlsl for the running executable's folder
//     and each folder above it (an installed bin/ beside share/; the build tree, where
//     CMake links build/share/... to the sources);
//  3. <install prefix>/share/d3d11_on_vulkan/shaders_hlsl (the prefix the library was
//     configured for, for programs outside both).
// When none exists it returns the first candidate of 2, so that a missing-file error
// names where the files were expected. Computed once.
const std::string& ShaderDirectory();

}  // namespace fx
