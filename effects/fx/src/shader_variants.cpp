// Functions, and the entry-point variants that bind `uniform` parameters.
//
// fxc compiles `CompileShader(ps_5_0, PSMain(true, 3))` by treating the listed
// arguments as compile-time values of PSMain's uniform parameters. glslang has
// no such notion, so each distinct argument list gets a wrapper appended to the
// HLSL, its call on the CompileShader's line (#line), the arguments at their column:
//     [attributes of PSMain] float4 fx_variant_0(PSIn input) : SV_Target {
//                                      return PSMain(input, true, (1 + 2)); }
// It keeps PSMain's other parameters with their semantics, so its signature
// is what fxc would have compiled. The `uniform` keywords themselves are blanked
// from the HLSL: the original function becomes an ordinary one. An overloaded
// function (`PS()` and `PS(uniform int index)`) always goes through a wrapper,
// even without uniform arguments: glslang finds no entry point by an
// overloaded name, and the wrapper's call picks the overload.
#include <cstdlib>

#include "effect_parser_impl.h"

namespace fx {
namespace {

std::string Join(const std::vector<std::string>& parts, const char* separator) {
  std::string s;
  for (size_t i = 0; i < parts.size(); ++i) s += (i ? separator : "") + parts[i];
  return s;
}

}  // namespace

// `spec` has been read; pos_ is at the function's name.
void EffectParser::ParseFunction(const DeclSpec& spec, size_t attributesStart) {
  FunctionInfo f;
  if (attributesStart < spec.start) f.attributes = Spell(attributesStart, spec.start);
  f.returnType = Spell(spec.typeToken, pos_);
  const Token& name = Take();
  f.name = name.text;
  f.where = name.where;
  size_t open = pos_;
  size_t close = SkipBalanced();
  // Split at top-level commas; `InputPatch<HSIn, 3>` has one inside angle brackets.
  int depth = 0, angle = 0;
  size_t begin = open + 1;
  for (size_t i = open + 1; i <= close; ++i) {
    const Token& t = t_[i];
    if (i == close || (t.kind == TokenKind::Punctuator && t.text == "," && depth == 0 && angle == 0)) {
      ParseParameter(f, begin, i);
      begin = i + 1;
      continue;
    }
    if (t.kind != TokenKind::Punctuator) continue;
    if (t.text == "(" || t.text == "[" || t.text == "{") ++depth;
    if (t.text == ")" || t.text == "]" || t.text == "}") --depth;
    if (t.text == "<") ++angle;
    if (t.text == ">") angle = std::max(0, angle - 1);
    if (t.text == ">>") angle = std::max(0, angle - 2);
  }
  if (Accept(":")) f.semantic = ExpectIdentifier("a semantic").text;
  if (IsPunct(0, "{")) {
    size_t bodyOpen = pos_;
    RefuseD3D9TextureFunctions(bodyOpen, SkipBalanced());
    functions_[f.name].push_back(std::move(f));
  } else {
    Expect(";", "after the function declaration");
  }
}

void EffectParser::ParseParameter(FunctionInfo& f, size_t begin, size_t end) {
  if (begin == end || (end - begin == 1 && IsIdentAt(begin, "void"))) return;
  size_t declEnd = end, stop = end;
  int depth = 0;
  for (size_t i = begin; i < end; ++i) {
    const Token& t = t_[i];
    if (t.kind != TokenKind::Punctuator) continue;
    if (depth == 0 && (t.text == ":" || t.text == "[") && stop == end) stop = i;
    if (depth == 0 && t.text == "=") {
      declEnd = i;
      break;
    }
    if (t.text == "(" || t.text == "[" || t.text == "{") ++depth;
    if (t.text == ")" || t.text == "]" || t.text == "}") --depth;
  }
  stop = std::min(stop, declEnd);
  CheckPatchSizes(begin, declEnd);
  FunctionInfo::Param p;
  p.text = Spell(begin, declEnd);
  if (declEnd < end) p.defaultValue = Spell(declEnd + 1, end);
  for (size_t i = begin; i < declEnd; ++i) {
    if (!IsIdentAt(i, "uniform")) continue;
    // Only fxc's CompileShader binding gives it meaning, and the variants do that now.
    p.uniform = true;
    Blank(i, i);
  }
  if (stop > begin && t_[stop - 1].kind == TokenKind::Identifier) p.name = t_[stop - 1].text;
  if (p.name.empty()) Fatal(t_[begin], "cannot read the parameter '" + p.text + "'");
  f.params.push_back(std::move(p));
}

// fxc refuses a patch of 0 or more than 32 control points (X3502); glslang 12 segfaults
// on an InputPatch<T, 0> hull shader (docs/FUZZING.md, finding 1), so it must not see one.
void EffectParser::CheckPatchSizes(size_t begin, size_t end) {
  for (size_t i = begin; i + 5 < end; ++i) {
    if (!(IsIdentAt(i, "InputPatch") || IsIdentAt(i, "OutputPatch")) || !IsPunctAt(i + 1, "<")) continue;
    size_t comma = i + 2;
    while (comma < end && !IsPunctAt(comma, ",") && !IsPunctAt(comma, ">")) ++comma;
    if (comma + 1 >= end || !IsPunctAt(comma, ",") || t_[comma + 1].kind != TokenKind::Number) continue;
    const Token& size = t_[comma + 1];
    const unsigned long points = std::strtoul(size.text.c_str(), nullptr, 0);
    if (points < 1 || points > 32)
      Error(size, t_[i].text + " takes 1 to 32 control points, not " + size.text);
  }
}

// tex2D(s, uv) and its kin sample D3D9's combined samplers, which shader model
// 4 and 5 only take under fxc's /Gec (backwards compatibility) and D3D11
// cannot bind: a clear refusal instead of glslang compiling a combined sampler.
void EffectParser::RefuseD3D9TextureFunctions(size_t begin, size_t end) {
  for (size_t i = begin; i < end; ++i) {
    const Token& t = t_[i];
    if (t.kind != TokenKind::Identifier || !IsPunctAt(i + 1, "(") || t.text.rfind("tex", 0) != 0) continue;
    std::string_view rest = std::string_view(t.text).substr(3);
    for (std::string_view dim : {"1D", "2D", "3D", "CUBE"}) {
      if (!rest.starts_with(dim)) continue;
      std::string_view suffix = rest.substr(dim.size());
      if (suffix.empty() || suffix == "bias" || suffix == "grad" || suffix == "lod" || suffix == "proj") {
        Error(t, "'" + t.text + "' is a D3D9 texture function, which fx_5_0 shaders do not take: declare a Texture" +
                     (dim == "CUBE" ? std::string("Cube") : std::string(dim)) + " and a SamplerState and call " +
                     "texture.Sample(sampler, uv)");
      }
    }
  }
}

bool EffectParser::IsIdentAt(size_t index, std::string_view name) const {
  return index < t_.size() && t_[index].kind == TokenKind::Identifier && t_[index].text == name;
}

std::string EffectParser::EntryPointFor(const Token& at, const std::string& function, std::vector<std::string>& args) {
  auto it = functions_.find(function);
  if (it == functions_.end()) Fatal(at, "unknown shader function '" + function + "'");
  // fxc picks the overload by the uniform arguments: one whose uniform
  // parameters they fill exactly, else the first that defaults fill up.
  const FunctionInfo* chosen = nullptr;
  size_t overload = 0;
  std::vector<const FunctionInfo::Param*> uniforms;
  std::string problem;
  auto uniformsOf = [](const FunctionInfo& f) {
    std::vector<const FunctionInfo::Param*> u;
    for (const FunctionInfo::Param& p : f.params) {
      if (p.uniform) u.push_back(&p);
    }
    return u;
  };
  for (size_t i = 0; i < it->second.size(); ++i) {
    if (uniformsOf(it->second[i]).size() != args.size()) continue;
    if (chosen) {
      Fatal(at, "ambiguous call to '" + function + "': the overloads at line " + std::to_string(chosen->where.line) +
                    " and line " + std::to_string(it->second[i].where.line) + " both take " +
                    std::to_string(args.size()) + " uniform argument(s)");
    }
    chosen = &it->second[i];
    overload = i;
  }
  for (size_t i = 0; i < it->second.size() && !chosen; ++i) {
    std::vector<const FunctionInfo::Param*> u = uniformsOf(it->second[i]);
    if (args.size() > u.size()) {
      problem = "'" + function + "' has " + std::to_string(u.size()) + " uniform parameter(s), but " +
                std::to_string(args.size()) + " argument(s) are given";
      continue;
    }
    auto missing = std::find_if(u.begin() + static_cast<std::ptrdiff_t>(args.size()), u.end(),
                                [](const FunctionInfo::Param* p) { return p->defaultValue.empty(); });
    if (missing != u.end()) {
      problem = "no value for uniform parameter '" + (*missing)->name + "' of '" + function + "'";
      continue;
    }
    chosen = &it->second[i];
    overload = i;
  }
  if (!chosen) Fatal(at, problem);
  uniforms = uniformsOf(*chosen);
  // glslang finds no entry point by an overloaded name: overloads go through a wrapper too.
  if (uniforms.empty() && it->second.size() == 1) return function;
  for (size_t i = args.size(); i < uniforms.size(); ++i) args.push_back(uniforms[i]->defaultValue);

  std::string key = function + "#" + std::to_string(overload) + "(" + Join(args, ",") + ")";
  auto found = variants_.find(key);
  if (found != variants_.end()) return found->second;
  std::string name = "fx_variant_" + std::to_string(variants_.size());
  std::vector<std::string> params, callArgs;
  size_t next = 0, firstUniform = 0;
  for (const FunctionInfo::Param& p : chosen->params) {
    if (p.uniform && next == 0) firstUniform = callArgs.size();
    if (p.uniform) {
      const std::string& a = args[next++];
      bool oneToken = std::all_of(a.begin(), a.end(), [](char c) { return IsIdentifierChar(c) || c == '.'; });
      callArgs.push_back(oneToken ? a : "(" + a + ")");
    } else {
      params.push_back(p.text);
      callArgs.push_back(p.name);
    }
  }
  // The call goes on the CompileShader's line, so that an error in an argument points there.
  std::string code = "// " + name + ": " + function + "(" + Join(args, ", ") + ")\n" + LineDirective(at.where);
  if (!chosen->attributes.empty()) code += chosen->attributes + " ";
  code += chosen->returnType + " " + name + "(" + Join(params, ", ") + ")";
  if (!chosen->semantic.empty()) code += " : " + chosen->semantic;
  // The first uniform argument goes where CompileShader has it (right after `function(`).
  std::string call = (chosen->returnType == "void" ? "" : "return ") + function + "(" + Join(callArgs, ", ") + "); }";
  size_t firstArg = call.find('(') + 1;
  if (!uniforms.empty()) firstArg = call.find(callArgs[firstUniform], firstArg);
  size_t column = static_cast<size_t>(std::max(1, at.where.column)) - 1 + function.size() + 1;
  code += " {\n" + LineDirective(at.where) + std::string(column > firstArg ? column - firstArg : 0, ' ') + call + "\n";
  variantCode_.push_back(std::move(code));
  variants_.emplace(std::move(key), name);
  return name;
}

std::string EffectParser::VariantSource() const {
  if (variantCode_.empty()) return "";
  return "\n" + Join(variantCode_, "");
}

}  // namespace fx
