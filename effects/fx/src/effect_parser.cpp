// Top level of the effect parser: the token cursor, HLSL blanking, and the
// global declarations (cbuffers, structs, typedefs, variables of every kind,
// annotations, state blocks).
#include "fx/effect_parser.h"

#include <algorithm>
#include <cctype>
#include <cmath>

#include "effect_parser_impl.h"
#include "fx/state_blocks.h"

namespace fx {

bool EqualsIgnoreCase(std::string_view a, std::string_view b) {
  return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](char x, char y) {
           return (x >= 'A' && x <= 'Z' ? x - 'A' + 'a' : x) == (y >= 'A' && y <= 'Z' ? y - 'A' + 'a' : y);
         });
}

namespace {

constexpr size_t kMaxErrors = 50;
constexpr uint64_t kMaxObjectElements = 4096;  // elements of a sampler / state / shader array

struct ResourceName {
  std::string_view name;
  ResourceKind kind;
};
constexpr ResourceName kResourceNames[] = {
    {"texture", ResourceKind::Texture},
    {"Texture", ResourceKind::Texture},
    {"Texture1D", ResourceKind::Texture1D},
    {"Texture1DArray", ResourceKind::Texture1DArray},
    {"Texture2D", ResourceKind::Texture2D},
    {"Texture2DArray", ResourceKind::Texture2DArray},
    {"Texture2DMS", ResourceKind::Texture2DMS},
    {"Texture2DMSArray", ResourceKind::Texture2DMSArray},
    {"Texture3D", ResourceKind::Texture3D},
    {"TextureCube", ResourceKind::TextureCube},
    {"TextureCubeArray", ResourceKind::TextureCubeArray},
    {"Buffer", ResourceKind::Buffer},
    {"ByteAddressBuffer", ResourceKind::ByteAddressBuffer},
    {"StructuredBuffer", ResourceKind::StructuredBuffer},
    {"RWTexture1D", ResourceKind::RWTexture1D},
    {"RWTexture1DArray", ResourceKind::RWTexture1DArray},
    {"RWTexture2D", ResourceKind::RWTexture2D},
    {"RWTexture2DArray", ResourceKind::RWTexture2DArray},
    {"RWTexture3D", ResourceKind::RWTexture3D},
    {"RWBuffer", ResourceKind::RWBuffer},
    {"RWByteAddressBuffer", ResourceKind::RWByteAddressBuffer},
    {"RWStructuredBuffer", ResourceKind::RWStructuredBuffer},
    {"AppendStructuredBuffer", ResourceKind::AppendStructuredBuffer},
    {"ConsumeStructuredBuffer", ResourceKind::ConsumeStructuredBuffer},
};

// The spelling glslang knows of an object type that fxc takes in any case
// (D3D9 files write texture2D, textureCUBE), e.g. "texture2D" -> "Texture2D";
// `type` itself when it is no such keyword. Other type names (Buffer, ...)
// are case-sensitive, so `buffer` stays a name.
std::string_view CanonicalObjectType(std::string_view type) {
  static constexpr std::string_view kAnyCase[] = {
      "Texture1D", "Texture2D", "Texture3D", "TextureCube", "SamplerState", "SamplerComparisonState",
      "sampler1D", "sampler2D", "sampler3D", "samplerCUBE"};
  for (std::string_view name : kAnyCase) {
    if (EqualsIgnoreCase(name, type)) return name;
  }
  return type;
}

std::optional<ResourceKind> ResourceKindOf(const std::string& type) {
  for (const ResourceName& r : kResourceNames) {
    if (r.name == type) return r.kind;
  }
  return std::nullopt;
}

std::optional<ShaderStage> ShaderStageOfType(const std::string& type) {
  static const std::pair<std::string_view, ShaderStage> kTypes[] = {
      {"VertexShader", ShaderStage::Vertex}, {"HullShader", ShaderStage::Hull},
      {"DomainShader", ShaderStage::Domain}, {"GeometryShader", ShaderStage::Geometry},
      {"PixelShader", ShaderStage::Pixel},   {"ComputeShader", ShaderStage::Compute}};
  for (const auto& [name, stage] : kTypes) {
    if (EqualsIgnoreCase(name, type)) return stage;
  }
  return std::nullopt;
}

bool IsSamplerType(const std::string& type) {
  for (std::string_view s : {"SamplerState", "SamplerComparisonState", "sampler", "sampler1D", "sampler2D",
                             "sampler3D", "samplerCUBE"}) {
    if (EqualsIgnoreCase(s, type)) return true;
  }
  return false;
}

// Storage classes and type modifiers that may precede a type.
bool IsModifier(const std::string& word) {
  static const std::set<std::string, std::less<>> kModifiers = {
      "static",  "const",    "uniform", "extern",     "shared",   "volatile",      "precise",
      "inline",  "row_major", "column_major", "groupshared", "nointerpolation", "linear",
      "centroid", "noperspective", "sample", "snorm", "unorm", "export", "in", "out", "inout"};
  return kModifiers.count(word) != 0;
}

template <class Desc>
Desc DefaultDesc();
template <>
rhi::BLEND_DESC DefaultDesc() { return DefaultBlendDesc(); }
template <>
rhi::DEPTH_STENCIL_DESC DefaultDesc() { return DefaultDepthStencilDesc(); }
template <>
rhi::RASTERIZER_DESC DefaultDesc() { return DefaultRasterizerDesc(); }

uint32_t AlignUp16(uint32_t v) { return (v + 15u) & ~15u; }



}  // namespace

// The text of a string literal token, with C escapes resolved.
std::string UnquoteString(const std::string& literal) {
  std::string out;
  for (size_t i = 1; i + 1 < literal.size(); ++i) {
    char c = literal[i];
    if (c == '\\' && i + 2 < literal.size()) {
      char n = literal[++i];
      c = n == 'n' ? '\n' : n == 't' ? '\t' : n;
    }
    out += c;
  }
  return out;
}

bool IsUnorderedAccess(ResourceKind kind) {
  switch (kind) {
    case ResourceKind::RWTexture1D:
    case ResourceKind::RWTexture1DArray:
    case ResourceKind::RWTexture2D:
    case ResourceKind::RWTexture2DArray:
    case ResourceKind::RWTexture3D:
    case ResourceKind::RWBuffer:
    case ResourceKind::RWByteAddressBuffer:
    case ResourceKind::RWStructuredBuffer:
    case ResourceKind::AppendStructuredBuffer:
    case ResourceKind::ConsumeStructuredBuffer:
      return true;
    default:
      return false;
  }
}

// ---------------------------------------------------------------------------
// Cursor, errors, blanking

EffectParser::EffectParser(PreprocessedSource source) : hlsl_(std::move(source.text)) {
  // Pragmas may sit anywhere; they leave the token stream and apply, in order,
  // when the parser reaches a declaration after them.
  for (Token& t : source.tokens) {
    if (t.kind == TokenKind::Pragma) {
      pragmas_.emplace_back(t_.size(), std::move(t.text));
    } else {
      t_.push_back(std::move(t));
    }
  }
  // fxc takes `texture2D` for Texture2D; glslang only the canonical spelling.
  for (Token& t : t_) {
    if (t.kind != TokenKind::Identifier) continue;
    std::string_view canonical = CanonicalObjectType(t.text);
    if (canonical == t.text) continue;
    hlsl_.replace(t.offset, canonical.size(), canonical);  // only the case differs
    t.text = canonical;
  }
  end_.kind = TokenKind::Invalid;
  end_.text = "end of file";
  end_.offset = hlsl_.size();
  if (!t_.empty()) {
    end_.where = t_.back().where;
    end_.where.column += static_cast<int>(t_.back().text.size());
  }
}

const Token& EffectParser::Peek(size_t ahead) const { return pos_ + ahead < t_.size() ? t_[pos_ + ahead] : end_; }

const Token& EffectParser::Take() {
  const Token& t = Peek();
  if (!AtEnd()) ++pos_;
  return t;
}

bool EffectParser::IsPunct(size_t ahead, std::string_view p) const {
  const Token& t = Peek(ahead);
  return t.kind == TokenKind::Punctuator && t.text == p;
}

bool EffectParser::IsIdent(size_t ahead, std::string_view name) const {
  const Token& t = Peek(ahead);
  return t.kind == TokenKind::Identifier && t.text == name;
}

bool EffectParser::Accept(std::string_view punct) {
  if (!IsPunct(0, punct)) return false;
  ++pos_;
  return true;
}

const Token& EffectParser::Expect(std::string_view punct, std::string_view context) {
  if (!IsPunct(0, punct)) {
    Fatal(Peek(), "expected '" + std::string(punct) + "' " + std::string(context) + ", found '" + Peek().text + "'");
  }
  return Take();
}

const Token& EffectParser::ExpectIdentifier(std::string_view what) {
  if (Peek().kind != TokenKind::Identifier) {
    Fatal(Peek(), "expected " + std::string(what) + ", found '" + Peek().text + "'");
  }
  return Take();
}

size_t EffectParser::SkipBalanced() {
  const Token& open = Peek();
  int depth = 0;
  for (size_t i = pos_; i < t_.size(); ++i) {
    const Token& t = t_[i];
    if (t.kind != TokenKind::Punctuator) continue;
    if (t.text == "(" || t.text == "[" || t.text == "{") ++depth;
    if (t.text == ")" || t.text == "]" || t.text == "}") --depth;
    if (depth == 0) {
      pos_ = i + 1;
      return i;
    }
  }
  Fatal(open, "'" + open.text + "' is never closed");
}

size_t EffectParser::FindAtDepthZero(std::initializer_list<std::string_view> stops) const {
  int depth = 0;
  for (size_t i = pos_; i < t_.size(); ++i) {
    const Token& t = t_[i];
    if (t.kind != TokenKind::Punctuator) continue;
    if (depth == 0 && std::find(stops.begin(), stops.end(), t.text) != stops.end()) return i;
    if (t.text == "(" || t.text == "[" || t.text == "{") ++depth;
    if (t.text == ")" || t.text == "]" || t.text == "}") {
      if (--depth < 0) return i;  // left the enclosing bracket: the caller reports it
    }
  }
  return t_.size();
}

std::string EffectParser::Spell(size_t begin, size_t end) const {
  std::string s;
  for (size_t i = begin; i < end && i < t_.size(); ++i) {
    if (i > begin && t_[i].offset > t_[i - 1].offset + t_[i - 1].text.size()) s += ' ';
    s += t_[i].text;
  }
  return s;
}

void EffectParser::Error(const Token& at, const std::string& message) {
  errors_.push_back(ParseError{at.where, message});
  if (errors_.size() >= kMaxErrors) throw FatalParseError{};
}

void EffectParser::Fatal(const Token& at, const std::string& message) {
  Error(at, message);
  throw FatalParseError{};
}

ConstValue EffectParser::Evaluate(size_t begin, size_t end, std::string_view what) {
  if (begin >= end) Fatal(begin < t_.size() ? t_[begin] : end_, "expected " + std::string(what));
  auto r = EvaluateConstant(t_, begin, end, constants_);
  if (auto* e = std::get_if<ConstError>(&r)) {
    Fatal(e->token < t_.size() ? t_[e->token] : end_, "invalid " + std::string(what) + ": " + e->message);
  }
  return std::get<ConstValue>(std::move(r));
}

uint32_t EffectParser::EvaluateUInt(size_t begin, size_t end, std::string_view what, uint64_t min, uint64_t max) {
  ConstValue v = Evaluate(begin, end, what);
  if (v.components.size() != 1 || v.components[0] != static_cast<double>(static_cast<int64_t>(v.components[0])) ||
      v.components[0] < static_cast<double>(min) || v.components[0] > static_cast<double>(max)) {
    Fatal(t_[begin], std::string(what) + " must be an integer in " + std::to_string(min) + ".." + std::to_string(max));
  }
  return static_cast<uint32_t>(v.components[0]);
}

void EffectParser::Blank(size_t firstToken, size_t lastToken) {
  if (firstToken >= t_.size() || lastToken < firstToken) return;
  lastToken = std::min(lastToken, t_.size() - 1);
  size_t begin = t_[firstToken].offset;
  size_t end = std::min(hlsl_.size(), t_[lastToken].offset + t_[lastToken].text.size());
  for (size_t i = begin; i < end; ++i) {
    bool lineStart = i == 0 || hlsl_[i - 1] == '\n';
    if (lineStart && hlsl_[i] == '#') {  // keep #line / #pragma lines
      while (i + 1 < end && hlsl_[i + 1] != '\n') ++i;
      continue;
    }
    if (hlsl_[i] != '\n') hlsl_[i] = ' ';
  }
}

std::string LineDirective(const SourceLocation& where) {
  std::string s = "#line " + std::to_string(where.line) + " \"";
  for (char c : where.file) {
    if (c == '"' || c == '\\') s += '\\';
    s += c;
  }
  return s + "\"\n";
}

void EffectParser::Hoist(size_t first, size_t last, size_t before) {
  size_t at = t_[before].offset;
  while (at > 0 && hlsl_[at - 1] != '\n') --at;
  std::string text = LineDirective(t_[first].where) + Spell(first, last + 1) + "\n" + LineDirective(t_[before].where);
  hoists_.emplace_back(at, std::move(text));
  Blank(first, last);
}

std::string EffectParser::ApplyHoists(std::string text) const {
  // In reverse, so earlier offsets stay valid; equal offsets keep source order.
  for (auto it = hoists_.rbegin(); it != hoists_.rend(); ++it) text.insert(it->first, it->second);
  return text;
}

// ---------------------------------------------------------------------------
// Top level

Result<EffectAst> EffectParser::Run() {
  try {
    ParseTopLevel();
  } catch (const FatalParseError&) {
  }
  if (!errors_.empty()) return errors_;
  if (globals_) {
    globals_->buffer.size = AlignUp16(globals_->used);
    globals_->buffer.defaults.resize(globals_->buffer.size);
    ast_.cbuffers.insert(ast_.cbuffers.begin(), std::move(globals_->buffer));
  }
  ast_.hlsl = ApplyHoists(std::move(hlsl_)) + VariantSource();
  return std::move(ast_);
}

void EffectParser::ParseTopLevel() {
  while (!AtEnd()) {
    ApplyPragmas();
    const Token& t = Peek();
    if (Accept(";")) continue;
    if (t.kind == TokenKind::Identifier) {
      const std::string& w = t.text;
      if (w == "cbuffer" || w == "tbuffer" ||
          (w == "shared" && (IsIdent(1, "cbuffer") || IsIdent(1, "tbuffer")))) {
        ParseBuffer();
        continue;
      }
      if (w == "struct") {
        ParseStruct();
        continue;
      }
      if (w == "typedef") {
        ParseTypedef();
        continue;
      }
      if (w == "technique" || w == "technique10" || w == "technique11") {
        ParseTechnique("");
        continue;
      }
      if (w == "fxgroup") {
        ParseGroup();
        continue;
      }
      if (w == "interface" || w == "class") Fatal(t, "'" + w + "' (dynamic shader linkage) is not supported");
      if (w == "namespace") Fatal(t, "'namespace' is not supported");
    }
    size_t attributesStart = pos_;
    while (IsPunct(0, "[")) SkipBalanced();
    ParseDeclaration(pos_, attributesStart, nullptr);
  }
}

void EffectParser::ApplyPragmas() {
  for (; nextPragma_ < pragmas_.size() && pragmas_[nextPragma_].first <= pos_; ++nextPragma_) {
    std::string compact;
    for (char c : pragmas_[nextPragma_].second) {
      if (c != ' ' && c != '\t') compact += c;
    }
    if (compact == "pack_matrix(row_major)") rowMajorDefault_ = true;
    if (compact == "pack_matrix(column_major)") rowMajorDefault_ = false;
  }
}

// [shared] cbuffer|tbuffer Name [: register(bN)] { declarations } [;]
void EffectParser::ParseBuffer() {
  BufferBuilder b;
  b.firstToken = pos_;
  if (IsIdent(0, "shared")) {
    b.buffer.shared = true;
    Blank(pos_, pos_);
    ++pos_;
  }
  b.buffer.isTBuffer = Take().text == "tbuffer";
  const Token& name = ExpectIdentifier("a constant buffer name");
  b.buffer.name = name.text;
  b.buffer.where = name.where;
  if (Accept(":")) {
    if (!IsIdent(0, "register")) Fatal(Peek(), "expected register(bN) after ':'");
    b.buffer.reg = ParseRegister();
  }
  if (IsPunct(0, "<")) {
    size_t begin = pos_;
    ParseAnnotations();
    Blank(begin, pos_ - 1);
  }
  const Token& open = Expect("{", "to open the constant buffer");
  while (!Accept("}")) {
    if (AtEnd()) Fatal(open, "unterminated cbuffer '" + b.buffer.name + "': '{' is never closed");
    ApplyPragmas();
    if (Accept(";")) continue;
    ParseDeclaration(pos_, pos_, &b);
  }
  Accept(";");
  b.buffer.size = AlignUp16(b.used);
  b.buffer.defaults.resize(b.buffer.size);
  ast_.cbuffers.push_back(std::move(b.buffer));
}

// struct Name { members }; - kept in the HLSL, and laid out when every member
// is numeric so that cbuffers can hold it.
void EffectParser::ParseStruct() {
  size_t start = pos_;
  ++pos_;  // struct
  const Token& name = ExpectIdentifier("a struct name");
  size_t nameToken = pos_ - 1;
  if (Accept(";")) return;  // forward declaration
  const Token& open = Expect("{", "to open the struct");
  VariableType st;
  st.cls = VariableType::Class::Struct;
  st.name = name.text;
  bool numeric = true;
  while (!Accept("}")) {
    if (AtEnd()) Fatal(open, "unterminated struct '" + st.name + "': '{' is never closed");
    ApplyPragmas();
    if (Accept(";")) continue;
    if (IsIdent(0, "struct")) Fatal(Peek(), "nested struct definitions are not supported");
    DeclSpec spec = ParseDeclSpec(pos_);
    if (Peek().kind == TokenKind::Identifier && IsPunct(1, "(")) {  // a method: skip it
      numeric = false;
      pos_ += 1;
      SkipBalanced();
      if (Accept(":")) ExpectIdentifier("a semantic");
      if (IsPunct(0, "{")) SkipBalanced();
      continue;
    }
    while (true) {
      Declarator d = ParseDeclarator();
      std::optional<VariableType> type = types_.Resolve(spec.typeName, spec.templateArgs, RowMajor(spec));
      if (type) {
        type->arrayDims.insert(type->arrayDims.begin(), d.arrayDims.begin(), d.arrayDims.end());
        if (ComputeLayout(*type)) numeric = false;
        st.members.push_back(StructMember{d.name, *type, 0});
      } else {
        numeric = false;
      }
      if (Accept(",")) continue;
      Expect(";", "after the struct member");
      break;
    }
  }
  if (numeric && !st.members.empty() && !ComputeLayout(st)) types_.Add(st.name, st);
  if (Accept(";")) return;
  // `struct S { ... } s;` declares variables too.
  DeclSpec spec;
  spec.start = start;
  spec.typeToken = nameToken;
  spec.typeName = st.name;
  ParseDeclarators(spec, nullptr);
}

// typedef [const] type name[dims];
void EffectParser::ParseTypedef() {
  ++pos_;
  DeclSpec spec = ParseDeclSpec(pos_);
  while (true) {
    Declarator d = ParseDeclarator();
    std::optional<VariableType> type = types_.Resolve(spec.typeName, spec.templateArgs, RowMajor(spec));
    if (type) {
      type->arrayDims.insert(type->arrayDims.begin(), d.arrayDims.begin(), d.arrayDims.end());
      if (!ComputeLayout(*type)) types_.Add(d.name, *type);
    }
    if (!Accept(",")) break;
  }
  Expect(";", "after the typedef");
}

// ---------------------------------------------------------------------------
// Declarations

DeclSpec EffectParser::ParseDeclSpec(size_t start) {
  DeclSpec s;
  s.start = start;
  while (Peek().kind == TokenKind::Identifier && IsModifier(Peek().text)) {
    s.modifiers.insert(Peek().text);
    s.modifierTokens.push_back(pos_++);
  }
  const Token& type = ExpectIdentifier("a type");
  s.typeToken = pos_ - 1;
  s.typeName = type.text;
  if (!IsPunct(0, "<")) return s;
  size_t openIndex = pos_;
  const Token& open = Take();
  int depth = 1;
  size_t argBegin = pos_;
  for (; depth > 0; ++pos_) {
    if (AtEnd()) Fatal(open, "'<' of the template arguments is never closed");
    const Token& t = t_[pos_];
    if (t.kind != TokenKind::Punctuator) continue;
    int closes = t.text == ">" ? 1 : t.text == ">>" ? 2 : 0;
    if (t.text == "<") ++depth;
    if (closes > depth) Fatal(t, "unbalanced '>' in template arguments");
    if (t.text == "," && depth == 1) {
      s.templateArgs.push_back(Spell(argBegin, pos_));
      argBegin = pos_ + 1;
    }
    if (closes > 0 && (depth -= closes) == 0) {
      std::string tail = closes == 2 ? ">" : "";  // `vector<float,4>>` closes two levels
      s.templateArgs.push_back(Spell(argBegin, pos_) + tail);
      s.templateText = Spell(openIndex + 1, pos_) + tail;
    }
  }
  return s;
}

Declarator EffectParser::ParseDeclarator() {
  Declarator d;
  const Token& name = ExpectIdentifier("a name");
  d.nameToken = pos_ - 1;
  d.name = name.text;
  while (IsPunct(0, "[")) {
    size_t open = pos_;
    if (IsPunct(1, "]")) {
      d.arrayDims.push_back(0);  // unsized
      pos_ += 2;
      continue;
    }
    size_t close = SkipBalanced();
    d.arrayDims.push_back(EvaluateUInt(open + 1, close, "array size", 1, kMaxConstantBufferBytes));
  }
  while (IsPunct(0, ":")) {
    size_t colon = pos_++;
    if (IsIdent(0, "register")) {
      d.reg = ParseRegister();
    } else if (IsIdent(0, "packoffset")) {
      d.packOffset = ParsePackOffset();
    } else {
      d.semantic = ExpectIdentifier("a semantic, register() or packoffset()").text;
      d.semanticTokens = std::make_pair(colon, pos_ - 1);
    }
  }
  if (IsPunct(0, "<")) {
    size_t begin = pos_;
    d.annotations = ParseAnnotations();
    d.annotationTokens = std::make_pair(begin, pos_ - 1);
  }
  return d;
}

// register([profile,] xN [, spaceM])
Register EffectParser::ParseRegister() {
  const Token& kw = Take();
  Expect("(", "after 'register'");
  std::optional<Register> r;
  uint32_t space = 0;
  while (!Accept(")")) {
    const Token& part = Take();
    if (part.kind == TokenKind::Identifier && part.text.size() >= 2) {
      const std::string& s = part.text;
      bool digits = s.find_first_not_of("0123456789", 1) == std::string::npos && s.size() <= 10;
      if (s.rfind("space", 0) == 0 && s.size() > 5 && s.size() <= 14 &&
          s.find_first_not_of("0123456789", 5) == std::string::npos) {
        space = static_cast<uint32_t>(std::stoul(s.substr(5)));
      } else if (digits && std::string_view("bcstuBCSTU").find(s[0]) != std::string_view::npos) {
        r = Register{static_cast<char>(std::tolower(static_cast<unsigned char>(s[0]))),
                     static_cast<uint32_t>(std::stoul(s.substr(1))), 0};
      }
    } else if (part.kind != TokenKind::Punctuator || part.text != ",") {
      Fatal(part, "invalid register '" + part.text + "'");
    }
  }
  if (!r) Fatal(kw, "register() needs a register such as b0, t1 or s2");
  r->space = space;
  return *r;
}

// packoffset(cN[.x|y|z|w]) -> byte offset
uint32_t EffectParser::ParsePackOffset() {
  ++pos_;
  Expect("(", "after 'packoffset'");
  const Token& reg = ExpectIdentifier("a register such as c1");
  const std::string& s = reg.text;
  if (s.size() < 2 || s.size() > 5 || (s[0] != 'c' && s[0] != 'C') ||
      s.find_first_not_of("0123456789", 1) != std::string::npos) {
    Fatal(reg, "invalid packoffset register '" + s + "'");
  }
  uint32_t offset = static_cast<uint32_t>(std::stoul(s.substr(1))) * 16;
  if (Accept(".")) {
    const Token& c = ExpectIdentifier("a component");
    size_t at = std::string_view("xyzw").find(c.text);
    if (c.text.size() != 1 || at == std::string_view::npos) Fatal(c, "invalid packoffset component '" + c.text + "'");
    offset += static_cast<uint32_t>(at) * 4;
  }
  Expect(")", "after packoffset");
  return offset;
}

// < type name = value; ... >
std::vector<Annotation> EffectParser::ParseAnnotations() {
  const Token& open = Take();
  std::vector<Annotation> out;
  while (!Accept(">")) {
    if (AtEnd()) Fatal(open, "annotation block '<' is never closed");
    if (Accept(";")) continue;
    Annotation a;
    if (IsIdent(0, "const")) ++pos_;
    const Token& typeToken = ExpectIdentifier("an annotation type");
    a.type = typeToken.text;
    const Token& name = ExpectIdentifier("an annotation name");
    a.name = name.text;
    a.where = name.where;
    std::vector<uint32_t> dims;
    while (IsPunct(0, "[")) {
      size_t open = pos_, close = SkipBalanced();
      dims.push_back(EvaluateUInt(open + 1, close, "array size", 1, kMaxConstantBufferBytes));
    }
    Expect("=", "in the annotation");
    size_t begin = pos_, end = FindAtDepthZero({";"});
    if (a.type == "string") {
      for (size_t i = begin; i < end; ++i) {
        const Token& s = t_[i];
        if (s.kind == TokenKind::String) {
          a.stringValue += UnquoteString(s.text);
        } else if (s.kind != TokenKind::Punctuator || (s.text != "{" && s.text != "}" && s.text != ",")) {
          Fatal(s, "string annotation '" + a.name + "' needs a string literal");
        }
      }
    } else {
      a.values = Evaluate(begin, end, "annotation value").components;
      std::optional<VariableType> type = types_.Resolve(a.type, {}, rowMajorDefault_);
      if (!type) Fatal(typeToken, "unknown annotation type '" + a.type + "'");
      type->arrayDims = dims;
      if (std::optional<std::string> e = ComputeLayout(*type)) Fatal(typeToken, *e);
      a.valueType = *type;
      a.bytes.resize(AlignUp16(type->size));
      if (std::optional<std::string> e = WriteInitializer(*type, a.values, a.bytes, 0)) Error(name, *e);
    }
    pos_ = end;
    Expect(";", "after the annotation");
    out.push_back(std::move(a));
  }
  return out;
}

bool EffectParser::RowMajor(const DeclSpec& spec) const {
  if (spec.modifiers.count("row_major")) return true;
  if (spec.modifiers.count("column_major")) return false;
  return rowMajorDefault_;
}

VariableType EffectParser::ResolveNumericType(const DeclSpec& spec, const Declarator& d) {
  std::optional<VariableType> type = types_.Resolve(spec.typeName, spec.templateArgs, RowMajor(spec));
  if (!type) Fatal(t_[spec.typeToken], "unknown type '" + spec.typeName + "'");
  type->arrayDims.insert(type->arrayDims.begin(), d.arrayDims.begin(), d.arrayDims.end());
  for (uint32_t dim : type->arrayDims) {
    if (dim == 0) Fatal(t_[d.nameToken], "array '" + d.name + "' needs a size");
  }
  if (std::optional<std::string> e = ComputeLayout(*type)) Fatal(t_[d.nameToken], *e);
  return *type;
}

void EffectParser::ParseDeclaration(size_t start, size_t attributesStart, BufferBuilder* buffer) {
  DeclSpec spec = ParseDeclSpec(start);
  if (Peek().kind == TokenKind::Identifier && IsPunct(1, "(")) {
    if (buffer) Fatal(Peek(), "a function cannot be declared inside a cbuffer");
    ParseFunction(spec, attributesStart);
    return;
  }
  if (attributesStart != start) Fatal(t_[attributesStart], "attributes can only precede a function");
  ParseDeclarators(spec, buffer);
}

void EffectParser::ParseDeclarators(const DeclSpec& spec, BufferBuilder* buffer) {
  enum class Kind { Numeric, Resource, Sampler, Blend, DepthStencil, Rasterizer, Shader, String };
  const std::string& type = spec.typeName;
  std::optional<ResourceKind> resource = ResourceKindOf(type);
  std::optional<ShaderStage> stage = ShaderStageOfType(type);
  Kind kind = resource                                       ? Kind::Resource
              : IsSamplerType(type)                          ? Kind::Sampler
              : EqualsIgnoreCase(type, "BlendState")         ? Kind::Blend
              : EqualsIgnoreCase(type, "DepthStencilState")  ? Kind::DepthStencil
              : EqualsIgnoreCase(type, "RasterizerState")    ? Kind::Rasterizer
              : stage                                        ? Kind::Shader
              : type == "string"                             ? Kind::String
                                                             : Kind::Numeric;
  while (true) {
    Declarator d = ParseDeclarator();
    bool endedWithBlock = false;
    switch (kind) {
      case Kind::Numeric:
        HandleNumeric(spec, d, buffer);
        break;
      case Kind::Resource:
        HandleResource(spec, d, *resource);
        break;
      case Kind::Sampler:
        endedWithBlock = HandleSampler(spec, d);
        break;
      case Kind::Blend:
        endedWithBlock = HandleStateObject(spec, d, ast_.blendStates);
        break;
      case Kind::DepthStencil:
        endedWithBlock = HandleStateObject(spec, d, ast_.depthStencilStates);
        break;
      case Kind::Rasterizer:
        endedWithBlock = HandleStateObject(spec, d, ast_.rasterizerStates);
        break;
      case Kind::Shader:
        HandleShaderVariable(d, *stage);
        break;
      case Kind::String:
        HandleString(d);
        break;
    }
    if (Accept(",")) continue;
    if (Accept(";") || endedWithBlock) break;
    Fatal(Peek(), "expected ';' after '" + d.name + "', found '" + Peek().text + "'");
  }
  // Effect-only declarations vanish from the HLSL; the others lose what glslang rejects.
  // FX10's untyped `texture` only names a resource for the effect: shaders sample typed ones.
  bool untypedTexture = kind == Kind::Resource && *resource == ResourceKind::Texture;
  if (kind == Kind::Blend || kind == Kind::DepthStencil || kind == Kind::Rasterizer || kind == Kind::Shader ||
      kind == Kind::String || untypedTexture) {
    Blank(spec.start, pos_ - 1);
    return;
  }
  bool isStatic = spec.modifiers.count("static") != 0;
  if (buffer && kind == Kind::Numeric && isStatic) {
    // fxc: a static inside a cbuffer is no member of it, only scoped there;
    // glslang takes no such declaration, so it moves out, before the cbuffer.
    Hoist(spec.start, pos_ - 1, buffer->firstToken);
    return;
  }
  bool uniform = kind == Kind::Numeric && !isStatic && !spec.modifiers.count("groupshared");
  for (size_t i : spec.modifierTokens) {
    const std::string& m = t_[i].text;
    if (m == "shared" || (uniform && (m == "const" || m == "extern"))) Blank(i, i);
  }
}

void EffectParser::BlankDecorations(const Declarator& d) {
  if (d.semanticTokens) Blank(d.semanticTokens->first, d.semanticTokens->second);
  if (d.annotationTokens) Blank(d.annotationTokens->first, d.annotationTokens->second);
}

BufferBuilder& EffectParser::Globals(const Token& at) {
  if (!globals_) {
    globals_.emplace();
    globals_->buffer.name = "$Globals";
    globals_->buffer.where = at.where;
  }
  return *globals_;
}

bool EffectParser::HandleNumeric(const DeclSpec& spec, const Declarator& d, BufferBuilder* buffer) {
  size_t equals = pos_;
  bool hasInit = Accept("=");
  size_t initBegin = pos_, initEnd = pos_;
  if (hasInit) {
    initEnd = FindAtDepthZero({",", ";"});
    pos_ = initEnd;
  }
  BlankDecorations(d);
  bool isStatic = spec.modifiers.count("static") != 0;
  if (isStatic || spec.modifiers.count("groupshared")) {
    // Stays in the HLSL as it is; a static const value can size arrays and feed later initializers.
    if (isStatic && spec.modifiers.count("const") && hasInit) {
      auto value = EvaluateConstant(t_, initBegin, initEnd, constants_);
      std::optional<VariableType> type = types_.Resolve(spec.typeName, spec.templateArgs, false);
      if (auto* v = std::get_if<ConstValue>(&value); v && type) {
        bool isFloat = type->scalar == ScalarType::Float || type->scalar == ScalarType::Double;
        for (double& c : v->components) {
          if (!isFloat) c = type->scalar == ScalarType::Bool ? (c != 0) : std::trunc(c);
        }
        v->integral = !isFloat;
        constants_[d.name] = *v;
      }
    }
    return false;
  }
  ConstantVariable v;
  v.name = d.name;
  v.type = ResolveNumericType(spec, d);
  v.hasInitializer = hasInit;
  v.semantic = d.semantic;
  v.annotations = d.annotations;
  v.where = t_[d.nameToken].where;
  std::vector<double> values;
  if (hasInit) {
    values = Evaluate(initBegin, initEnd, "initializer of '" + d.name + "'").components;
    Blank(equals, initEnd - 1);  // glslang accepts no initializers on uniforms
  }
  BufferBuilder& b = buffer ? *buffer : Globals(t_[d.nameToken]);
  AddConstant(b, std::move(v), d.packOffset, hasInit ? &values : nullptr, t_[d.nameToken]);
  return false;
}

void EffectParser::AddConstant(BufferBuilder& b, ConstantVariable v, const std::optional<uint32_t>& packOffset,
                               const std::vector<double>* values, const Token& at) {
  uint32_t offset = packOffset ? *packOffset : PlaceVariable(b.used, v.type);
  if (uint64_t{offset} + v.type.size > kMaxConstantBufferBytes) {
    Fatal(at, "constant buffer '" + b.buffer.name + "' is larger than 64 KB");
  }
  v.offset = offset;
  b.used = std::max(b.used, offset + v.type.size);
  if (b.buffer.defaults.size() < AlignUp16(b.used)) b.buffer.defaults.resize(AlignUp16(b.used));
  if (values) {
    if (std::optional<std::string> e = WriteInitializer(v.type, *values, b.buffer.defaults, offset)) Error(at, *e);
  }
  b.buffer.variables.push_back(std::move(v));
}

void EffectParser::HandleResource(const DeclSpec& spec, const Declarator& d, ResourceKind kind) {
  if (IsPunct(0, "=")) Fatal(Peek(), "a texture or buffer cannot have an initializer");
  ResourceVariable r;
  r.name = d.name;
  r.kind = kind;
  r.templateArgs = spec.templateText;
  r.arrayDims = d.arrayDims;
  r.reg = d.reg;
  r.shared = spec.modifiers.count("shared") != 0;
  r.annotations = d.annotations;
  r.where = t_[d.nameToken].where;
  BlankDecorations(d);
  ast_.resources.push_back(std::move(r));
}

uint32_t EffectParser::ObjectElementCount(const Declarator& d) {
  uint64_t n = 1;
  for (uint32_t dim : d.arrayDims) {
    n *= dim;
    if (dim == 0 || n > kMaxObjectElements) {
      Fatal(t_[d.nameToken], "array '" + d.name + "' needs a size of 1.." + std::to_string(kMaxObjectElements));
    }
  }
  return static_cast<uint32_t>(n);
}

// SamplerState s [= sampler_state] { Filter = ...; ... }
bool EffectParser::HandleSampler(const DeclSpec& spec, const Declarator& d) {
  SamplerVariable s;
  s.name = d.name;
  s.comparison = EqualsIgnoreCase(spec.typeName, "SamplerComparisonState");
  uint32_t count = ObjectElementCount(d);
  s.descs.assign(count, DefaultSamplerDesc());
  s.textures.assign(count, "");
  s.arrayDims = d.arrayDims;
  s.reg = d.reg;
  s.shared = spec.modifiers.count("shared") != 0;
  s.annotations = d.annotations;
  s.where = t_[d.nameToken].where;
  size_t blockStart = pos_;
  bool equals = Accept("=");
  if (equals && IsIdent(0, "sampler_state")) ++pos_;
  bool block = IsPunct(0, "{");
  if (block) {
    ParseStateBlocks(s.descs, !d.arrayDims.empty(), &s.textures);
  } else if (equals) {
    Fatal(Peek(), "expected a sampler state block '{ ... }'");
  }
  if (pos_ > blockStart) Blank(blockStart, pos_ - 1);
  BlankDecorations(d);
  ast_.samplers.push_back(std::move(s));
  return block;
}

template <class Desc>
bool EffectParser::HandleStateObject(const DeclSpec& spec, const Declarator& d,
                                     std::vector<StateObjectVariable<Desc>>& out) {
  StateObjectVariable<Desc> v;
  v.name = d.name;
  v.descs.assign(ObjectElementCount(d), DefaultDesc<Desc>());
  v.arrayDims = d.arrayDims;
  v.shared = spec.modifiers.count("shared") != 0;
  v.annotations = d.annotations;
  v.where = t_[d.nameToken].where;
  bool equals = Accept("=");
  bool block = IsPunct(0, "{");
  if (block) {
    ParseStateBlocks(v.descs, !d.arrayDims.empty(), nullptr);
  } else if (equals) {
    Fatal(Peek(), "expected a state block '{ ... }'");
  }
  out.push_back(std::move(v));
  return block;
}

template <class Desc>
void EffectParser::ParseStateBlocks(std::vector<Desc>& descs, bool isArray, std::vector<std::string>* textures) {
  if (!isArray) {
    ParseStateBlock(descs[0], textures ? &(*textures)[0] : nullptr);
    return;
  }
  const Token& open = Expect("{", "to open the list of state blocks");
  for (size_t i = 0; !Accept("}"); ++i) {
    if (AtEnd()) Fatal(open, "unterminated list of state blocks: '{' is never closed");
    if (i >= descs.size()) Fatal(Peek(), "more state blocks than array elements");
    if (IsIdent(0, "sampler_state")) ++pos_;
    ParseStateBlock(descs[i], textures ? &(*textures)[i] : nullptr);
    if (!Accept(",")) {
      Expect("}", "after the last state block");
      break;
    }
  }
}

// { Member[index] = value; ... }
template <class Desc>
void EffectParser::ParseStateBlock(Desc& desc, std::string* samplerTexture) {
  const Token& open = Expect("{", "to open the state block");
  while (!Accept("}")) {
    if (AtEnd()) Fatal(open, "unterminated state block: '{' is never closed");
    if (Accept(";")) continue;
    const Token& member = ExpectIdentifier("a state name");
    std::optional<uint32_t> index;
    size_t indexToken = pos_;
    if (IsPunct(0, "[")) {
      size_t close = SkipBalanced();
      index = EvaluateUInt(indexToken + 1, close, "state index", 0, UINT32_MAX);
      ++indexToken;
    }
    Expect("=", "after the state name");
    size_t begin = pos_, end = FindAtDepthZero({";", "}"});
    if (end >= t_.size()) Fatal(open, "unterminated state block: '{' is never closed");
    StateValue value = ReadStateValue(begin, end);
    pos_ = end;
    if (samplerTexture && EqualsIgnoreCase(member.text, "Texture")) {
      // FX10 binds a texture in the sampler block; D3D11 samplers carry none.
      if (value.identifier.empty()) Error(t_[begin], "Texture needs a texture variable or NULL");
      *samplerTexture = value.identifier == "NULL" ? "" : value.identifier;
    } else if (std::optional<StateError> e = ApplyStateAssignment(desc, member.text, index, value)) {
      const Token& at = e->part == StateError::Part::Member  ? member
                        : e->part == StateError::Part::Index ? t_[indexToken]
                                                             : t_[begin];
      Error(at, e->message);
    }
    Expect(";", "after the state assignment");
  }
}

// A bare name (also FX10's <name> and (name)) stays a name for the state table;
// anything else is a constant expression.
StateValue EffectParser::ReadStateValue(size_t begin, size_t end) {
  StateValue v;
  if (begin >= end) Fatal(t_[std::min(begin, t_.size() - 1)], "expected a state value");
  size_t b = begin, e = end;
  if (e - b == 3 && t_[b + 1].kind == TokenKind::Identifier &&
      ((IsPunctAt(b, "<") && IsPunctAt(e - 1, ">")) || (IsPunctAt(b, "(") && IsPunctAt(e - 1, ")")))) {
    ++b;
    --e;
  }
  const Token& t = t_[b];
  if (e - b == 1 && t.kind == TokenKind::Identifier && t.text != "true" && t.text != "false" &&
      !constants_.count(t.text)) {
    v.identifier = t.text;
    return v;
  }
  v.numbers = Evaluate(begin, end, "state value").components;
  return v;
}

bool EffectParser::IsPunctAt(size_t index, std::string_view p) const {
  return index < t_.size() && t_[index].kind == TokenKind::Punctuator && t_[index].text == p;
}

void EffectParser::HandleString(const Declarator& d) {
  StringVariable s;
  s.name = d.name;
  s.annotations = d.annotations;
  s.where = t_[d.nameToken].where;
  uint32_t count = ObjectElementCount(d);
  if (Accept("=")) {
    size_t end = FindAtDepthZero({",", ";"});
    std::string current;
    bool any = false;
    for (; pos_ < end; ++pos_) {
      const Token& t = t_[pos_];
      if (t.kind == TokenKind::String) {
        current += UnquoteString(t.text);
        any = true;
      } else if (IsPunct(0, ",") || IsPunct(0, "}")) {
        if (any) s.values.push_back(current);
        current.clear();
        any = false;
      } else if (!IsPunct(0, "{")) {
        Fatal(t, "string '" + d.name + "' needs a string literal");
      }
    }
    if (any) s.values.push_back(current);
  }
  if (s.values.size() > count) Fatal(t_[d.nameToken], "too many strings for '" + d.name + "'");
  s.values.resize(count);
  ast_.strings.push_back(std::move(s));
}

// ---------------------------------------------------------------------------

Result<EffectAst> ParseEffect(const std::string& source, const std::string& fileName, const ParseOptions& options) {
  Result<PreprocessedSource> pp = Preprocess(source, fileName, options);
  if (auto* errors = std::get_if<std::vector<ParseError>>(&pp)) return std::move(*errors);
  return EffectParser(std::get<PreprocessedSource>(std::move(pp))).Run();
}

Result<EffectAst> ParseEffectFile(const std::string& path, const ParseOptions& options) {
  std::optional<std::string> source = ReadSourceFile(path, options);
  if (!source) return std::vector<ParseError>{ParseError{SourceLocation{path, 0, 0}, "cannot open file"}};
  return ParseEffect(*source, path, options);
}

}  // namespace fx
