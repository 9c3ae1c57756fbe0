// The effect parser's internals, shared by effect_parser.cpp (declarations),
// technique_parser.cpp (techniques, passes, shader expressions) and
// shader_variants.cpp (functions and generated entry points).
#pragma once

#include <map>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "const_eval.h"
#include "fx/effect_ast.h"
#include "fx/preprocessor.h"
#include "fx/state_blocks.h"
#include "type_layout.h"

namespace fx {

// Thrown after a syntax error has been recorded: the parse cannot go on.
struct FatalParseError {};

// A function definition, kept to generate entry-point variants that bind
// uniform parameters.
struct FunctionInfo {
  struct Param {
    std::string text;  // the declaration as written, without its default value
    std::string name;
    bool uniform = false;
    std::string defaultValue;  // empty when none
  };
  std::string name;
  std::string attributes;  // "[maxvertexcount(3)]" etc. as written
  std::string returnType;
  std::string semantic;  // of the return value, empty when none
  std::vector<Param> params;
  SourceLocation where;
};

// `modifiers type<args>` at the start of a declaration.
struct DeclSpec {
  size_t start = 0;  // first token, attributes excluded
  std::set<std::string> modifiers;
  std::vector<size_t> modifierTokens;
  size_t typeToken = 0;
  std::string typeName;
  std::vector<std::string> templateArgs;  // split at top-level commas, as written
  std::string templateText;               // everything between < and >, as written
};

// `name[dims] : semantic : register(..) < annotations >` of one declarator.
struct Declarator {
  size_t nameToken = 0;
  std::string name;
  std::vector<uint32_t> arrayDims;
  std::string semantic;
  std::optional<std::pair<size_t, size_t>> semanticTokens;  // ": SEMANTIC", to blank
  std::optional<Register> reg;
  std::optional<uint32_t> packOffset;  // bytes
  std::vector<Annotation> annotations;
  std::optional<std::pair<size_t, size_t>> annotationTokens;  // "< ... >", to blank

  uint32_t ElementCount() const {
    uint32_t n = 1;
    for (uint32_t d : arrayDims) n *= d;
    return n;
  }
};

// A constant buffer being filled.
struct BufferBuilder {
  ConstantBuffer buffer;
  uint32_t used = 0;  // bytes taken so far
  size_t firstToken = 0;  // `cbuffer` (or `shared`): where its static declarations move to
};

// A shader named or built by an expression in a pass or a shader variable.
struct ShaderValue {
  int shader = -1;  // index into EffectAst::shaders, -1 for NULL
  std::string variable;
  uint32_t element = 0;
  ShaderStage stage = ShaderStage::Vertex;  // for NULL: any
  bool isNull = true;
};

class EffectParser {
 public:
  explicit EffectParser(PreprocessedSource source);
  Result<EffectAst> Run();

  // ---- token cursor ----
  const Token& Peek(size_t ahead = 0) const;
  bool AtEnd() const { return pos_ >= t_.size(); }
  const Token& Take();
  bool IsPunct(size_t ahead, std::string_view p) const;
  bool IsIdent(size_t ahead, std::string_view name) const;
  bool Accept(std::string_view punct);
  const Token& Expect(std::string_view punct, std::string_view context);
  const Token& ExpectIdentifier(std::string_view what);
  // At an opening bracket: moves past its match. Returns the closing token's index.
  size_t SkipBalanced();
  // Index of the first `stop` punctuator at bracket depth 0, from pos_.
  size_t FindAtDepthZero(std::initializer_list<std::string_view> stops) const;
  // The tokens [begin, end) as written (spaces where the output had them).
  std::string Spell(size_t begin, size_t end) const;

  // ---- errors ----
  [[noreturn]] void Fatal(const Token& at, const std::string& message);
  void Error(const Token& at, const std::string& message);
  ConstValue Evaluate(size_t begin, size_t end, std::string_view what);  // fatal on error
  uint32_t EvaluateUInt(size_t begin, size_t end, std::string_view what, uint64_t min, uint64_t max);
  bool IsPunctAt(size_t index, std::string_view p) const;

  // ---- HLSL editing ----
  void Blank(size_t firstToken, size_t lastToken);  // inclusive
  // Moves the declaration [first, last] to just before the line of token
  // `before`, between #line directives, so every position stays true.
  void Hoist(size_t first, size_t last, size_t before);
  std::string ApplyHoists(std::string text) const;

  // ---- declarations (effect_parser.cpp) ----
  void ParseTopLevel();
  void ApplyPragmas();  // those before pos_ (only pack_matrix matters)
  void ParseBuffer();
  void ParseStruct();
  void ParseTypedef();
  void ParseDeclaration(size_t start, size_t attributesStart, BufferBuilder* buffer);
  void ParseDeclarators(const DeclSpec& spec, BufferBuilder* buffer);
  DeclSpec ParseDeclSpec(size_t start);
  Declarator ParseDeclarator();
  Register ParseRegister();
  uint32_t ParsePackOffset();
  std::vector<Annotation> ParseAnnotations();
  bool RowMajor(const DeclSpec& spec) const;
  VariableType ResolveNumericType(const DeclSpec& spec, const Declarator& d);
  void BlankDecorations(const Declarator& d);  // its semantic and annotations
  BufferBuilder& Globals(const Token& at);      // $Globals, created on first use
  uint32_t ObjectElementCount(const Declarator& d);
  StateValue ReadStateValue(size_t begin, size_t end);

  // Each handles one declarator after its annotations; returns true when it
  // ended with a `{ }` block (after which the ';' is optional).
  bool HandleNumeric(const DeclSpec& spec, const Declarator& d, BufferBuilder* buffer);
  void HandleResource(const DeclSpec& spec, const Declarator& d, ResourceKind kind);
  bool HandleSampler(const DeclSpec& spec, const Declarator& d);
  template <class Desc>
  bool HandleStateObject(const DeclSpec& spec, const Declarator& d, std::vector<StateObjectVariable<Desc>>& out);
  void HandleShaderVariable(const Declarator& d, ShaderStage stage);
  void HandleString(const Declarator& d);
  void AddConstant(BufferBuilder& b, ConstantVariable v, const std::optional<uint32_t>& packOffset,
                   const std::vector<double>* values, const Token& at);

  // `{ Member[i] = value; ... }` into `descs` (an array takes `{ {..}, {..} }`).
  template <class Desc>
  void ParseStateBlocks(std::vector<Desc>& descs, bool isArray, std::vector<std::string>* samplerTextures);
  template <class Desc>
  void ParseStateBlock(Desc& desc, std::string* samplerTexture);

  // ---- techniques and shaders (technique_parser.cpp) ----
  void ParseGroup();
  void ParseTechnique(const std::string& group);
  Pass ParsePass();
  PassAssignment ParsePassAssignment();
  ObjectRef ParseStateRef(size_t begin, size_t end, std::string_view kind);
  ShaderValue ParseShaderValue(int depth);
  int ParseCompileShader(bool legacyCompileKeyword);
  int ParseConstructGSWithSO(int depth);
  std::vector<std::pair<size_t, size_t>> ParseArgumentRanges();

  // ---- functions and variants (shader_variants.cpp) ----
  void ParseFunction(const DeclSpec& spec, size_t attributesStart);
  void ParseParameter(FunctionInfo& f, size_t begin, size_t end);
  bool IsIdentAt(size_t index, std::string_view name) const;
  void RefuseD3D9TextureFunctions(size_t begin, size_t end);  // tokens of a function body
  void CheckPatchSizes(size_t begin, size_t end);              // tokens of a parameter
  // The entry point glslang compiles for `function` with `args` bound to its
  // uniform parameters (defaults appended to `args`); generates a variant when needed.
  std::string EntryPointFor(const Token& at, const std::string& function, std::vector<std::string>& args);
  std::string VariantSource() const;

  // ---- state ----
  std::vector<Token> t_;
  Token end_;  // returned by Peek() past the end
  size_t pos_ = 0;
  std::string hlsl_;
  EffectAst ast_;
  std::vector<ParseError> errors_;
  TypeTable types_;
  ConstantTable constants_;  // static const values
  std::optional<BufferBuilder> globals_;
  std::vector<std::pair<size_t, std::string>> pragmas_;  // (index of the next token, text)
  size_t nextPragma_ = 0;
  bool rowMajorDefault_ = false;  // #pragma pack_matrix
  std::map<std::string, std::vector<FunctionInfo>> functions_;
  std::map<std::string, std::string> variants_;  // "Function(args)" -> fx_variant_N
  std::vector<std::string> variantCode_;
  std::vector<std::pair<size_t, std::string>> hoists_;  // (offset in hlsl_, text inserted there)
};

bool EqualsIgnoreCase(std::string_view a, std::string_view b);

// `#line N "file"` and a newline: what follows is reported at `where`'s line.
std::string LineDirective(const SourceLocation& where);

// The text of a string literal token, with C escapes resolved.
std::string UnquoteString(const std::string& literal);

}  // namespace fx
