// The compile pipeline: glslang HLSL front end with D3D register mapping,
// SPIR-V generation, SPIRV-Tools legalization and validation, and turning
// glslang's info log into Diagnostics.

#include <glslang/MachineIndependent/localintermediate.h>
#include <glslang/Public/ResourceLimits.h>
#include <glslang/Public/ShaderLang.h>
#include <glslang/SPIRV/GlslangToSpv.h>

#include <rhi/shader_bindings.h>
#include <algorithm>
#include <cctype>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <list>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <regex>
#include <spirv-tools/libspirv.hpp>
#include <spirv-tools/optimizer.hpp>
#include <sstream>

#include "internal.h"

namespace hlsl::detail {
namespace {

namespace fs = std::filesystem;

constexpr char kSpirvEntryPoint[] = "main";
constexpr uint32_t kOpEntryPoint = 15;
constexpr char kPreambleName[] = "<defines>";

// --- Diagnostics

bool IsIdentifierChar(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; }

// The texts of line `line` of `file` as glslang numbers it: in `text` (named
// `textName`) after its #line directives, which the effect front end writes
// where an #include starts and ends and before its generated entry points
// (so one logical line may have several texts).
std::vector<std::string> LogicalLines(const std::string& text, const std::string& textName, const std::string& file,
                                      int line) {
  std::vector<std::string> found;
  static const std::regex kLineDirective(R"re(^\s*#\s*line\s+(\d{1,9})(?:\s+"((?:[^"\\]|\\.)*)")?\s*$)re");
  std::istringstream in(text);
  std::string current, name = textName;
  int number = 1;
  while (std::getline(in, current)) {
    std::smatch m;
    if (current.find('#') != std::string::npos && std::regex_match(current, m, kLineDirective)) {
      number = std::stoi(m[1]);
      if (m[2].matched) {
        const std::string quoted = m[2];
        name.clear();
        for (size_t i = 0; i < quoted.size(); ++i) name += quoted[i] == '\\' && i + 1 < quoted.size() ? quoted[++i] : quoted[i];
      }
      continue;
    }
    if (number == line && name == file) found.push_back(current);
    ++number;
  }
  return found;
}

// 1-based column of the n-th (0-based) occurrence of token on the line, as a
// whole word when the token is an identifier; 0 when there is none.
int FindColumn(const std::string& lineText, const std::string& token, int occurrence) {
  if (token.empty()) return 0;
  const bool word = std::all_of(token.begin(), token.end(), IsIdentifierChar);
  for (size_t at = lineText.find(token); at != std::string::npos; at = lineText.find(token, at + 1)) {
    const size_t end = at + token.size();
    const bool whole = (at == 0 || !IsIdentifierChar(lineText[at - 1])) &&
                       (end == lineText.size() || !IsIdentifierChar(lineText[end]));
    if (word && !whole) continue;
    if (occurrence-- == 0) return static_cast<int>(at) + 1;
  }
  return 0;
}

// glslang 12 tracks columns but prints only the line, so find the token the
// message quotes on that line. Repeated errors for one token on one line
// (x = y + y) map to successive occurrences.
int RecoverColumn(const Diagnostic& d, const std::vector<Diagnostic>& earlier, const SourceFiles& files) {
  static const std::regex kQuoted(R"(^'([^']*)' :)");
  std::smatch quoted;
  if (d.line <= 0 || !std::regex_search(d.message, quoted, kQuoted)) return 0;
  const std::string token = quoted[1];
  const auto same = std::count_if(earlier.begin(), earlier.end(), [&](const Diagnostic& e) {
    return e.file == d.file && e.line == d.line && e.message.starts_with(quoted[0].str());
  });
  for (const auto& [name, text] : files) {
    for (const std::string& lineText : LogicalLines(text, name, d.file, d.line)) {
      if (int column = FindColumn(lineText, token, static_cast<int>(same))) return column;
    }
  }
  return 0;
}

// Unlocated entries (link errors) are attributed to mainFile.
void ParseInfoLog(const std::string& log, const std::string& mainFile, const SourceFiles& files,
                  std::vector<Diagnostic>& errors, std::vector<Diagnostic>& warnings) {
  static const std::regex kEntry(R"(^(ERROR|WARNING|INTERNAL ERROR|UNIMPLEMENTED): (.*)$)");
  static const std::regex kLocated(R"(^(.*?):(\d{1,9}): (.*)$)");
  static const std::regex kSummary(R"(^\d+ compilation errors\.)");
  // "file(12): error at column 40, HLSL parsing failed.": where the parse
  // stopped, the column for that line's errors whose token was not found.
  static const std::regex kParseStop(R"(^(.*)\((\d{1,9})\): error at column (\d{1,9}), HLSL parsing failed\.)");
  std::istringstream in(log);
  for (std::string line; std::getline(in, line);) {
    std::smatch entry, located, stop;
    if (std::regex_search(line, stop, kParseStop)) {
      for (Diagnostic& e : errors) {
        if (e.column == 0 && e.file == stop[1].str() && e.line == std::stoi(stop[2])) e.column = std::stoi(stop[3]);
      }
      continue;
    }
    if (!std::regex_match(line, entry, kEntry)) continue;
    const std::string body = entry[2];
    if (std::regex_search(body, kSummary)) continue;  // "1 compilation errors.  No code generated."
    Diagnostic d{mainFile, 0, 0, body};
    if (std::regex_match(body, located, kLocated)) d = {located[1], std::stoi(located[2]), 0, located[3]};
    if (d.file == "-1") d.file = kPreambleName;  // glslang's name for the preamble string
    while (!d.message.empty() && std::isspace(static_cast<unsigned char>(d.message.back()))) d.message.pop_back();
    auto& sink = entry[1] == "WARNING" ? warnings : errors;
    d.column = RecoverColumn(d, sink, files);
    // "0:0: 'constructor' : can't convert" follows the error of the expression it is about.
    if (d.file == "0" && d.line == 0) {
      d.file = sink.empty() ? mainFile : sink.back().file;
      if (!sink.empty()) d.line = sink.back().line, d.column = sink.back().column;
    }
    sink.push_back(std::move(d));
  }
}

// --- Pipeline

void EnsureGlslangInitialized() {
  // glslang keeps process-wide tables; they must be built once, before any
  // TShader exists, and never torn down while another thread compiles.
  static std::once_flag once;
  std::call_once(once, [] { glslang::InitializeProcess(); });
}

EShLanguage ToGlslang(Stage stage) {
  switch (stage) {
    case Stage::Vertex: return EShLangVertex;
    case Stage::Hull: return EShLangTessControl;
    case Stage::Domain: return EShLangTessEvaluation;
    case Stage::Geometry: return EShLangGeometry;
    case Stage::Pixel: return EShLangFragment;
    case Stage::Compute: return EShLangCompute;
  }
  return EShLangVertex;
}

// Resolves "file.h" relative to the including file, then through includeDirs
// (glslang tries includeLocal first and falls back to includeSystem). Every
// file read is recorded in `files` so diagnostics can quote it later.
class Includer final : public glslang::TShader::Includer {
 public:
  Includer(const std::vector<std::string>& includeDirs, SourceFiles& files)
      : includeDirs_(includeDirs), files_(files) {}

  IncludeResult* includeLocal(const char* header, const char* includer, size_t) override {
    return TryOpen(fs::path(includer).parent_path() / header);
  }

  IncludeResult* includeSystem(const char* header, const char*, size_t) override {
    for (const std::string& dir : includeDirs_) {
      if (IncludeResult* found = TryOpen(fs::path(dir) / header)) return found;
    }
    // An empty headerName tells glslang the include failed; headerData is the reason.
    std::string& reason = messages_.emplace_back("cannot open include file (searched the including file's folder");
    for (const std::string& dir : includeDirs_) reason += ", " + dir;
    reason += ")";
    return new IncludeResult("", reason.data(), reason.size(), nullptr);
  }

  void releaseInclude(IncludeResult* result) override { delete result; }

 private:
  IncludeResult* TryOpen(const fs::path& path) {
    std::error_code ec;
    if (!fs::is_regular_file(path, ec)) return nullptr;
    std::ifstream in(path, std::ios::binary);
    if (!in) return nullptr;
    std::ostringstream text;
    text << in.rdbuf();
    const std::string name = path.lexically_normal().string();
    const std::string& stored = files_[name] = text.str();  // std::map keeps the data alive and in place
    return new IncludeResult(name, stored.data(), stored.size(), nullptr);
  }

  const std::vector<std::string>& includeDirs_;
  SourceFiles& files_;
  std::list<std::string> messages_;
};

std::string BuildPreamble(const std::vector<Define>& defines) {
  std::string preamble;
  for (const Define& d : defines) preamble += "#define " + d.name + " " + (d.value.empty() ? "1" : d.value) + "\n";
  return preamble;
}

// glslang 12's HLSL front end lacks GetRenderTargetSamplePosition (its
// Texture2DMS.GetSamplePosition is a table of D3D11's standard positions). A
// shader that calls it is compiled again with this definition: the same table,
// chosen by the render targets' sample count, which the backend supplies as
// the specialization constant kRenderTargetSampleCountSpecId. Positions are in
// pixels from the pixel centre; an index past the count gives (0, 0).
constexpr char kUnknownRenderTargetSamplePosition[] =
    "'GetRenderTargetSamplePosition' : no matching overloaded function found";

std::string RenderTargetSamplePositionPreamble() {
  return "[[vk::constant_id(" + std::to_string(rhi::kRenderTargetSampleCountSpecId) +
         ")]] const uint RhiRenderTargetSampleCount = 1;\n"
         "static const int2 RhiStandardPattern[30] = {  // 2, 4, 8 and 16 samples, from index count - 2\n"
         "  int2(4, 4), int2(-4, -4),\n"
         "  int2(-2, -6), int2(6, -2), int2(-6, 2), int2(2, 6),\n"
         "  int2(1, -3), int2(-1, 3), int2(5, 1), int2(-3, -5), int2(-5, 5), int2(-7, -1), int2(3, 7), int2(7, -7),\n"
         "  int2(1, 1), int2(-1, -3), int2(-3, 2), int2(4, -1), int2(-5, -2), int2(2, 5), int2(5, 3), int2(3, -5),\n"
         "  int2(-2, 6), int2(0, -7), int2(-4, -6), int2(-6, 4), int2(-8, 0), int2(7, -4), int2(6, 7), int2(-7, -8)};\n"
         "float2 GetRenderTargetSamplePosition(int index) {\n"
         "  uint count = RhiRenderTargetSampleCount;\n"
         "  if (count < 2 || count > 16 || (count & (count - 1)) != 0 || index < 0 || uint(index) >= count)\n"
         "    return float2(0, 0);\n"
         "  return RhiStandardPattern[count - 2 + index] / 16.0;\n"
         "}\n";
}

bool CallsMissingSamplePosition(const CompileResult& result) {
  return std::any_of(result.errors.begin(), result.errors.end(), [](const Diagnostic& d) {
    return d.message.find(kUnknownRenderTargetSamplePosition) != std::string::npos;
  });
}

// Puts each D3D register class of this stage into its rhi binding window of set 0.
void ConfigureShader(glslang::TShader& shader, Stage stage, EShLanguage lang) {
  using rhi::RegisterClass;
  const auto base = [stage](RegisterClass c) { return rhi::BindingFor(static_cast<rhi::ShaderStage>(stage), c, 0); };
  shader.setEnvInput(glslang::EShSourceHlsl, lang, glslang::EShClientVulkan, 100);
  shader.setEnvClient(glslang::EShClientVulkan, glslang::EShTargetVulkan_1_3);
  shader.setEnvTarget(glslang::EShTargetSpv, glslang::EShTargetSpv_1_5);
  shader.setEnvTargetHlslFunctionality1();  // keeps semantics as UserSemantic decorations
  shader.setHlslIoMapping(true);            // classify resources as b/t/s/u, not GLSL kinds
  shader.setAutoMapBindings(true);
  shader.setAutoMapLocations(true);
  shader.setResourceSetBinding({"0"});
  // The HLSL IO resolver only produces these four resource types.
  shader.setShiftBinding(glslang::EResUbo, base(RegisterClass::ConstantBuffer));
  shader.setShiftBinding(glslang::EResTexture, base(RegisterClass::ShaderResource));
  shader.setShiftBinding(glslang::EResSampler, base(RegisterClass::Sampler));
  shader.setShiftBinding(glslang::EResUav, base(RegisterClass::UnorderedAccess));
}

void AddError(CompileResult& result, const std::string& file, std::string message) {
  result.errors.push_back({file, 0, 0, std::move(message)});
}

// glslang 12's HLSL front end drops a pixel shader's SV_Coverage input
// declared as a plain entry-point parameter: it declares the SampleMaskIn
// variable but never copies it into the parameter, so the shader reads an
// undefined value (as a member of an input struct it is copied). Such an
// input is one the linker objects list and nothing in the shader reads.
class UnreadCoverageInput final : public glslang::TIntermTraverser {
 public:
  bool visitAggregate(glslang::TVisit, glslang::TIntermAggregate* node) override {
    if (node->getOp() != glslang::EOpLinkerObjects) return true;
    for (TIntermNode* object : node->getSequence()) {
      const glslang::TIntermSymbol* symbol = object->getAsSymbolNode();
      if (symbol && symbol->getQualifier().builtIn == glslang::EbvSampleMask &&
          symbol->getQualifier().storage == glslang::EvqVaryingIn)
        coverageInputs_.push_back(symbol->getId());
    }
    return false;
  }
  void visitSymbol(glslang::TIntermSymbol* symbol) override { read_.push_back(symbol->getId()); }
  bool Found() const {
    return std::any_of(coverageInputs_.begin(), coverageInputs_.end(),
                       [&](long long id) { return std::find(read_.begin(), read_.end(), id) == read_.end(); });
  }

 private:
  std::vector<long long> coverageInputs_, read_;
};

spvtools::MessageConsumer CollectInto(std::string& sink) {
  return [&sink](spv_message_level_t level, const char*, const spv_position_t& pos, const char* message) {
    if (level > SPV_MSG_ERROR) return;
    if (!sink.empty()) sink += "; ";
    sink += message;
    if (pos.index != 0) sink += " (word " + std::to_string(pos.index) + ")";
  };
}

// glslang emits HLSL "literally" (opaque types in function parameters and
// locals, static const arrays); the SPIRV-Tools legalization recipe inlines
// and forwards them so the module is valid for Vulkan. glslang's own call to
// it prints to std::cerr, so it is run here instead.
bool Legalize(std::vector<uint32_t>& spirv, std::string& error) {
  spvtools::Optimizer optimizer(SPV_ENV_VULKAN_1_3);
  optimizer.SetMessageConsumer(CollectInto(error));
  optimizer.RegisterLegalizationPasses();
  spvtools::OptimizerOptions options;
  options.set_run_validator(false);  // the input is not valid before legalization
  std::vector<uint32_t> legal;
  if (!optimizer.Run(spirv.data(), spirv.size(), &legal, options)) return false;
  spirv = std::move(legal);
  return true;
}

// Rewrites the (single) OpEntryPoint's name literal to "main".
void RenameEntryPoint(std::vector<uint32_t>& spirv) {
  for (size_t at = 5; at < spirv.size();) {
    const uint32_t count = spirv[at] >> 16;
    if (count == 0 || at + count > spirv.size()) return;
    if ((spirv[at] & 0xffff) != kOpEntryPoint) {
      at += count;
      continue;
    }
    size_t nameEnd = at + 3;  // words: opcode, execution model, function id, name..., interface ids...
    while (nameEnd < at + count && (spirv[nameEnd] >> 24) != 0) ++nameEnd;
    std::vector<uint32_t> name((sizeof(kSpirvEntryPoint) + 3) / 4, 0);
    std::memcpy(name.data(), kSpirvEntryPoint, sizeof(kSpirvEntryPoint));
    spirv.erase(spirv.begin() + at + 3, spirv.begin() + nameEnd + 1);
    spirv.insert(spirv.begin() + at + 3, name.begin(), name.end());
    const uint32_t newCount =
        count - static_cast<uint32_t>(nameEnd + 1 - (at + 3)) + static_cast<uint32_t>(name.size());
    spirv[at] = (newCount << 16) | kOpEntryPoint;
    return;
  }
}

// glslang's HLSL front end passes an integer literal given to a
// RWByteAddressBuffer atomic (raw.InterlockedAdd(0, 1), the comparand of
// InterlockedCompareExchange) as an `int` constant to a `uint` atomic, which
// SPIR-V forbids; fxc converts it. This gives each such operand the constant
// of the atomic's own type with the same bits (found, or added after that type).
class AtomicLiteralRetyper {
 public:
  explicit AtomicLiteralRetyper(std::vector<uint32_t>& spirv) : spirv_(spirv) {}

  void Run() {
    Index();
    for (size_t at = 5; at < spirv_.size() && (spirv_[at] >> 16) != 0; at += spirv_[at] >> 16) {
      const uint32_t op = spirv_[at] & 0xffff, count = spirv_[at] >> 16;
      if (op == kOpAtomicCompareExchange && count > 8) {
        Retype(at, 7);
        Retype(at, 8);
      } else if ((op == kOpAtomicExchange || (op >= kOpAtomicIAdd && op <= kOpAtomicXor)) && count > 6) {
        Retype(at, 6);
      }
    }
    InsertAddedConstants();
  }

 private:
  static constexpr uint32_t kOpTypeInt = 21, kOpConstant = 43, kOpAtomicExchange = 229,
                            kOpAtomicCompareExchange = 230, kOpAtomicIAdd = 234, kOpAtomicXor = 242;
  struct Constant {
    uint32_t type, value;
  };

  void Index() {
    for (size_t at = 5; at < spirv_.size() && (spirv_[at] >> 16) != 0; at += spirv_[at] >> 16) {
      const uint32_t op = spirv_[at] & 0xffff, count = spirv_[at] >> 16;
      if (op == kOpTypeInt && count == 4) intTypes_[spirv_[at + 1]] = {at, spirv_[at + 2]};
      if (op == kOpConstant && count == 4) {
        constants_[spirv_[at + 2]] = {spirv_[at + 1], spirv_[at + 3]};
        byValue_[{spirv_[at + 1], spirv_[at + 3]}] = spirv_[at + 2];
      }
    }
  }

  // Operand word `word` of the atomic at `at`, against its result type (word 1).
  void Retype(size_t at, size_t word) {
    const uint32_t type = spirv_[at + 1];
    const auto constant = constants_.find(spirv_[at + word]);
    if (constant == constants_.end() || constant->second.type == type) return;
    const auto from = intTypes_.find(constant->second.type), to = intTypes_.find(type);
    if (from == intTypes_.end() || to == intTypes_.end() || from->second.width != to->second.width) return;
    spirv_[at + word] = ConstantOf(type, constant->second.value);
  }

  uint32_t ConstantOf(uint32_t type, uint32_t value) {
    if (const auto it = byValue_.find({type, value}); it != byValue_.end()) return it->second;
    const uint32_t id = spirv_[3]++;  // the header's id bound
    added_[intTypes_.at(type).at].push_back({type, id, value});
    byValue_[{type, value}] = id;
    return id;
  }

  // After each integer type, the constants added of that type (positions from the back, so none moves).
  void InsertAddedConstants() {
    for (auto it = added_.rbegin(); it != added_.rend(); ++it) {
      std::vector<uint32_t> words;
      for (const auto& [type, id, value] : it->second) words.insert(words.end(), {4u << 16 | kOpConstant, type, id, value});
      spirv_.insert(spirv_.begin() + static_cast<std::ptrdiff_t>(it->first + 4), words.begin(), words.end());
    }
  }

  struct IntType {
    size_t at;
    uint32_t width;
  };
  struct Added {
    uint32_t type, id, value;
  };
  std::vector<uint32_t>& spirv_;
  std::map<uint32_t, IntType> intTypes_;
  std::map<uint32_t, Constant> constants_;
  std::map<std::pair<uint32_t, uint32_t>, uint32_t> byValue_;
  std::map<size_t, std::vector<Added>> added_;  // by the position of their type
};

bool Validate(const std::vector<uint32_t>& spirv, std::string& error) {
  spvtools::SpirvTools tools(SPV_ENV_VULKAN_1_3);
  tools.SetMessageConsumer(CollectInto(error));
  return tools.Validate(spirv);
}

// Parse, link and IO-map; reflection and SPIR-V generation need all three.
bool Frontend(const CompileRequest& request, const std::string& fileName, EShLanguage lang, Stage stage,
              bool samplePositions, glslang::TShader& shader, glslang::TProgram& program, SourceFiles& files,
              CompileResult& result) {
  const char* text = request.source.c_str();
  const int length = static_cast<int>(request.source.size());
  const char* name = fileName.c_str();
  const std::string preamble =
      BuildPreamble(request.defines) + (samplePositions ? RenderTargetSamplePositionPreamble() : std::string());
  shader.setStringsWithLengthsAndNames(&text, &length, &name, 1);
  shader.setPreamble(preamble.c_str());
  // glslang's own renaming (setEntryPoint("main") + setSourceEntryPoint) would
  // silently fall back to any function named "main" when the requested entry
  // point is missing, so the HLSL name is kept here and renamed in the SPIR-V.
  shader.setEntryPoint(request.entryPoint.c_str());
  ConfigureShader(shader, stage, lang);
  // glslang 12 does not switch HLSL buffers to the StorageBuffer class for
  // SPIR-V >= 1.3 itself; the old Uniform+BufferBlock form is invalid in 1.5.
  shader.getIntermediate()->setUseStorageBuffer();

  const auto messages =
      static_cast<EShMessages>(EShMsgSpvRules | EShMsgVulkanRules | EShMsgReadHlsl | EShMsgHlslOffsets);
  Includer includer(request.includeDirs, files);
  const bool parsed = shader.parse(GetDefaultResources(), 100, false, messages, includer);
  ParseInfoLog(shader.getInfoLog(), fileName, files, result.errors, result.warnings);
  if (!parsed) return false;

  program.addShader(&shader);
  const bool linked = program.link(messages);
  ParseInfoLog(program.getInfoLog(), fileName, files, result.errors, result.warnings);
  if (!linked) return false;
  if (program.getIntermediate(lang)->getNumEntryPoints() != 1) {
    AddError(result, fileName, "entry point '" + request.entryPoint + "' not found");
    return false;
  }
  UnreadCoverageInput coverage;
  program.getIntermediate(lang)->getTreeRoot()->traverse(&coverage);
  if (coverage.Found()) {
    AddError(result, fileName,
             "SV_Coverage input declared as a parameter of '" + request.entryPoint +
                 "': glslang's HLSL front end drops it (the shader would read an undefined value); declare it as a "
                 "member of the input struct");
    return false;
  }
  if (!program.mapIO()) {
    AddError(result, fileName, "resource binding assignment failed");
    return false;
  }
  return true;
}

std::vector<uint32_t> GenerateSpirv(const glslang::TProgram& program, EShLanguage lang, const std::string& fileName,
                                    CompileResult& result) {
  glslang::SpvOptions options;
  options.disableOptimizer = true;  // legalization runs in Legalize() with our message consumer
  options.validate = false;
  spv::SpvBuildLogger logger;
  std::vector<uint32_t> spirv;
  glslang::GlslangToSpv(*program.getIntermediate(lang), spirv, &logger, &options);
  if (const std::string log = logger.getAllMessages(); !log.empty()) result.warnings.push_back({fileName, 0, 0, log});
  return spirv;
}

void Finish(std::vector<uint32_t> spirv, const std::string& fileName, CompileResult& result) {
  std::string error;
  AtomicLiteralRetyper(spirv).Run();
  if (!Legalize(spirv, error)) return AddError(result, fileName, "SPIR-V legalization failed: " + error);
  RenameEntryPoint(spirv);
  if (!Validate(spirv, error)) return AddError(result, fileName, "SPIR-V validation failed: " + error);
  result.spirv = std::move(spirv);
}

}  // namespace

CompileResult CompileInProcess(const CompileRequest& request) {
  CompileResult result;
  const std::string fileName = SourceName(request);
  bool validProfile = false;
  result.stage = StageFromProfile(request.profile, &validProfile);
  if (!validProfile) {
    AddError(result, fileName,
             "unknown profile '" + request.profile + "' (expected vs/hs/ds/gs/ps/cs_4_0, _4_1 or _5_0)");
    return result;
  }
  if (request.entryPoint.empty()) {
    AddError(result, fileName, "no entry point given");
    return result;
  }
  static const std::regex kIdentifier(R"([A-Za-z_]\w*)");
  for (const Define& d : request.defines) {
    if (!std::regex_match(d.name, kIdentifier) || d.value.find_first_of("\r\n") != std::string::npos)
      AddError(result, fileName,
               "invalid define '" + d.name + "': the name must be an identifier and the value one line");
  }
  if (!result.errors.empty()) return result;

  EnsureGlslangInitialized();
  const EShLanguage lang = ToGlslang(result.stage);
  // The program must be destroyed before the shader it links.
  auto shader = std::make_unique<glslang::TShader>(lang);
  auto program = std::make_unique<glslang::TProgram>();
  SourceFiles files{{fileName, request.source}};
  bool ok = Frontend(request, fileName, lang, result.stage, false, *shader, *program, files, result);
  if (!ok && CallsMissingSamplePosition(result)) {
    // A glslang shader parses once: the second try, with the definition, needs new objects.
    program.reset();
    shader = std::make_unique<glslang::TShader>(lang);
    program = std::make_unique<glslang::TProgram>();
    result.errors.clear();
    result.warnings.clear();
    files = {{fileName, request.source}};
    ok = Frontend(request, fileName, lang, result.stage, true, *shader, *program, files, result);
  }
  if (!ok) {
    if (result.errors.empty()) AddError(result, fileName, "compilation failed");
    return result;
  }
  if (!program->buildReflection(EShReflectionAllBlockVariables | EShReflectionSeparateBuffers)) {
    AddError(result, fileName, "glslang reflection failed");
    return result;
  }
  std::vector<uint32_t> spirv = GenerateSpirv(*program, lang, fileName, result);
  // Reflect from the unoptimized module: it still has every declared block.
  Reflect(*program, result.stage, files, spirv, result);
  Finish(std::move(spirv), fileName, result);
  result.ok = result.errors.empty();
  return result;
}

}  // namespace hlsl::detail
