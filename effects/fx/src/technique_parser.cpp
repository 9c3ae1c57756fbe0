// Techniques, passes and shader expressions (CompileShader, ConstructGSWithSO).
// All of it is effect-only: it is recorded in the AST and blanked from the HLSL.
#include "effect_parser_impl.h"

namespace fx {
namespace {

constexpr int kMaxShaderNesting = 8;

std::string StageName(ShaderStage s) {
  switch (s) {
    case ShaderStage::Vertex: return "vertex";
    case ShaderStage::Hull: return "hull";
    case ShaderStage::Domain: return "domain";
    case ShaderStage::Geometry: return "geometry";
    case ShaderStage::Pixel: return "pixel";
    case ShaderStage::Compute: return "compute";
  }
  return "?";
}

// vs_5_0, ps_4_1, gs_4_0, vs_4_0_level_9_3, ...
std::optional<ShaderStage> StageOfProfile(const std::string& p) {
  static const std::pair<std::string_view, ShaderStage> kPrefixes[] = {
      {"vs_", ShaderStage::Vertex},   {"hs_", ShaderStage::Hull},  {"ds_", ShaderStage::Domain},
      {"gs_", ShaderStage::Geometry}, {"ps_", ShaderStage::Pixel}, {"cs_", ShaderStage::Compute}};
  std::string_view version = std::string_view(p).substr(std::min<size_t>(3, p.size()));
  bool known = false;
  for (std::string_view v : {"4_0", "4_1", "5_0", "4_0_level_9_1", "4_0_level_9_2", "4_0_level_9_3"}) {
    known = known || version == v;
  }
  if (!known) return std::nullopt;
  for (const auto& [prefix, stage] : kPrefixes) {
    if (p.compare(0, 3, prefix) == 0) return stage;
  }
  return std::nullopt;
}

}  // namespace

// fxgroup Name [<annotations>] { technique11 ... }
void EffectParser::ParseGroup() {
  size_t start = pos_++;
  const Token& name = ExpectIdentifier("a group name");
  if (IsPunct(0, "<")) ParseAnnotations();
  const Token& open = Expect("{", "to open the group");
  while (!Accept("}")) {
    if (AtEnd()) Fatal(open, "unterminated fxgroup '" + name.text + "': '{' is never closed");
    if (Accept(";")) continue;
    if (!IsIdent(0, "technique") && !IsIdent(0, "technique10") && !IsIdent(0, "technique11")) {
      Fatal(Peek(), "expected a technique in fxgroup '" + name.text + "'");
    }
    ParseTechnique(name.text);
  }
  Accept(";");
  Blank(start, pos_ - 1);
}

// technique11 [Name] [<annotations>] { pass ... }
void EffectParser::ParseTechnique(const std::string& group) {
  size_t start = pos_;
  const Token& keyword = Take();
  Technique t;
  t.version = keyword.text == "technique10" ? 10 : 11;
  t.group = group;
  t.where = keyword.where;
  if (Peek().kind == TokenKind::Identifier) t.name = Take().text;
  if (IsPunct(0, "<")) t.annotations = ParseAnnotations();
  const Token& open = Expect("{", "to open the technique");
  while (!Accept("}")) {
    if (AtEnd()) Fatal(open, "unterminated technique '" + t.name + "': '{' is never closed");
    if (Accept(";")) continue;
    if (!IsIdent(0, "pass")) Fatal(Peek(), "expected 'pass' in technique '" + t.name + "', found '" + Peek().text + "'");
    t.passes.push_back(ParsePass());
  }
  Accept(";");
  Blank(start, pos_ - 1);
  ast_.techniques.push_back(std::move(t));
}

// pass [Name] [<annotations>] { SetXxx(...); ... }
Pass EffectParser::ParsePass() {
  Pass p;
  p.where = Take().where;
  if (Peek().kind == TokenKind::Identifier) p.name = Take().text;
  if (IsPunct(0, "<")) p.annotations = ParseAnnotations();
  const Token& open = Expect("{", "to open the pass");
  while (!Accept("}")) {
    if (AtEnd()) Fatal(open, "unterminated pass '" + p.name + "': '{' is never closed");
    if (Accept(";")) continue;
    p.assignments.push_back(ParsePassAssignment());
  }
  Accept(";");
  return p;
}

PassAssignment EffectParser::ParsePassAssignment() {
  static const std::pair<std::string_view, ShaderStage> kShaderSetters[] = {
      {"SetVertexShader", ShaderStage::Vertex},     {"SetHullShader", ShaderStage::Hull},
      {"SetDomainShader", ShaderStage::Domain},     {"SetGeometryShader", ShaderStage::Geometry},
      {"SetPixelShader", ShaderStage::Pixel},       {"SetComputeShader", ShaderStage::Compute}};
  const Token& fn = ExpectIdentifier("a pass assignment such as SetVertexShader(...)");
  PassAssignment a;
  a.where = fn.where;
  for (const auto& [name, stage] : kShaderSetters) {
    if (fn.text != name) continue;
    Expect("(", "after " + fn.text);
    const Token& at = Peek();
    ShaderValue v = ParseShaderValue(0);
    Expect(")", "after the shader");
    Expect(";", "after " + fn.text + "(...)");
    if (!v.isNull && v.stage != stage) {
      Error(at, fn.text + " needs a " + StageName(stage) + " shader, not a " + StageName(v.stage) + " shader");
    }
    a.value = ShaderAssignment{stage, v.shader, v.variable, v.element};
    return a;
  }
  size_t arity = fn.text == "SetBlendState" ? 3 : fn.text == "SetDepthStencilState" ? 2 : fn.text == "SetRasterizerState" ? 1 : 0;
  if (arity == 0) {
    std::string hint = IsPunct(0, "=") ? " (FX9-style state assignments are not supported; use SetVertexShader(...) etc.)" : "";
    Fatal(fn, "unknown pass assignment '" + fn.text + "'" + hint);
  }
  std::vector<std::pair<size_t, size_t>> args = ParseArgumentRanges();
  Expect(";", "after " + fn.text + "(...)");
  if (args.size() != arity) {
    static const char* kUsage[] = {"", "SetRasterizerState(state)", "SetDepthStencilState(state, stencilRef)",
                                   "SetBlendState(state, blendFactor, sampleMask)"};
    Fatal(fn, fn.text + " takes " + std::to_string(arity) + " argument" + (arity > 1 ? "s: " : ": ") + kUsage[arity]);
  }
  if (arity == 3) {
    BlendStateAssignment b;
    b.state = ParseStateRef(args[0].first, args[0].second, "BlendState");
    ConstValue factor = Evaluate(args[1].first, args[1].second, "blend factor");
    if (factor.components.size() != 4 && factor.components.size() != 1) {
      Fatal(t_[args[1].first], "the blend factor needs 4 components");
    }
    for (size_t i = 0; i < 4; ++i) {
      b.blendFactor[i] = static_cast<float>(factor.components[factor.components.size() == 1 ? 0 : i]);
    }
    b.sampleMask = EvaluateUInt(args[2].first, args[2].second, "sample mask", 0, UINT32_MAX);
    a.value = b;
  } else if (arity == 2) {
    DepthStencilStateAssignment d;
    d.state = ParseStateRef(args[0].first, args[0].second, "DepthStencilState");
    d.stencilRef = EvaluateUInt(args[1].first, args[1].second, "stencil reference", 0, UINT32_MAX);
    a.value = d;
  } else {
    a.value = RasterizerStateAssignment{ParseStateRef(args[0].first, args[0].second, "RasterizerState")};
  }
  return a;
}

// At '(': the ranges of the comma-separated arguments; leaves pos_ after ')'.
std::vector<std::pair<size_t, size_t>> EffectParser::ParseArgumentRanges() {
  const Token& open = Expect("(", "to open the argument list");
  std::vector<std::pair<size_t, size_t>> args;
  size_t begin = pos_;
  int depth = 0;
  for (; pos_ < t_.size(); ++pos_) {
    const Token& t = t_[pos_];
    if (t.kind != TokenKind::Punctuator) continue;
    if (t.text == "(" || t.text == "[" || t.text == "{") ++depth;
    bool close = t.text == ")" || t.text == "]" || t.text == "}";
    if (close && depth == 0) {
      if (t.text != ")") Fatal(t, "unbalanced '" + t.text + "' in the argument list");
      if (pos_ > begin || !args.empty()) args.emplace_back(begin, pos_);
      ++pos_;
      return args;
    }
    if (close) --depth;
    if (t.text == "," && depth == 0) {
      args.emplace_back(begin, pos_);
      begin = pos_ + 1;
    }
  }
  Fatal(open, "'(' is never closed");
}

// NULL | name | name[constant]
ObjectRef EffectParser::ParseStateRef(size_t begin, size_t end, std::string_view kind) {
  if (begin >= end) Fatal(t_[std::min(begin, t_.size() - 1)], "expected a " + std::string(kind) + " or NULL");
  const Token& name = t_[begin];
  if (end - begin == 1 && (name.text == "NULL" || name.text == "0")) return ObjectRef{};
  if (name.kind != TokenKind::Identifier) Fatal(name, "expected a " + std::string(kind) + " or NULL");
  ObjectRef r;
  r.variable = name.text;
  if (end - begin > 1) {
    if (!IsPunctAt(begin + 1, "[") || !IsPunctAt(end - 1, "]")) Fatal(t_[begin + 1], "unexpected '" + t_[begin + 1].text + "'");
    r.element = EvaluateUInt(begin + 2, end - 1, "state array index", 0, UINT32_MAX);
  }
  size_t elements = 0;
  bool found = false;
  auto look = [&](const auto& list) {
    if (const auto* v = FindByName(list, name.text)) {
      found = true;
      elements = v->descs.size();
    }
  };
  if (kind == "BlendState") look(ast_.blendStates);
  if (kind == "DepthStencilState") look(ast_.depthStencilStates);
  if (kind == "RasterizerState") look(ast_.rasterizerStates);
  if (!found) Fatal(name, "unknown " + std::string(kind) + " '" + name.text + "'");
  if (r.element >= elements) Fatal(name, "index " + std::to_string(r.element) + " out of range for '" + name.text + "'");
  return r;
}

// NULL | CompileShader(...) | compile profile f(...) | ConstructGSWithSO(...) | variable[index]
ShaderValue EffectParser::ParseShaderValue(int depth) {
  if (depth > kMaxShaderNesting) Fatal(Peek(), "shader expression nested too deeply");
  const Token& t = Peek();
  ShaderValue v;
  if (IsIdent(0, "NULL") || (t.kind == TokenKind::Number && t.text == "0")) {
    ++pos_;
    return v;
  }
  v.isNull = false;
  if (IsIdent(0, "CompileShader") || IsIdent(0, "compile")) {
    v.shader = ParseCompileShader(t.text == "compile");
    v.stage = ast_.shaders[v.shader].stage;
    return v;
  }
  if (IsIdent(0, "ConstructGSWithSO")) {
    v.shader = ParseConstructGSWithSO(depth);
    v.stage = ShaderStage::Geometry;
    return v;
  }
  if (t.kind != TokenKind::Identifier) {
    Fatal(t, "expected a shader: CompileShader(...), ConstructGSWithSO(...), a shader variable or NULL");
  }
  ++pos_;
  const ShaderVariable* var = FindByName(ast_.shaderVariables, t.text);
  if (!var) Fatal(t, "unknown shader '" + t.text + "'");
  if (IsPunct(0, "[")) {
    size_t open = pos_;
    size_t close = SkipBalanced();
    if (close == open + 2 && t_[open + 1].kind == TokenKind::Identifier && !constants_.count(t_[open + 1].text)) {
      Fatal(t_[open + 1], "shader arrays indexed by a variable are not supported");
    }
    v.element = EvaluateUInt(open + 1, close, "shader array index", 0, UINT32_MAX);
  }
  if (v.element >= var->shaders.size()) Fatal(t, "index " + std::to_string(v.element) + " out of range for '" + t.text + "'");
  v.variable = var->name;
  v.stage = var->stage;
  v.shader = var->shaders[v.element];
  return v;
}

// CompileShader(profile, Function(args)) or FX9's `compile profile Function(args)`.
int EffectParser::ParseCompileShader(bool legacyCompileKeyword) {
  const Token& keyword = Take();
  if (!legacyCompileKeyword) Expect("(", "after CompileShader");
  const Token& profile = ExpectIdentifier("a shader profile such as vs_5_0");
  std::optional<ShaderStage> stage = StageOfProfile(profile.text);
  if (!stage) Fatal(profile, "unknown shader profile '" + profile.text + "'");
  if (!legacyCompileKeyword) Expect(",", "after the shader profile");
  const Token& function = ExpectIdentifier("the shader's entry function");
  std::vector<std::string> args;
  for (const auto& [b, e] : ParseArgumentRanges()) {
    if (b == e) Fatal(t_[b], "empty argument");
    args.push_back(Spell(b, e));
  }
  if (!legacyCompileKeyword) Expect(")", "after CompileShader(...)");
  CompiledShader s;
  s.stage = *stage;
  s.profile = profile.text;
  s.function = function.text;
  s.entryPoint = EntryPointFor(function, function.text, args);
  s.uniformArgs = std::move(args);
  s.where = keyword.where;
  ast_.shaders.push_back(std::move(s));
  return static_cast<int>(ast_.shaders.size()) - 1;
}

// ConstructGSWithSO(shader, "decl")  or, fx_5_0,
// ConstructGSWithSO(shader, "decl0", "decl1", "decl2", "decl3", rasterizedStream)
int EffectParser::ParseConstructGSWithSO(int depth) {
  const Token& keyword = Take();
  Expect("(", "after ConstructGSWithSO");
  const Token& shaderToken = Peek();
  bool inlineShader = IsIdent(0, "CompileShader") || IsIdent(0, "compile");
  ShaderValue inner = ParseShaderValue(depth + 1);
  if (inner.shader < 0) Fatal(shaderToken, "ConstructGSWithSO needs a shader, not NULL");
  if (inner.stage != ShaderStage::Vertex && inner.stage != ShaderStage::Domain && inner.stage != ShaderStage::Geometry) {
    Error(shaderToken, "stream output needs a vertex, domain or geometry shader");
  }
  std::vector<std::string> decls;
  std::vector<const Token*> declTokens;
  std::optional<size_t> streamToken;
  while (Accept(",")) {
    if (streamToken) Fatal(Peek(), "the rasterized stream must be the last argument");
    const Token& first = Peek();
    if (first.kind == TokenKind::String) {
      std::string decl;
      while (Peek().kind == TokenKind::String) decl += UnquoteString(Take().text);
      decls.push_back(decl);
      declTokens.push_back(&first);
    } else if (IsIdent(0, "NULL")) {
      ++pos_;
      decls.emplace_back();
      declTokens.push_back(&first);
    } else if (decls.size() == rhi::SO_STREAM_COUNT) {
      streamToken = pos_;
      pos_ = FindAtDepthZero({",", ")"});
    } else {
      Fatal(first, "expected a stream-output declaration string");
    }
  }
  size_t close = pos_;
  Expect(")", "after ConstructGSWithSO(...)");
  bool fx4Form = decls.size() == 1 && !streamToken;
  bool fx5Form = decls.size() == rhi::SO_STREAM_COUNT && streamToken;
  if (!fx4Form && !fx5Form) {
    Fatal(keyword, "ConstructGSWithSO takes (shader, decl) or (shader, decl0, decl1, decl2, decl3, rasterizedStream)");
  }
  // An inline CompileShader becomes the stream-output shader; a variable's shader is copied.
  int index = inner.shader;
  if (!inlineShader) {
    CompiledShader copy = ast_.shaders[inner.shader];
    ast_.shaders.push_back(std::move(copy));
    index = static_cast<int>(ast_.shaders.size()) - 1;
  }
  CompiledShader& s = ast_.shaders[index];
  s.hasStreamOutput = true;
  s.where = keyword.where;
  for (size_t i = 0; i < decls.size(); ++i) s.soDeclarations[i] = decls[i];
  if (streamToken) {
    // D3D11_SO_NO_RASTERIZED_STREAM is 0xFFFFFFFF; effects write it as -1 too.
    ConstValue stream = Evaluate(*streamToken, close, "rasterized stream");
    if (stream.components.size() == 1 && stream.components[0] == -1) {
      s.rasterizedStream = rhi::SO_NO_RASTERIZED_STREAM;
    } else {
      s.rasterizedStream = EvaluateUInt(*streamToken, close, "rasterized stream", 0, UINT32_MAX);
    }
    if (s.rasterizedStream >= rhi::SO_STREAM_COUNT && s.rasterizedStream != rhi::SO_NO_RASTERIZED_STREAM) {
      Error(t_[*streamToken], "the rasterized stream must be 0..3 or D3D11_SO_NO_RASTERIZED_STREAM");
    }
  }
  auto parsed = StreamOutputDecl::Parse(decls);
  if (auto* e = std::get_if<SoDeclError>(&parsed)) {
    // Point into the string literal (past its quote) when its text is the source's.
    Token at = *declTokens[e->stream];
    if (!at.fromMacro) at.where.column += 1 + static_cast<int>(e->offset);
    Error(at, "stream-output declaration: " + e->message);
  } else {
    s.streamOutput = std::get<StreamOutputDecl>(std::move(parsed));
  }
  return index;
}

void EffectParser::HandleShaderVariable(const Declarator& d, ShaderStage stage) {
  ShaderVariable v;
  v.name = d.name;
  v.stage = stage;
  v.arrayDims = d.arrayDims;
  v.annotations = d.annotations;
  v.where = t_[d.nameToken].where;
  uint32_t count = ObjectElementCount(d);
  auto element = [&] {
    const Token& at = Peek();
    ShaderValue s = ParseShaderValue(0);
    if (!s.isNull && s.stage != stage) {
      Error(at, "'" + d.name + "' holds " + StageName(stage) + " shaders, not a " + StageName(s.stage) + " shader");
    }
    v.shaders.push_back(s.shader);
  };
  if (!Accept("=")) {
    v.shaders.assign(count, -1);
  } else if (d.arrayDims.empty()) {
    element();
  } else {
    const Token& open = Expect("{", "to open the list of shaders");
    while (!Accept("}")) {
      if (AtEnd()) Fatal(open, "'{' is never closed");
      element();
      if (!Accept(",")) {
        Expect("}", "after the last shader");
        break;
      }
    }
    if (v.shaders.size() != count) {
      Fatal(open, "'" + d.name + "' needs " + std::to_string(count) + " shaders, got " + std::to_string(v.shaders.size()));
    }
  }
  ast_.shaderVariables.push_back(std::move(v));
}

}  // namespace fx
