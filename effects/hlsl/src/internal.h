// Pieces shared by the compiler's source files; not part of the public API.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "hlsl/hlsl_compiler.h"

namespace glslang {
class TProgram;
}

namespace hlsl::detail {

// Text of every file the preprocessor read, by the name glslang reports it
// under; used to recover error columns glslang 12 does not print.
using SourceFiles = std::map<std::string, std::string>;

// The name diagnostics use for the main source.
inline std::string SourceName(const CompileRequest& request) {
  return request.fileName.empty() ? "<memory>" : request.fileName;
}

// The whole compile, in this process (no crash isolation).
CompileResult CompileInProcess(const CompileRequest& request);

// Fills result.constantBuffers and result.resources from a linked, IO-mapped
// program whose reflection has been built, and the SPIR-V generated from it
// (the source of truth for cbuffer member offsets).
void Reflect(const glslang::TProgram& program, Stage stage, const SourceFiles& files,
             const std::vector<uint32_t>& spirv, CompileResult& result);

}  // namespace hlsl::detail
