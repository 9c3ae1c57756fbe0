// fxtool: the effect command-line tool.
//
//   fxtool info FILE.fx [-I dir] [-D NAME[=VALUE]]
//   fxtool run  FILE.fx --technique T [--pass P] [--points N | --vertices FILE]
//               [--target FORMAT:WxH[:clear=r,g,b,a][:samples=N]]... [--sample-mask M]
//               [--depth D32_FLOAT[:clear=1]] [--texture NAME=FILE]... [--set name=v1,v2,...]... [--out DIR] [--pixel x,y]... [--dispatch X,Y,Z]
//               [--buffer NAME:ELEMENTS]... [--so-bytes N] [--so-vertices N] [--so-uint SEM,...] [--topology NAME]
//               [--validation] [-I dir] [-D NAME=VALUE]
//
// `info` needs no GPU: it runs the effect front end and compiles every shader
// with the HLSL compiler. `run` creates an rhi::Device (RHI_DEVICE picks the
// Vulkan device), loads the effect with the runtime and draws or dispatches;
// what it needs to know of the effect comes from FX11's reflection
// (Get*ShaderDesc, GetTypeDesc), not from a second parse.
// Errors print as "file:line:col: error: message" and the exit code is 1
// (2 for bad usage, 3 for device/validation failures).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cfloat>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb_image_write.h>

#include "cli_args.h"
#include "fx/effect.h"
#include "fx/effect_parser.h"
#include "fx/gs_isolation.h"
#include "fx/so_decl.h"
#include "fxtool_names.h"
#include "hlsl/hlsl_compiler.h"
#include "rhi/query_wait.h"
#include "rhi/texture_files.h"
#include "rhi/rhi.h"
#include "rhi_reference/formats.h"

namespace {

using rhi::ComPtr;

constexpr const char* kUsage =
    "usage:\n"
    "  fxtool info FILE.fx [-I dir] [-D NAME[=VALUE]]\n"
    "  fxtool run FILE.fx --technique T [--pass P] [--points N | --vertices FILE]\n"
    "         [--target FORMAT:WxH[:clear=r,g,b,a][:samples=N]]... [--sample-mask M]\n"
    "         [--depth D32_FLOAT[:clear=1]] [--texture NAME=FILE]... [--set name=v1,v2,...]... [--out DIR] [--pixel x,y]... [--dispatch X,Y,Z]\n"
    "         [--buffer NAME:ELEMENTS]... [--so-bytes N] [--so-vertices N] [--so-uint SEM,...] [--topology NAME]\n"
    "         [--validation]"
    " [-I dir] [-D NAME=VALUE]\n";

struct Target {
  std::string formatName;
  rhi::DXGI_FORMAT format = rhi::DXGI_FORMAT_R8G8B8A8_UNORM;
  unsigned width = 0, height = 0;
  unsigned samples = 1;  // multisampled targets are resolved before they are read
  float clear[4] = {0, 0, 0, 0};
};

struct Options {
  std::string command, file;
  std::vector<std::string> includeDirs;
  std::vector<std::pair<std::string, std::string>> defines;
  std::string technique, pass;
  int points = -1;
  std::string verticesFile;
  std::vector<Target> targets;
  std::optional<unsigned> sampleMask;  // --sample-mask: replaces the pass's SampleMask
  std::vector<std::pair<std::string, std::string>> textures;  // --texture NAME=FILE
  bool depth = false;
  float depthClear = 1.0f;
  std::vector<std::pair<std::string, std::vector<double>>> sets;
  std::string outDir;
  std::vector<std::pair<unsigned, unsigned>> pixels;
  bool dispatch = false;
  unsigned groups[3] = {1, 1, 1};
  unsigned soBytes = 4096;
  unsigned soVertices = 4;
  std::string topology;
  bool validation = false;
  std::vector<std::pair<std::string, unsigned>> buffers;  // --buffer NAME:ELEMENTS
  std::set<std::string> soUint;  // SO semantics printed as uint32 instead of float
};

[[noreturn]] void Usage(const std::string& why) {
  std::fprintf(stderr, "fxtool: %s\n%s", why.c_str(), kUsage);
  std::exit(2);
}

// A bad value of an option: one line (cli_args.h says what was wrong), exit 2.
[[noreturn]] void BadValue(const std::string& error) {
  std::fprintf(stderr, "fxtool: %s\n", error.c_str());
  std::exit(2);
}

int64_t ParseInteger(const std::string& s, const std::string& what, int64_t min, int64_t max) {
  std::string error;
  std::optional<int64_t> value = cli::ParseInteger(what, s, min, max, &error);
  if (!value) BadValue(error);
  return *value;
}

std::vector<int64_t> ParseIntegers(const std::string& s, const std::string& what, char separator, size_t count,
                                   int64_t min, int64_t max) {
  std::string error;
  std::optional<std::vector<int64_t>> values = cli::ParseIntegers(what, s, separator, count, min, max, &error);
  if (!values) BadValue(error);
  return *values;
}

std::vector<std::string> Split(const std::string& s, char sep) {
  std::vector<std::string> out;
  std::string cur;
  std::istringstream in(s);
  while (std::getline(in, cur, sep)) out.push_back(cur);
  if (!s.empty() && s.back() == sep) out.push_back("");
  return out;
}

// A shader constant or clear value: any finite float.
double ParseNumber(const std::string& s, const std::string& what) {
  std::string error;
  std::optional<double> value = cli::ParseNumber(what, s, -FLT_MAX, FLT_MAX, &error);
  if (!value) BadValue(error);
  return *value;
}

std::vector<double> ParseNumbers(const std::string& s, const std::string& what) {
  std::vector<double> out;
  for (const std::string& part : Split(s, ',')) out.push_back(ParseNumber(part, what));
  return out;
}

// FORMAT:WxH[:clear=r,g,b,a][:samples=N]
Target ParseTarget(const std::string& spec) {
  std::vector<std::string> parts = Split(spec, ':');
  if (parts.size() < 2 || parts.size() > 4)
    Usage("--target wants FORMAT:WxH[:clear=r,g,b,a][:samples=N], got '" + spec + "'");
  Target t;
  t.formatName = parts[0];
  bool known = false;
  for (const auto& f : fxtool::TargetFormats())
    if (parts[0] == f.name || parts[0] == std::string("DXGI_FORMAT_") + f.name) {
      t.format = f.format;
      t.formatName = f.name;
      known = true;
    }
  if (!known) {
    std::string list;
    for (const auto& f : fxtool::TargetFormats()) list += std::string(" ") + f.name;
    Usage("unsupported target format '" + parts[0] + "' (supported:" + list + ")");
  }
  const std::vector<int64_t> size = ParseIntegers(parts[1], "--target size", 'x', 2, 1, 16384);
  t.width = static_cast<unsigned>(size[0]);
  t.height = static_cast<unsigned>(size[1]);
  for (size_t i = 2; i < parts.size(); ++i) {
    if (parts[i].rfind("clear=", 0) == 0) {
      std::vector<double> c = ParseNumbers(parts[i].substr(6), "--target clear");
      if (c.size() != 4) Usage("clear= wants 4 values");
      for (int k = 0; k < 4; ++k) t.clear[k] = static_cast<float>(c[k]);
    } else if (parts[i].rfind("samples=", 0) == 0) {
      t.samples = static_cast<unsigned>(ParseIntegers(parts[i].substr(8), "--target samples", ',', 1, 1, 32)[0]);
      // D3D11 resolves only float, UNORM and sRGB formats (ResolveSubresource).
      if (t.samples > 1 && rhi::reference::IsUintFormat(t.format))
        Usage("samples= needs a format that can be resolved; " + t.formatName + " cannot");
    } else {
      Usage("bad target option '" + parts[i] + "'");
    }
  }
  return t;
}

// Bounds of the counts the options take: vertices, points and buffer elements;
// stream-output bytes (a 256 MiB buffer).
constexpr int64_t kMaxElements = 1 << 24;
constexpr int64_t kMaxSoBytes = int64_t(1) << 28;

Options ParseArgs(int argc, char** argv) {
  Options o;
  if (argc < 3) Usage(argc < 2 ? "no command" : "no effect file");
  o.command = argv[1];
  if (o.command != "info" && o.command != "run") Usage("unknown command '" + o.command + "'");
  for (int i = 2; i < argc; ++i) {
    std::string a = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) Usage(a + " needs a value");
      return argv[++i];
    };
    if (a == "-I") o.includeDirs.push_back(value());
    else if (a.rfind("-I", 0) == 0 && a.size() > 2) o.includeDirs.push_back(a.substr(2));
    else if (a == "-D" || (a.rfind("-D", 0) == 0 && a.size() > 2)) {
      std::string d = a == "-D" ? value() : a.substr(2);
      size_t eq = d.find('=');
      o.defines.emplace_back(d.substr(0, eq), eq == std::string::npos ? "" : d.substr(eq + 1));
    } else if (a == "--technique") o.technique = value();
    else if (a == "--pass") o.pass = value();
    else if (a == "--points") o.points = static_cast<int>(ParseInteger(value(), a, 1, kMaxElements));
    else if (a == "--vertices") o.verticesFile = value();
    else if (a == "--target") o.targets.push_back(ParseTarget(value()));
    else if (a == "--sample-mask") {
      const std::string m = value();
      char* end = nullptr;
      const unsigned long mask = std::strtoul(m.c_str(), &end, 0);
      if (m.empty() || *end != '\0' || mask > 0xFFFFFFFFul) Usage("--sample-mask wants a 32-bit number, got '" + m + "'");
      o.sampleMask = static_cast<unsigned>(mask);
    } else if (a == "--texture") {
      const std::string t = value();
      const size_t eq = t.find('=');
      if (eq == std::string::npos || eq == 0 || eq + 1 == t.size()) Usage("--texture wants NAME=FILE, got '" + t + "'");
      o.textures.emplace_back(t.substr(0, eq), t.substr(eq + 1));
    }
    else if (a == "--depth") {
      std::vector<std::string> parts = Split(value(), ':');
      if (parts[0] != "D32_FLOAT") Usage("--depth supports D32_FLOAT only");
      o.depth = true;
      if (parts.size() > 1) {
        if (parts[1].rfind("clear=", 0) != 0) Usage("bad --depth option '" + parts[1] + "'");
        o.depthClear = static_cast<float>(ParseNumber(parts[1].substr(6), "--depth clear"));
      }
    } else if (a == "--set") {
      std::string s = value();
      size_t eq = s.find('=');
      if (eq == std::string::npos || eq == 0) Usage("--set wants name=v1,v2,...");
      o.sets.emplace_back(s.substr(0, eq), ParseNumbers(s.substr(eq + 1), "--set"));
    } else if (a == "--out") o.outDir = value();
    else if (a == "--pixel") {
      std::vector<int64_t> p = ParseIntegers(value(), a, ',', 2, 0, 16383);
      o.pixels.emplace_back(static_cast<unsigned>(p[0]), static_cast<unsigned>(p[1]));
    } else if (a == "--dispatch") {
      // D3D11_CS_DISPATCH_MAX_THREAD_GROUPS_PER_DIMENSION bounds each count.
      std::vector<int64_t> g = ParseIntegers(value(), a, ',', 3, 0, rhi::CS_DISPATCH_MAX_THREAD_GROUPS_PER_DIMENSION);
      o.dispatch = true;
      for (int k = 0; k < 3; ++k) o.groups[k] = static_cast<unsigned>(g[k]);
    } else if (a == "--so-bytes") o.soBytes = static_cast<unsigned>(ParseInteger(value(), a, 4, kMaxSoBytes));
    else if (a == "--so-vertices") o.soVertices = static_cast<unsigned>(ParseInteger(value(), a, 0, kMaxElements));
    else if (a == "--topology") o.topology = value();
    else if (a == "--so-uint") {
      for (const std::string& sem : Split(value(), ',')) o.soUint.insert(sem);
    }
    else if (a == "--buffer") {
      std::string b = value();
      size_t colon = b.find(':');
      if (colon == std::string::npos || colon == 0) Usage("--buffer wants NAME:ELEMENTS");
      const int64_t n = ParseInteger(b.substr(colon + 1), "--buffer ELEMENTS", 1, kMaxElements);
      o.buffers.emplace_back(b.substr(0, colon), static_cast<unsigned>(n));
    }
    else if (a == "--validation") o.validation = true;
    else if (!a.empty() && a[0] == '-') Usage("unknown option '" + a + "'");
    else if (o.file.empty()) o.file = a;
    else Usage("more than one effect file");
  }
  if (o.file.empty()) Usage("no effect file");
  if (o.command == "run" && o.technique.empty()) Usage("run needs --technique");
  if (o.points >= 0 && !o.verticesFile.empty()) Usage("--points and --vertices exclude each other");
  return o;
}

void PrintParseErrors(const std::vector<fx::ParseError>& errors) {
  for (const fx::ParseError& e : errors)
    std::fprintf(stderr, "%s:%d:%d: error: %s\n", e.where.file.c_str(), e.where.line, e.where.column, e.message.c_str());
}

fx::ParseOptions FrontEndOptions(const Options& o) {
  fx::ParseOptions p;
  p.includeDirs = o.includeDirs;
  p.defines = o.defines;
  return p;
}

// The front end's view of the effect, or nullopt after printing the errors.
std::optional<fx::EffectAst> Parse(const Options& o) {
  if (!std::filesystem::exists(o.file)) {
    std::fprintf(stderr, "%s:0:0: error: cannot open the effect file\n", o.file.c_str());
    return std::nullopt;
  }
  fx::Result<fx::EffectAst> r = fx::ParseEffectFile(o.file, FrontEndOptions(o));
  if (auto* errors = std::get_if<std::vector<fx::ParseError>>(&r)) {
    PrintParseErrors(*errors);
    return std::nullopt;
  }
  return std::get<fx::EffectAst>(std::move(r));
}

// ---------------------------------------------------------------------------
// info

std::string TypeText(const fx::VariableType& t) {
  std::string s = (t.rowMajor ? "row_major " : "") + t.name;
  for (uint32_t d : t.arrayDims) s += "[" + std::to_string(d) + "]";
  return s;
}

std::string Where(const fx::SourceLocation& w) {
  return w.file + ":" + std::to_string(w.line) + ":" + std::to_string(w.column);
}

template <class Var>
const Var* FindState(const std::vector<Var>& vars, const fx::ObjectRef& ref) {
  return ref.variable.empty() ? nullptr : fx::FindByName(vars, ref.variable);
}

template <class Desc>
std::string StateLine(const std::vector<fx::StateObjectVariable<Desc>>& vars, const fx::ObjectRef& ref) {
  if (ref.variable.empty()) return "NULL (defaults)";
  std::string s = ref.variable;
  const auto* v = FindState(vars, ref);
  if (!v) return s + " (unknown)";
  if (!v->arrayDims.empty()) s += "[" + std::to_string(ref.element) + "]";
  if (ref.element >= v->descs.size()) return s + " (element out of range)";
  std::vector<std::string> fields = fxtool::NonDefault(v->descs[ref.element]);
  s += ":";
  if (fields.empty()) s += " (all defaults)";
  for (const std::string& f : fields) s += " " + f;
  return s;
}

std::string ShaderLine(const fx::CompiledShader& sh) {
  std::string s = std::string(fxtool::StageName(sh.stage)) + " " + sh.function + " " + sh.profile;
  if (sh.entryPoint != sh.function) s += " (entry " + sh.entryPoint + ")";
  if (!sh.uniformArgs.empty()) {
    s += " uniform(";
    for (size_t i = 0; i < sh.uniformArgs.size(); ++i) s += (i ? ", " : "") + sh.uniformArgs[i];
    s += ")";
  }
  if (sh.hasStreamOutput) {
    s += " SO:";
    for (unsigned k = 0; k < rhi::SO_STREAM_COUNT; ++k)
      if (!sh.soDeclarations[k].empty()) s += " stream" + std::to_string(k) + "=\"" + sh.soDeclarations[k] + "\"";
    auto strides = sh.streamOutput.Strides();
    s += " strides=";
    for (unsigned k = 0; k < rhi::SO_BUFFER_SLOT_COUNT; ++k) s += (k ? "," : "") + std::to_string(strides[k]);
    s += sh.rasterizedStream == rhi::SO_NO_RASTERIZED_STREAM ? " rasterized=none"
                                                              : " rasterized=" + std::to_string(sh.rasterizedStream);
  }
  return s;
}

// `<indent>@Name = value` lines, one per annotation.
void PrintAnnotations(const std::vector<fx::Annotation>& annotations, const char* indent) {
  for (const fx::Annotation& a : annotations) {
    std::string value;
    if (a.type == "string") {
      value = "\"" + a.stringValue + "\"";
    } else {
      for (size_t i = 0; i < a.values.size(); ++i) {
        char number[32];
        std::snprintf(number, sizeof number, "%g", a.values[i]);
        value += (i ? ", " : "") + std::string(number);
      }
    }
    std::printf("%s@%s %s = %s\n", indent, a.type.c_str(), a.name.c_str(), value.c_str());
  }
}

// Compiles every distinct (entry, profile) of the effect; prints errors. Returns the failure count.
int CompileAll(const Options& o, const fx::EffectAst& ast, std::map<int, std::string>* status) {
  int failures = 0;
  std::map<std::pair<std::string, std::string>, std::string> done;
  for (size_t i = 0; i < ast.shaders.size(); ++i) {
    const fx::CompiledShader& sh = ast.shaders[i];
    auto key = std::make_pair(sh.entryPoint, sh.profile);
    auto it = done.find(key);
    if (it == done.end()) {
      hlsl::CompileRequest req;
      // As the runtime does: glslang 12 crashes on a source holding geometry
      // shaders of different stream types, so blank the other ones.
      req.source = fx::IsolateGeometryShader(ast.hlsl, {sh.entryPoint, sh.function});
      req.fileName = o.file;
      req.entryPoint = sh.entryPoint;
      req.profile = sh.profile;
      req.includeDirs = o.includeDirs;
      hlsl::CompileResult r = hlsl::CompileHlsl(req);
      std::string st;
      if (r.ok) {
        st = "ok, " + std::to_string(r.spirv.size() * 4) + " bytes SPIR-V";
      } else {
        ++failures;
        std::string text = r.FormatErrors();
        std::fputs(text.c_str(), stderr);
        if (!text.empty() && text.back() != '\n') std::fputc('\n', stderr);
        st = "FAILED";
      }
      it = done.emplace(key, st).first;
    }
    (*status)[static_cast<int>(i)] = it->second;
  }
  return failures;
}

int Info(const Options& o) {
  std::optional<fx::EffectAst> parsed = Parse(o);
  if (!parsed) return 1;
  const fx::EffectAst& ast = *parsed;
  std::map<int, std::string> status;
  int failures = CompileAll(o, ast, &status);

  std::printf("effect %s\n", o.file.c_str());
  for (const fx::Technique& t : ast.techniques) {
    std::printf("technique%d %s", t.version, t.name.c_str());
    if (!t.group.empty()) std::printf(" (fxgroup %s)", t.group.c_str());
    std::printf("  [%s]\n", Where(t.where).c_str());
    PrintAnnotations(t.annotations, "  ");
    for (const fx::Pass& p : t.passes) {
      std::printf("  pass %s\n", p.name.empty() ? "(unnamed)" : p.name.c_str());
      PrintAnnotations(p.annotations, "    ");
      for (const fx::PassAssignment& a : p.assignments) {
        if (auto* s = std::get_if<fx::ShaderAssignment>(&a.value)) {
          if (s->shader < 0) {
            std::printf("    %s NULL\n", fxtool::StageName(s->stage));
          } else {
            const fx::CompiledShader& sh = ast.shaders[s->shader];
            std::printf("    %s%s  [%s]\n", ShaderLine(sh).c_str(),
                        s->variable.empty() ? "" : (" via " + s->variable).c_str(), status[s->shader].c_str());
          }
        } else if (auto* b = std::get_if<fx::BlendStateAssignment>(&a.value)) {
          std::printf("    blend %s factor=(%g,%g,%g,%g) mask=0x%08X\n", StateLine(ast.blendStates, b->state).c_str(),
                      b->blendFactor[0], b->blendFactor[1], b->blendFactor[2], b->blendFactor[3], b->sampleMask);
        } else if (auto* d = std::get_if<fx::DepthStencilStateAssignment>(&a.value)) {
          std::printf("    depth-stencil %s ref=%u\n", StateLine(ast.depthStencilStates, d->state).c_str(), d->stencilRef);
        } else if (auto* r = std::get_if<fx::RasterizerStateAssignment>(&a.value)) {
          std::printf("    rasterizer %s\n", StateLine(ast.rasterizerStates, r->state).c_str());
        }
      }
    }
  }
  for (const fx::ConstantBuffer& cb : ast.cbuffers) {
    std::printf("%s %s size=%u", cb.isTBuffer ? "tbuffer" : "cbuffer", cb.name.c_str(), cb.size);
    if (cb.reg) std::printf(" register=%c%u", cb.reg->kind, cb.reg->index);
    std::printf("\n");
    for (const fx::ConstantVariable& v : cb.variables) {
      std::printf("  %s %s offset=%u size=%u%s%s\n", TypeText(v.type).c_str(), v.name.c_str(), v.offset, v.type.size,
                  v.semantic.empty() ? "" : (" semantic=" + v.semantic).c_str(), v.hasInitializer ? " (initialized)" : "");
      PrintAnnotations(v.annotations, "    ");
    }
  }
  for (const fx::ResourceVariable& r : ast.resources) {
    std::printf("resource %s%s%s%s\n", r.name.c_str(), r.templateArgs.empty() ? "" : (" <" + r.templateArgs + ">").c_str(),
                fx::IsUnorderedAccess(r.kind) ? " (UAV)" : "",
                r.reg ? (" register=" + std::string(1, r.reg->kind) + std::to_string(r.reg->index)).c_str() : "");
    PrintAnnotations(r.annotations, "  ");
  }
  for (const fx::SamplerVariable& s : ast.samplers)
    std::printf("sampler %s%s\n", s.name.c_str(), s.comparison ? " (comparison)" : "");
  for (const fx::BlendStateVariable& v : ast.blendStates)
    std::printf("blendstate %s%s\n", v.name.c_str(), v.descs.size() > 1 ? ("[" + std::to_string(v.descs.size()) + "]").c_str() : "");
  for (const fx::DepthStencilStateVariable& v : ast.depthStencilStates) std::printf("depthstencilstate %s\n", v.name.c_str());
  for (const fx::RasterizerStateVariable& v : ast.rasterizerStates) std::printf("rasterizerstate %s\n", v.name.c_str());
  for (const fx::StringVariable& v : ast.strings) {
    std::printf("string %s\n", v.name.c_str());
    PrintAnnotations(v.annotations, "  ");
  }
  if (failures) {
    std::fprintf(stderr, "fxtool: %d shader(s) failed to compile\n", failures);
    return 1;
  }
  return 0;
}

// ---------------------------------------------------------------------------
// run

int g_deviceErrors = 0;

bool Check(rhi::HRESULT hr, const char* what) {
  if (rhi::SUCCEEDED(hr)) return true;
  std::fprintf(stderr, "fxtool: error: %s failed (0x%08X)\n", what, static_cast<unsigned>(hr));
  return false;
}

std::string JsonNumber(double v) {
  if (std::isnan(v)) return "\"NaN\"";
  if (std::isinf(v)) return v > 0 ? "\"Infinity\"" : "\"-Infinity\"";
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.9g", v);
  return buf;
}

std::string JsonString(const std::string& s) {
  std::string out = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  return out + "\"";
}

using PassShaderGetter = rhi::HRESULT (fx::EffectPass::*)(fx::PASS_SHADER_DESC*);

// What `pass` sets on a stage, through FX11's reflection (Get*ShaderDesc, then
// GetShaderDesc); nullopt for NULL or a stage it leaves alone.
std::optional<fx::EFFECT_SHADER_DESC> StageShader(fx::EffectPass* pass, PassShaderGetter getter) {
  fx::PASS_SHADER_DESC where;
  fx::EFFECT_SHADER_DESC desc;
  if (!rhi::SUCCEEDED((pass->*getter)(&where)) ||
      !rhi::SUCCEEDED(where.pShaderVariable->GetShaderDesc(where.ShaderIndex, &desc)) || desc.BytecodeLength == 0)
    return std::nullopt;
  return desc;
}

std::string TypeNameOf(fx::EffectVariable* v) {
  fx::EFFECT_TYPE_DESC t;
  return rhi::SUCCEEDED(v->GetTypeDesc(&t)) && t.TypeName ? t.TypeName : "";
}

// The template argument of a type name such as "RWStructuredBuffer<float4>"; "" when none.
std::string TemplateArgument(const std::string& typeName) {
  size_t open = typeName.find('<');
  if (open == std::string::npos || typeName.back() != '>') return "";
  return typeName.substr(open + 1, typeName.size() - open - 2);
}

bool SetVariable(fx::Effect* effect, const std::string& name, const std::vector<double>& values) {
  fx::EffectVariable* v = effect->GetVariableByName(name.c_str());
  if (!v || !v->IsValid()) {
    std::fprintf(stderr, "fxtool: error: --set %s: no such variable\n", name.c_str());
    return false;
  }
  fx::EFFECT_TYPE_DESC t;
  if (!Check(v->GetTypeDesc(&t), "GetTypeDesc")) return false;
  std::string type = t.TypeName ? t.TypeName : "";
  if (t.Class == fx::SVC_MATRIX_ROWS || t.Class == fx::SVC_MATRIX_COLUMNS) {
    if (values.size() != t.Rows * t.Columns || t.Elements) {
      std::fprintf(stderr, "fxtool: error: --set %s: a %ux%u matrix wants %u values (row by row)\n", name.c_str(), t.Rows,
                   t.Columns, t.Rows * t.Columns);
      return false;
    }
    float m[16] = {};
    for (unsigned r = 0; r < t.Rows; ++r)
      for (unsigned c = 0; c < t.Columns; ++c) m[r * 4 + c] = static_cast<float>(values[r * t.Columns + c]);
    return Check(v->AsMatrix()->SetMatrix(m), "SetMatrix");
  }
  if (t.Class != fx::SVC_SCALAR && t.Class != fx::SVC_VECTOR) {
    std::fprintf(stderr, "fxtool: error: --set %s: only scalars, vectors and matrices can be set\n", name.c_str());
    return false;
  }
  const unsigned components = std::max(1u, t.Columns);
  const unsigned elements = std::max(1u, t.Elements);
  if (values.size() != components * elements) {
    std::fprintf(stderr, "fxtool: error: --set %s: %s wants %u values, got %zu\n", name.c_str(), type.c_str(),
                 components * elements, values.size());
    return false;
  }
  // FX11 packing: array elements start on 16-byte registers.
  const unsigned stride = t.Elements ? 16 : components * 4;
  std::vector<uint32_t> raw((elements - 1) * stride / 4 + components, 0);
  for (unsigned e = 0; e < elements; ++e)
    for (unsigned c = 0; c < components; ++c) {
      double x = values[e * components + c];
      uint32_t bits;
      if (type.rfind("bool", 0) == 0) bits = x != 0 ? 0xFFFFFFFFu : 0u;
      else if (type.rfind("int", 0) == 0) bits = static_cast<uint32_t>(static_cast<int32_t>(x));
      else if (type.rfind("uint", 0) == 0 || type.rfind("dword", 0) == 0) bits = static_cast<uint32_t>(x);
      else {
        float f = static_cast<float>(x);
        std::memcpy(&bits, &f, 4);
      }
      raw[(e * stride) / 4 + c] = bits;
    }
  return Check(v->SetRawValue(raw.data(), 0, static_cast<rhi::UINT>(raw.size() * 4)), "SetRawValue");
}

struct VertexData {
  std::vector<std::string> semantics;  // storage for SemanticName pointers
  std::vector<rhi::INPUT_ELEMENT_DESC> elements;
  std::vector<uint32_t> data;  // 32-bit components, bit patterns
  std::vector<char> kinds;      // per component: f, u, i
  unsigned stride = 0, count = 0;
};

// First non-comment line: the layout, e.g. "POSITION:3 COLOR0:4 SEEDAGE:2u" (N components,
// float32 unless suffixed u = uint32 or i = int32); then one vertex per line.
bool ReadVertices(const std::string& path, VertexData* v) {
  std::ifstream in(path);
  if (!in) {
    std::fprintf(stderr, "%s:0:0: error: cannot open the vertex file\n", path.c_str());
    return false;
  }
  std::string line;
  int lineNo = 0;
  std::vector<unsigned> widths;
  unsigned floatsPerVertex = 0;
  while (std::getline(in, line)) {
    ++lineNo;
    size_t hash = line.find('#');
    if (hash != std::string::npos) line.resize(hash);
    std::istringstream words(line);
    std::string w;
    std::vector<std::string> tokens;
    while (words >> w) tokens.push_back(w);
    if (tokens.empty()) continue;
    if (widths.empty()) {
      for (const std::string& tok : tokens) {
        size_t colon = tok.find(':');
        unsigned n = colon == std::string::npos ? 4 : static_cast<unsigned>(std::atoi(tok.c_str() + colon + 1));
        char kind = colon == std::string::npos || tok.back() < 'a' ? 'f' : tok.back();
        std::string sem = tok.substr(0, colon);
        if (n < 1 || n > 4 || sem.empty()) {
          std::fprintf(stderr, "%s:%d:1: error: layout entries are SEMANTIC:N with N in 1..4\n", path.c_str(), lineNo);
          return false;
        }
        size_t digits = sem.find_last_not_of("0123456789") + 1;
        unsigned index = digits < sem.size() ? static_cast<unsigned>(std::atoi(sem.c_str() + digits)) : 0;
        v->semantics.push_back(sem.substr(0, digits));
        static const rhi::DXGI_FORMAT floats[] = {rhi::DXGI_FORMAT_R32_FLOAT, rhi::DXGI_FORMAT_R32G32_FLOAT,
                                                  rhi::DXGI_FORMAT_R32G32B32_FLOAT, rhi::DXGI_FORMAT_R32G32B32A32_FLOAT};
        static const rhi::DXGI_FORMAT uints[] = {rhi::DXGI_FORMAT_R32_UINT, rhi::DXGI_FORMAT_R32G32_UINT,
                                                 rhi::DXGI_FORMAT_R32G32B32_UINT, rhi::DXGI_FORMAT_R32G32B32A32_UINT};
        static const rhi::DXGI_FORMAT ints[] = {rhi::DXGI_FORMAT_R32_SINT, rhi::DXGI_FORMAT_R32G32_SINT,
                                                rhi::DXGI_FORMAT_R32G32B32_SINT, rhi::DXGI_FORMAT_R32G32B32A32_SINT};
        if (kind != 'f' && kind != 'u' && kind != 'i') {
          std::fprintf(stderr, "%s:%d:1: error: component type suffix is u or i\n", path.c_str(), lineNo);
          return false;
        }
        const rhi::DXGI_FORMAT* formats = kind == 'u' ? uints : kind == 'i' ? ints : floats;
        v->elements.push_back({nullptr, index, formats[n - 1], 0, floatsPerVertex * 4, rhi::INPUT_PER_VERTEX_DATA, 0});
        for (unsigned k = 0; k < n; ++k) v->kinds.push_back(kind);
        widths.push_back(n);
        floatsPerVertex += n;
      }
      continue;
    }
    if (tokens.size() != floatsPerVertex) {
      std::fprintf(stderr, "%s:%d:1: error: a vertex has %u numbers, this line %zu\n", path.c_str(), lineNo,
                   floatsPerVertex, tokens.size());
      return false;
    }
    for (size_t k = 0; k < tokens.size(); ++k) {
      uint32_t bits;
      if (v->kinds[k] == 'u') bits = static_cast<uint32_t>(std::strtoul(tokens[k].c_str(), nullptr, 0));
      else if (v->kinds[k] == 'i') bits = static_cast<uint32_t>(static_cast<int32_t>(std::strtol(tokens[k].c_str(), nullptr, 0)));
      else {
        float f = std::strtof(tokens[k].c_str(), nullptr);
        std::memcpy(&bits, &f, 4);
      }
      v->data.push_back(bits);
    }
    ++v->count;
  }
  for (size_t i = 0; i < v->elements.size(); ++i) v->elements[i].SemanticName = v->semantics[i].c_str();
  v->stride = floatsPerVertex * 4;
  if (v->count == 0) {
    std::fprintf(stderr, "%s:%d:1: error: no vertices\n", path.c_str(), lineNo);
    return false;
  }
  return true;
}

rhi::PRIMITIVE_TOPOLOGY ParseTopology(const std::string& name) {
  static const std::pair<const char*, rhi::PRIMITIVE_TOPOLOGY> table[] = {
      {"POINTLIST", rhi::PRIMITIVE_TOPOLOGY_POINTLIST},
      {"LINELIST", rhi::PRIMITIVE_TOPOLOGY_LINELIST},
      {"LINESTRIP", rhi::PRIMITIVE_TOPOLOGY_LINESTRIP},
      {"TRIANGLELIST", rhi::PRIMITIVE_TOPOLOGY_TRIANGLELIST},
      {"TRIANGLESTRIP", rhi::PRIMITIVE_TOPOLOGY_TRIANGLESTRIP},
      {"1_CONTROL_POINT_PATCHLIST", rhi::PRIMITIVE_TOPOLOGY_1_CONTROL_POINT_PATCHLIST},
      {"3_CONTROL_POINT_PATCHLIST", rhi::PRIMITIVE_TOPOLOGY_3_CONTROL_POINT_PATCHLIST},
      {"4_CONTROL_POINT_PATCHLIST", rhi::PRIMITIVE_TOPOLOGY_4_CONTROL_POINT_PATCHLIST},
  };
  for (const auto& [n, t] : table)
    if (name == n) return t;
  Usage("unknown topology '" + name + "'");
}

struct TargetResources {
  ComPtr<rhi::Texture2D> texture;
  ComPtr<rhi::RenderTargetView> rtv;
  ComPtr<rhi::UnorderedAccessView> uav;
};

// Reads a target back as decoded RGBA floats (and the stored codes), row-major, top row first.
bool ReadBack(rhi::Device* device, rhi::DeviceContext* ctx, const Target& t, rhi::Texture2D* texture,
              std::vector<rhi::reference::Float4>* pixels, std::vector<rhi::reference::StoredColor>* stored) {
  rhi::TEXTURE2D_DESC desc{};
  texture->GetDesc(&desc);
  ComPtr<rhi::Texture2D> resolved;  // a multisampled target: the average of its samples
  if (desc.SampleDesc.Count > 1) {
    desc.SampleDesc = {1, 0};
    desc.BindFlags = rhi::BIND_RENDER_TARGET;
    if (!Check(device->CreateTexture2D(&desc, nullptr, resolved.GetAddressOf()), "CreateTexture2D(resolve)"))
      return false;
    ctx->ResolveSubresource(resolved.Get(), 0, texture, 0, desc.Format);
    texture = resolved.Get();
  }
  desc.Usage = rhi::USAGE_STAGING;
  desc.BindFlags = 0;
  desc.CPUAccessFlags = rhi::CPU_ACCESS_READ;
  desc.MiscFlags = 0;
  ComPtr<rhi::Texture2D> staging;
  if (!Check(device->CreateTexture2D(&desc, nullptr, staging.GetAddressOf()), "CreateTexture2D(staging)")) return false;
  ctx->CopyResource(staging.Get(), texture);
  rhi::MAPPED_SUBRESOURCE mapped{};
  if (!Check(ctx->Map(staging.Get(), 0, rhi::MAP_READ, 0, &mapped), "Map(staging)")) return false;
  const size_t bpp = rhi::reference::BytesPerPixel(t.format);
  pixels->resize(size_t{t.width} * t.height);
  stored->resize(pixels->size());
  for (unsigned y = 0; y < t.height; ++y)
    for (unsigned x = 0; x < t.width; ++x) {
      const uint8_t* p = static_cast<const uint8_t*>(mapped.pData) + size_t{y} * mapped.RowPitch + x * bpp;
      rhi::reference::StoredColor s = rhi::reference::UnpackPixel(t.format, std::span<const uint8_t>(p, bpp));
      (*stored)[size_t{y} * t.width + x] = s;
      (*pixels)[size_t{y} * t.width + x] = rhi::reference::Decode(t.format, s);
    }
  ctx->Unmap(staging.Get(), 0);
  return true;
}

// DIR/targetN.png (8-bit, clamped) and DIR/targetN.f32: 16-byte header "F32\0",
// uint32 width, height, channels (4), then width*height*4 little-endian float32 RGBA, top row first.
bool SaveTarget(const std::string& dir, const std::string& name, const Target& t,
                const std::vector<rhi::reference::Float4>& pixels) {
  std::vector<uint8_t> rgba8(pixels.size() * 4);
  std::vector<float> f32(pixels.size() * 4);
  const bool uintFormat = rhi::reference::IsUintFormat(t.format);
  for (size_t i = 0; i < pixels.size(); ++i)
    for (int c = 0; c < 4; ++c) {
      float v = pixels[i][c];
      if (uintFormat) {
        uint32_t bits;
        std::memcpy(&bits, &v, 4);
        v = static_cast<float>(bits);
      }
      f32[i * 4 + c] = v;
      float clamped = std::isnan(v) ? 0.0f : std::clamp(v, 0.0f, 1.0f);
      rgba8[i * 4 + c] = static_cast<uint8_t>(clamped * 255.0f + 0.5f);
    }
  const std::string png = dir + "/" + name + ".png";
  if (!stbi_write_png(png.c_str(), static_cast<int>(t.width), static_cast<int>(t.height), 4, rgba8.data(),
                      static_cast<int>(t.width * 4))) {
    std::fprintf(stderr, "fxtool: error: cannot write %s\n", png.c_str());
    return false;
  }
  const std::string raw = dir + "/" + name + ".f32";
  std::ofstream out(raw, std::ios::binary);
  const uint32_t header[4] = {0x00323346u /* "F32\0" */, t.width, t.height, 4};
  out.write(reinterpret_cast<const char*>(header), sizeof header);
  out.write(reinterpret_cast<const char*>(f32.data()), static_cast<std::streamsize>(f32.size() * 4));
  if (!out) {
    std::fprintf(stderr, "fxtool: error: cannot write %s\n", raw.c_str());
    return false;
  }
  return true;
}

int Run(const Options& o) {
  if (!std::filesystem::exists(o.file)) {
    std::fprintf(stderr, "%s:0:0: error: cannot open the effect file\n", o.file.c_str());
    return 1;
  }
  // Before the device: BadValue exits, and a live device at exit is a leak (./run sanitize).
  if (std::string error; !o.outDir.empty() && !cli::MakeFolder("--out", o.outDir, &error)) BadValue(error);
  rhi::DEVICE_OPTIONS dopt;
  dopt.EnableValidation = o.validation ? rhi::TRUE : rhi::FALSE;
  dopt.OnMessage = [](rhi::MESSAGE_CATEGORY, rhi::MESSAGE_SEVERITY severity, const char* text) {
    if (severity <= rhi::MESSAGE_SEVERITY_ERROR) ++g_deviceErrors;
    if (severity <= rhi::MESSAGE_SEVERITY_WARNING) std::fprintf(stderr, "fxtool: device: %s\n", text);
  };
  ComPtr<rhi::Device> device;
  ComPtr<rhi::DeviceContext> ctx;
  if (!Check(rhi::CreateDevice(&dopt, device.GetAddressOf(), ctx.GetAddressOf()), "CreateDevice")) return 3;

  int rc = 0;
  {
    std::string errors;
    fx::EFFECT_OPTIONS eopt;
    eopt.IncludeDirs = o.includeDirs;
    eopt.Defines = o.defines;
    eopt.Errors = &errors;
    ComPtr<fx::Effect> effect;
    rhi::HRESULT hr = fx::CreateEffectFromFile(o.file.c_str(), eopt, device.Get(), effect.GetAddressOf());
    if (!rhi::SUCCEEDED(hr) || !effect) {
      std::fputs(errors.c_str(), stderr);
      if (!errors.empty() && errors.back() != '\n') std::fputc('\n', stderr);
      if (errors.empty()) std::fprintf(stderr, "%s:0:0: error: the effect runtime refused the effect\n", o.file.c_str());
      return 1;
    }
    fx::EffectTechnique* tech = effect->GetTechniqueByName(o.technique.c_str());
    if (!tech || !tech->IsValid()) {
      std::fprintf(stderr, "fxtool: error: no technique '%s'\n", o.technique.c_str());
      return 1;
    }
    fx::TECHNIQUE_DESC tdesc;
    tech->GetDesc(&tdesc);
    std::vector<unsigned> passes;
    if (o.pass.empty()) {
      for (unsigned i = 0; i < tdesc.Passes; ++i) passes.push_back(i);
    } else {
      for (unsigned i = 0; i < tdesc.Passes; ++i) {
        fx::PASS_DESC pd;
        tech->GetPassByIndex(i)->GetDesc(&pd);
        if ((pd.Name && o.pass == pd.Name) || o.pass == std::to_string(i)) passes.push_back(i);
      }
      if (passes.empty()) {
        std::fprintf(stderr, "fxtool: error: technique '%s' has no pass '%s'\n", o.technique.c_str(), o.pass.c_str());
        return 1;
      }
    }
    for (const auto& [name, values] : o.sets)
      if (!SetVariable(effect.Get(), name, values)) return 1;
    // --texture NAME=FILE: DDS, PNG, JPEG, TGA or BMP (rhi/texture_files.h), with its mip chain.
    std::vector<ComPtr<rhi::ShaderResourceView>> textures;
    for (const auto& [name, file] : o.textures) {
      fx::EffectShaderResourceVariable* var = effect->GetVariableByName(name.c_str())->AsShaderResource();
      if (!var->IsValid()) {
        std::fprintf(stderr, "fxtool: error: --texture %s: the effect has no shader-resource variable '%s'\n",
                     name.c_str(), name.c_str());
        return 1;
      }
      std::string error;
      ComPtr<rhi::ShaderResourceView>& srv = textures.emplace_back();
      if (rhi::FAILED(rhi::CreateTextureFromFile(device.Get(), ctx.Get(), file, rhi::WIC_LOADER_DEFAULT, nullptr,
                                                 srv.GetAddressOf(), &error))) {
        std::fprintf(stderr, "fxtool: error: --texture %s: %s\n", name.c_str(), error.c_str());
        return 1;
      }
      if (!Check(var->SetResource(srv.Get()), "SetResource")) return 1;
    }

    // Targets: render targets, or (for a compute pass) UAVs bound to the effect's
    // RWTexture2D variables in declaration order.
    std::vector<fx::EffectVariable*> rwTextures;
    fx::EFFECT_DESC edesc;
    effect->GetDesc(&edesc);
    for (unsigned i = 0; i < edesc.GlobalVariables; ++i) {
      std::string type = TypeNameOf(effect->GetVariableByIndex(i));
      if (type == "RWTexture2D" || type.rfind("RWTexture2D<", 0) == 0) rwTextures.push_back(effect->GetVariableByIndex(i));
    }
    bool anyCompute = false, anyGraphics = false;
    for (unsigned pi : passes) {
      if (StageShader(tech->GetPassByIndex(pi), &fx::EffectPass::GetComputeShaderDesc)) anyCompute = true;
      else anyGraphics = true;
    }
    std::vector<TargetResources> targets(o.targets.size());
    for (size_t i = 0; i < o.targets.size(); ++i) {
      const Target& t = o.targets[i];
      rhi::TEXTURE2D_DESC desc{};
      desc.Width = t.width;
      desc.Height = t.height;
      desc.MipLevels = 1;
      desc.ArraySize = 1;
      desc.Format = t.format;
      desc.SampleDesc = {t.samples, 0};
      desc.Usage = rhi::USAGE_DEFAULT;
      desc.BindFlags = (anyGraphics ? rhi::BIND_RENDER_TARGET : 0u) |
                       (anyCompute && i < rwTextures.size() ? rhi::BIND_UNORDERED_ACCESS : 0u);
      if (desc.BindFlags == 0) desc.BindFlags = rhi::BIND_RENDER_TARGET;
      if (!Check(device->CreateTexture2D(&desc, nullptr, targets[i].texture.GetAddressOf()), "CreateTexture2D(target)"))
        return 3;
      if (desc.BindFlags & rhi::BIND_RENDER_TARGET) {
        if (!Check(device->CreateRenderTargetView(targets[i].texture.Get(), nullptr, targets[i].rtv.GetAddressOf()),
                   "CreateRenderTargetView"))
          return 3;
        ctx->ClearRenderTargetView(targets[i].rtv.Get(), t.clear);
      }
      if (desc.BindFlags & rhi::BIND_UNORDERED_ACCESS) {
        if (!Check(device->CreateUnorderedAccessView(targets[i].texture.Get(), nullptr, targets[i].uav.GetAddressOf()),
                   "CreateUnorderedAccessView"))
          return 3;
        if (!(desc.BindFlags & rhi::BIND_RENDER_TARGET)) ctx->ClearUnorderedAccessViewFloat(targets[i].uav.Get(), t.clear);
        fx::EffectVariable* var = rwTextures[i];
        if (!Check(var->AsUnorderedAccessView()->SetUnorderedAccessView(targets[i].uav.Get()),
                           "SetUnorderedAccessView"))
          return 1;
      }
    }
    // --buffer NAME:ELEMENTS: a RWStructuredBuffer<T> (T a 32-bit scalar or vector) bound to the variable.
    struct UavBuffer {
      std::string name;
      char kind = 'f';
      unsigned components = 1, elements = 0;
      ComPtr<rhi::Buffer> buffer;
      ComPtr<rhi::UnorderedAccessView> uav;
    };
    std::vector<UavBuffer> uavBuffers;
    for (const auto& [name, n] : o.buffers) {
      const std::string typeName = TypeNameOf(effect->GetVariableByName(name.c_str()));
      const std::string element = TemplateArgument(typeName);
      if (typeName.rfind("RWStructuredBuffer<", 0) != 0) {
        std::fprintf(stderr, "fxtool: error: --buffer %s: no RWStructuredBuffer of that name\n", name.c_str());
        return 1;
      }
      UavBuffer b;
      b.name = name;
      b.elements = n;
      std::string t = element;
      t.erase(std::remove(t.begin(), t.end(), ' '), t.end());
      std::string base = t;
      if (!t.empty() && t.back() >= '1' && t.back() <= '4') {
        b.components = static_cast<unsigned>(t.back() - '0');
        base = t.substr(0, t.size() - 1);
      }
      if (base == "float") b.kind = 'f';
      else if (base == "uint" || base == "dword") b.kind = 'u';
      else if (base == "int") b.kind = 'i';
      else {
        std::fprintf(stderr, "fxtool: error: --buffer %s: element type '%s' is not a 32-bit scalar or vector\n",
                     name.c_str(), element.c_str());
        return 1;
      }
      rhi::BUFFER_DESC bd{};
      bd.ByteWidth = n * b.components * 4;
      bd.Usage = rhi::USAGE_DEFAULT;
      bd.BindFlags = rhi::BIND_UNORDERED_ACCESS;
      bd.MiscFlags = rhi::RESOURCE_MISC_BUFFER_STRUCTURED;
      bd.StructureByteStride = b.components * 4;
      std::vector<uint32_t> zeros(size_t{n} * b.components, 0);
      rhi::SUBRESOURCE_DATA init{zeros.data(), 0, 0};
      if (!Check(device->CreateBuffer(&bd, &init, b.buffer.GetAddressOf()), "CreateBuffer(--buffer)")) return 3;
      rhi::UNORDERED_ACCESS_VIEW_DESC ud{};
      ud.Format = rhi::DXGI_FORMAT_UNKNOWN;
      ud.ViewDimension = rhi::UAV_DIMENSION_BUFFER;
      ud.Buffer = {0, n, 0};
      if (!Check(device->CreateUnorderedAccessView(b.buffer.Get(), &ud, b.uav.GetAddressOf()), "CreateUnorderedAccessView(--buffer)"))
        return 3;
      if (!Check(effect->GetVariableByName(name.c_str())->AsUnorderedAccessView()->SetUnorderedAccessView(b.uav.Get()),
                 "SetUnorderedAccessView(--buffer)"))
        return 1;
      uavBuffers.push_back(std::move(b));
    }

    ComPtr<rhi::Texture2D> depthTex;
    ComPtr<rhi::DepthStencilView> dsv;
    if (o.depth) {
      if (o.targets.empty()) Usage("--depth needs a --target for its size");
      rhi::TEXTURE2D_DESC desc{};
      desc.Width = o.targets[0].width;
      desc.Height = o.targets[0].height;
      desc.MipLevels = 1;
      desc.ArraySize = 1;
      desc.Format = rhi::DXGI_FORMAT_D32_FLOAT;
      desc.Usage = rhi::USAGE_DEFAULT;
      desc.BindFlags = rhi::BIND_DEPTH_STENCIL;
      if (!Check(device->CreateTexture2D(&desc, nullptr, depthTex.GetAddressOf()), "CreateTexture2D(depth)") ||
          !Check(device->CreateDepthStencilView(depthTex.Get(), nullptr, dsv.GetAddressOf()), "CreateDepthStencilView"))
        return 3;
      ctx->ClearDepthStencilView(dsv.Get(), rhi::CLEAR_DEPTH, o.depthClear, 0);
    }

    VertexData verts;
    ComPtr<rhi::Buffer> vb;
    if (!o.verticesFile.empty()) {
      if (!ReadVertices(o.verticesFile, &verts)) return 1;
      rhi::BUFFER_DESC bd{};
      bd.ByteWidth = static_cast<rhi::UINT>(verts.data.size() * 4);
      bd.Usage = rhi::USAGE_DEFAULT;
      bd.BindFlags = rhi::BIND_VERTEX_BUFFER;
      rhi::SUBRESOURCE_DATA init{verts.data.data(), 0, 0};
      if (!Check(device->CreateBuffer(&bd, &init, vb.GetAddressOf()), "CreateBuffer(vertices)")) return 3;
    }

    std::string soJson;
    for (unsigned pi : passes) {
      fx::EffectPass* pass = tech->GetPassByIndex(pi);
      fx::PASS_DESC pd;
      pass->GetDesc(&pd);
      auto cs = StageShader(pass, &fx::EffectPass::GetComputeShaderDesc);
      auto gs = StageShader(pass, &fx::EffectPass::GetGeometryShaderDesc);
      auto hs = StageShader(pass, &fx::EffectPass::GetHullShaderDesc);
      // The stream-output layout, read back below, from the declaration strings as FX11 reports them.
      std::optional<fx::StreamOutputDecl> streamOutput;
      if (gs && std::any_of(std::begin(gs->SODecls), std::end(gs->SODecls), [](rhi::LPCSTR d) { return d; })) {
        std::vector<std::string> decls;
        for (rhi::LPCSTR d : gs->SODecls) decls.emplace_back(d ? d : "");
        auto parsed = fx::StreamOutputDecl::Parse(decls);
        if (auto* decl = std::get_if<fx::StreamOutputDecl>(&parsed)) streamOutput = std::move(*decl);
      }
      if (cs) {
        if (!Check(pass->Apply(0, ctx.Get()), "EffectPass::Apply")) return 1;
        ctx->Dispatch(o.groups[0], o.groups[1], o.groups[2]);
        rhi::UnorderedAccessView* none[rhi::PS_CS_UAV_REGISTER_COUNT] = {};
        ctx->CSSetUnorderedAccessViews(0, rhi::PS_CS_UAV_REGISTER_COUNT, none, nullptr);
        ctx->CSSetShader(nullptr, nullptr, 0);
        continue;
      }
      std::vector<rhi::RenderTargetView*> rtvs;
      for (auto& t : targets) rtvs.push_back(t.rtv.Get());
      ctx->OMSetRenderTargets(static_cast<rhi::UINT>(rtvs.size()), rtvs.data(), dsv.Get());
      if (!o.targets.empty()) {
        rhi::VIEWPORT vp{0, 0, static_cast<float>(o.targets[0].width), static_cast<float>(o.targets[0].height), 0, 1};
        ctx->RSSetViewports(1, &vp);
      } else {
        rhi::VIEWPORT vp{0, 0, 1, 1, 0, 1};
        ctx->RSSetViewports(1, &vp);
      }
      // What FX11 leaves to the caller: shaders the pass does not set stay as they were, so clear them first.
      ctx->HSSetShader(nullptr, nullptr, 0);
      ctx->DSSetShader(nullptr, nullptr, 0);
      ctx->GSSetShader(nullptr, nullptr, 0);
      ctx->PSSetShader(nullptr, nullptr, 0);
      if (!Check(pass->Apply(0, ctx.Get()), "EffectPass::Apply")) return 1;
      if (o.sampleMask) {  // the pass's blend state and factor with --sample-mask's mask
        ComPtr<rhi::BlendState> blend;
        rhi::FLOAT factor[4];
        ctx->OMGetBlendState(blend.GetAddressOf(), factor, nullptr);
        ctx->OMSetBlendState(blend.Get(), factor, *o.sampleMask);
      }

      rhi::PRIMITIVE_TOPOLOGY topology = rhi::PRIMITIVE_TOPOLOGY_TRIANGLELIST;
      unsigned count = 3;
      if (!o.verticesFile.empty()) {
        ComPtr<rhi::InputLayout> layout;
        if (!Check(device->CreateInputLayout(verts.elements.data(), static_cast<rhi::UINT>(verts.elements.size()),
                                             pd.pIAInputSignature, pd.IAInputSignatureSize, layout.GetAddressOf()),
                   "CreateInputLayout"))
          return 1;
        ctx->IASetInputLayout(layout.Get());
        rhi::Buffer* buffers[] = {vb.Get()};
        rhi::UINT strides[] = {verts.stride}, offsets[] = {0};
        ctx->IASetVertexBuffers(0, 1, buffers, strides, offsets);
        topology = rhi::PRIMITIVE_TOPOLOGY_POINTLIST;
        count = verts.count;
      } else {
        ctx->IASetInputLayout(nullptr);
        if (o.points >= 0) {
          topology = rhi::PRIMITIVE_TOPOLOGY_POINTLIST;
          count = static_cast<unsigned>(o.points);
        }
      }
      if (hs) topology = rhi::PRIMITIVE_TOPOLOGY_3_CONTROL_POINT_PATCHLIST;
      if (!o.topology.empty()) topology = ParseTopology(o.topology);
      ctx->IASetPrimitiveTopology(topology);

      ComPtr<rhi::Buffer> soBuffer;
      ComPtr<rhi::Query> soQuery;
      if (streamOutput) {
        rhi::BUFFER_DESC bd{};
        bd.ByteWidth = std::max(16u, o.soBytes);
        bd.Usage = rhi::USAGE_DEFAULT;
        bd.BindFlags = rhi::BIND_STREAM_OUTPUT;
        if (!Check(device->CreateBuffer(&bd, nullptr, soBuffer.GetAddressOf()), "CreateBuffer(stream output)")) return 3;
        rhi::Buffer* sob[] = {soBuffer.Get()};
        rhi::UINT offs[] = {0};
        ctx->SOSetTargets(1, sob, offs);
        rhi::QUERY_DESC qd{rhi::QUERY_SO_STATISTICS, 0};
        if (!Check(device->CreateQuery(&qd, soQuery.GetAddressOf()), "CreateQuery(SO_STATISTICS)")) return 3;
        ctx->Begin(soQuery.Get());
      }
      ctx->Draw(count, 0);
      if (soQuery) {
        ctx->End(soQuery.Get());
        ctx->SOSetTargets(0, nullptr, nullptr);
        rhi::QUERY_DATA_SO_STATISTICS stats{};
        if (!Check(rhi::WaitForData(ctx.Get(), soQuery.Get(), &stats), "GetData(SO_STATISTICS)")) return 3;
        // Read the first vertices back through a staging buffer.
        rhi::BUFFER_DESC sd{};
        sd.ByteWidth = std::max(16u, o.soBytes);
        sd.Usage = rhi::USAGE_STAGING;
        sd.CPUAccessFlags = rhi::CPU_ACCESS_READ;
        ComPtr<rhi::Buffer> staging;
        if (!Check(device->CreateBuffer(&sd, nullptr, staging.GetAddressOf()), "CreateBuffer(staging)")) return 3;
        ctx->CopyResource(staging.Get(), soBuffer.Get());
        rhi::MAPPED_SUBRESOURCE m{};
        if (!Check(ctx->Map(staging.Get(), 0, rhi::MAP_READ, 0, &m), "Map(stream output)")) return 3;
        const unsigned stride = streamOutput->Strides()[0];
        const auto& entries = streamOutput->Entries();
        uint64_t vertsPerPrim = topology == rhi::PRIMITIVE_TOPOLOGY_POINTLIST ? 1 : 0;  // GS output kind decides; report raw
        (void)vertsPerPrim;
        const uint64_t capacity = stride ? sd.ByteWidth / stride : 0;
        std::string vj = "[";
        unsigned shown = 0;
        // Vertices written: at most what fits. GS point streams write 1 vertex per primitive, strips 2 or 3;
        // print up to --so-vertices vertices from the start of the buffer.
        for (uint64_t v = 0; v < capacity && shown < o.soVertices && stride; ++v, ++shown) {
          if (stats.NumPrimitivesWritten == 0) break;
          const uint8_t* base = static_cast<const uint8_t*>(m.pData) + v * stride;
          vj += shown ? ", {" : "{";
          unsigned offset = 0;
          bool firstField = true;
          for (const rhi::SO_DECLARATION_ENTRY& e : entries) {
            if (e.OutputSlot != 0 || e.Stream != 0) continue;
            if (e.SemanticName) {
              std::string key = std::string(e.SemanticName) + (e.SemanticIndex ? std::to_string(e.SemanticIndex) : "");
              vj += (firstField ? "" : ", ") + JsonString(key) + ": [";
              const bool asUint = o.soUint.count(key) || o.soUint.count(e.SemanticName);
              for (unsigned c = 0; c < e.ComponentCount; ++c) {
                float f;
                uint32_t bits;
                std::memcpy(&f, base + offset + c * 4, 4);
                std::memcpy(&bits, base + offset + c * 4, 4);
                vj += (c ? ", " : "") + (asUint ? std::to_string(bits) : JsonNumber(f));
              }
              vj += "]";
              firstField = false;
            }
            offset += e.ComponentCount * 4u;
          }
          vj += "}";
        }
        vj += "]";
        ctx->Unmap(staging.Get(), 0);
        char head[256];
        std::snprintf(head, sizeof head,
                      "{\"pass\": %s, \"primitives_written\": %llu, \"primitives_storage_needed\": %llu, "
                      "\"stride\": %u, \"vertices\": ",
                      JsonString(pd.Name ? pd.Name : std::to_string(pi)).c_str(),
                      static_cast<unsigned long long>(stats.NumPrimitivesWritten),
                      static_cast<unsigned long long>(stats.PrimitivesStorageNeeded), stride);
        soJson += (soJson.empty() ? "" : ", ") + std::string(head) + vj + "}";
      }
    }
    ctx->ClearState();

    // Read back, save, print.
    std::string json = "{";
    bool firstKey = true;
    std::string storedJson;
    for (size_t i = 0; i < o.targets.size(); ++i) {
      std::vector<rhi::reference::Float4> pixels;
      std::vector<rhi::reference::StoredColor> stored;
      if (!ReadBack(device.Get(), ctx.Get(), o.targets[i], targets[i].texture.Get(), &pixels, &stored)) return 3;
      const std::string name = "target" + std::to_string(i);
      if (!o.outDir.empty() && !SaveTarget(o.outDir, name, o.targets[i], pixels)) rc = 1;
      if (o.pixels.empty()) continue;
      std::string pj, sj;
      for (const auto& [x, y] : o.pixels) {
        if (x >= o.targets[i].width || y >= o.targets[i].height) {
          std::fprintf(stderr, "fxtool: error: --pixel %u,%u is outside %s (%ux%u)\n", x, y, name.c_str(),
                       o.targets[i].width, o.targets[i].height);
          return 2;
        }
        const auto& p = pixels[size_t{y} * o.targets[i].width + x];
        const auto& s = stored[size_t{y} * o.targets[i].width + x];
        std::string key = "\"" + std::to_string(x) + "," + std::to_string(y) + "\": ";
        pj += (pj.empty() ? "" : ", ") + key + "[";
        sj += (sj.empty() ? "" : ", ") + key + "[";
        const bool uintFormat = rhi::reference::IsUintFormat(o.targets[i].format);
        for (int c = 0; c < 4; ++c) {
          double v = p[c];
          if (uintFormat) {
            uint32_t bits;
            std::memcpy(&bits, &p[c], 4);
            v = bits;
          }
          pj += (c ? ", " : "") + JsonNumber(v);
          sj += (c ? ", " : "") + std::to_string(s.bits[c]);
        }
        pj += "]";
        sj += "]";
      }
      json += (firstKey ? "\"" : ", \"") + name + "\": {" + pj + "}";
      storedJson += (storedJson.empty() ? "\"" : ", \"") + name + "\": {" + sj + "}";
      firstKey = false;
    }
    if (!storedJson.empty()) {
      json += ", \"stored\": {" + storedJson + "}";
    }
    std::string buffersJson;
    for (UavBuffer& b : uavBuffers) {
      rhi::BUFFER_DESC sd{};
      sd.ByteWidth = b.elements * b.components * 4;
      sd.Usage = rhi::USAGE_STAGING;
      sd.CPUAccessFlags = rhi::CPU_ACCESS_READ;
      ComPtr<rhi::Buffer> staging;
      if (!Check(device->CreateBuffer(&sd, nullptr, staging.GetAddressOf()), "CreateBuffer(staging)")) return 3;
      ctx->CopyResource(staging.Get(), b.buffer.Get());
      rhi::MAPPED_SUBRESOURCE m{};
      if (!Check(ctx->Map(staging.Get(), 0, rhi::MAP_READ, 0, &m), "Map(--buffer)")) return 3;
      std::string j;
      for (unsigned e = 0; e < b.elements; ++e) {
        j += e ? ", " : "";
        if (b.components > 1) j += "[";
        for (unsigned c = 0; c < b.components; ++c) {
          uint32_t bits;
          std::memcpy(&bits, static_cast<const uint8_t*>(m.pData) + (size_t{e} * b.components + c) * 4, 4);
          float f;
          std::memcpy(&f, &bits, 4);
          j += (c ? ", " : "") + (b.kind == 'u'   ? std::to_string(bits)
                                  : b.kind == 'i' ? std::to_string(static_cast<int32_t>(bits))
                                                  : JsonNumber(f));
        }
        if (b.components > 1) j += "]";
      }
      ctx->Unmap(staging.Get(), 0);
      buffersJson += (buffersJson.empty() ? "" : ", ") + JsonString(b.name) + ": [" + j + "]";
    }
    if (!buffersJson.empty()) {
      json += (firstKey ? "" : ", ") + std::string("\"buffers\": {") + buffersJson + "}";
      firstKey = false;
    }
    if (!soJson.empty()) {
      json += (firstKey ? "" : ", ") + std::string("\"stream_out\": [") + soJson + "]";
      firstKey = false;
    }
    json += "}";
    std::printf("%s\n", json.c_str());
  }
  if (g_deviceErrors) {
    std::fprintf(stderr, "fxtool: %d device/validation error(s)\n", g_deviceErrors);
    return 3;
  }
  return rc;
}

}  // namespace

int main(int argc, char** argv) {
  Options o = ParseArgs(argc, argv);
  return o.command == "info" ? Info(o) : Run(o);
}
