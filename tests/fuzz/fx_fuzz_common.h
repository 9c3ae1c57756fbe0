// Shared by the libFuzzer target (fx_fuzz.cpp) and the deterministic corpus
// replay (fx_corpus_replay.cpp): one input = the bytes of an .fx file.
//
//  1. fx::ParseEffect on the bytes, named "fuzz/input.fx". #include resolves
//     through an in-memory readFile hook: "common.fxh" (any folder) is a fixed
//     header below, every other path is "no such file" (a clean error).
//  2. When parsing succeeds, hlsl::CompileHlsl on the effect's HLSL for at most
//     `maxCompiles` distinct (entry point, profile) pairs of EffectAst::shaders.
//
// The outcome must be "clean": a success, or errors that each carry a non-empty
// message and a sane position. Anything else is reported as a Problem; the
// fuzz target aborts on one so libFuzzer saves the input.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "fx/effect_parser.h"
#include "hlsl/hlsl_compiler.h"

namespace fxfuzz {

// glslang is slow (milliseconds to seconds per compile): bound the work per input.
inline constexpr size_t kMaxSourceBytes = 16 * 1024;
inline constexpr int kMaxCompilesPerInput = 3;

inline const char* kCommonHeader = R"(// in-memory include of the fuzz harness
#ifndef COMMON_FXH
#define COMMON_FXH
#define MAX_LIGHTS 2
#define SATURATE_COLOR(c) saturate(c)
struct VSInput { float3 Position : POSITION; float3 Normal : NORMAL; float2 TexCoord : TEXCOORD0; };
struct PSInput { float4 Position : SV_Position; float3 Normal : NORMAL; float2 TexCoord : TEXCOORD0; };
#endif
)";

inline std::optional<std::string> ReadInMemory(const std::string& path) {
  const std::string name = "common.fxh";
  if (path.size() >= name.size() && path.compare(path.size() - name.size(), name.size(), name) == 0 &&
      (path.size() == name.size() || path[path.size() - name.size() - 1] == '/')) {
    return std::string(kCommonHeader);
  }
  return std::nullopt;
}

struct Outcome {
  bool parsed = false;
  size_t parseErrors = 0;
  int compiled = 0;        // CompileHlsl calls made
  int compiledOk = 0;      // of which succeeded
  std::vector<std::string> problems;  // empty: clean
};

inline bool SaneLocation(const fx::SourceLocation& where) { return where.line >= 0 && where.column >= 0; }

inline Outcome RunOne(const uint8_t* data, size_t size, int maxCompiles = kMaxCompilesPerInput) {
  Outcome out;
  if (size > kMaxSourceBytes) return out;  // not interesting: skipped
  std::string source(reinterpret_cast<const char*>(data), size);

  fx::ParseOptions options;
  options.readFile = ReadInMemory;
  options.defines = {{"FUZZ", ""}};
  fx::Result<fx::EffectAst> result = fx::ParseEffect(source, "fuzz/input.fx", options);

  if (auto* errors = std::get_if<std::vector<fx::ParseError>>(&result)) {
    out.parseErrors = errors->size();
    if (errors->empty()) out.problems.push_back("parse failed with no error");
    for (const fx::ParseError& e : *errors) {
      if (e.message.empty()) out.problems.push_back("parse error without a message: " + e.Format());
      if (!SaneLocation(e.where)) out.problems.push_back("parse error with a negative position: " + e.Format());
    }
    return out;
  }

  const fx::EffectAst& ast = std::get<fx::EffectAst>(result);
  out.parsed = true;
  std::set<std::pair<std::string, std::string>> done;
  for (const fx::CompiledShader& shader : ast.shaders) {
    if (out.compiled >= maxCompiles) break;
    if (!done.insert({shader.entryPoint, shader.profile}).second) continue;
    if (shader.entryPoint.empty()) out.problems.push_back("shader with an empty entry point");
    hlsl::CompileRequest request;
    request.source = ast.hlsl;
    request.fileName = "fuzz/input.fx";
    request.entryPoint = shader.entryPoint;
    request.profile = shader.profile;
    hlsl::CompileResult compiled = hlsl::CompileHlsl(request);
    ++out.compiled;
    if (compiled.ok) {
      ++out.compiledOk;
      if (compiled.spirv.empty()) out.problems.push_back("compile ok without SPIR-V: " + shader.entryPoint);
    } else {
      if (compiled.errors.empty()) out.problems.push_back("compile failed with no error: " + shader.entryPoint);
      for (const hlsl::Diagnostic& d : compiled.errors) {
        if (d.message.empty()) out.problems.push_back("compile error without a message: " + shader.entryPoint);
        if (d.line < 0 || d.column < 0) out.problems.push_back("compile error with a negative position: " + d.message);
      }
    }
  }
  return out;
}

}  // namespace fxfuzz
