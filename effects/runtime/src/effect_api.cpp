// The entry points and the Effect / Technique lookups.
#include <strings.h>

#include <cstdio>
#include <exception>
#include <set>

#include "effect_impl.h"
#include "fx/effect_parser.h"
#include "rhi/wide_path.h"
#include "variables.h"

namespace fx {
namespace detail {
namespace {

PassImpl* InvalidPass() {
  static PassImpl invalid;
  return &invalid;
}

TechniqueImpl* InvalidTechnique() {
  static TechniqueImpl invalid;
  return &invalid;
}

HRESULT Create(const Result<EffectAst>& parsed, const EFFECT_OPTIONS& options, rhi::Device* device, Effect** out) {
  std::vector<std::string> errors;
  if (auto* parseErrors = std::get_if<std::vector<ParseError>>(&parsed)) {
    for (const ParseError& e : *parseErrors)
      errors.push_back(e.where.file + ":" + std::to_string(e.where.line) + ":" + std::to_string(e.where.column) +
                       ": error: " + e.message);
  } else {
    ComPtr<EffectImpl> effect;
    effect.Attach(new EffectImpl());
    effect->device = device;
    effect->ast = std::get<EffectAst>(parsed);
    if (LoadEffect(*effect, options, errors)) {
      *out = effect.Detach();
      return rhi::S_OK;
    }
  }
  if (options.Errors) {
    options.Errors->clear();
    for (const std::string& e : errors) *options.Errors += e + "\n";
  }
  return rhi::E_FAIL;
}

ParseOptions ToParseOptions(const EFFECT_OPTIONS& options) {
  ParseOptions parse;
  parse.includeDirs = options.IncludeDirs;
  parse.defines = options.Defines;
  return parse;
}

// Never let an exception (bad_alloc, a front-end bug) cross the C-style API.
template <class F>
HRESULT Guarded(const EFFECT_OPTIONS& options, rhi::Device* device, Effect** out, F parse) {
  if (!out) return rhi::E_INVALIDARG;
  *out = nullptr;
  if (!device) return rhi::E_INVALIDARG;
  try {
    return Create(parse(), options, device, out);
  } catch (const std::exception& e) {
    if (options.Errors) *options.Errors = std::string("<effect>: error: internal error: ") + e.what() + "\n";
    return rhi::E_FAIL;
  }
}

std::string ToHex(UINT value) {
  char text[9];
  std::snprintf(text, sizeof text, "%X", value);
  return text;
}

}  // namespace

EffectImpl::~EffectImpl() = default;

HRESULT EffectImpl::GetDevice(rhi::Device** ppDevice) {
  if (!ppDevice) return rhi::E_INVALIDARG;
  *ppDevice = device.Get();
  if (*ppDevice) (*ppDevice)->AddRef();
  return rhi::S_OK;
}

HRESULT EffectImpl::GetDesc(EFFECT_DESC* pDesc) {
  if (!pDesc) return rhi::E_INVALIDARG;
  *pDesc = stats;
  pDesc->ConstantBuffers = static_cast<UINT>(cbuffers.size());
  pDesc->GlobalVariables = static_cast<UINT>(globals.size());
  pDesc->Techniques = static_cast<UINT>(techniques.size());
  std::set<std::string> groups;
  for (const Technique& t : ast.techniques) {
    if (!t.group.empty()) groups.insert(t.group);
  }
  pDesc->Groups = static_cast<UINT>(groups.size());
  return rhi::S_OK;
}

VariableImpl* EffectImpl::Own(VariableImpl&& view) {
  views.push_back(std::move(view));
  return &views.back();
}

EffectConstantBuffer* EffectImpl::GetConstantBufferByIndex(UINT Index) {
  return Index < cbufferViews.size() ? cbufferViews[Index] : VariableImpl::Invalid();
}

EffectConstantBuffer* EffectImpl::GetConstantBufferByName(LPCSTR Name) {
  for (VariableImpl* v : cbufferViews)
    if (Name && v->name == Name) return v;
  return VariableImpl::Invalid();
}

EffectVariable* EffectImpl::GetVariableByIndex(UINT Index) {
  return Index < globals.size() ? globals[Index] : VariableImpl::Invalid();
}

EffectVariable* EffectImpl::GetVariableByName(LPCSTR Name) {
  for (VariableImpl* v : globals)
    if (Name && v->name == Name) return v;
  return VariableImpl::Invalid();
}

EffectVariable* EffectImpl::GetVariableBySemantic(LPCSTR Semantic) {
  for (VariableImpl* v : globals)
    if (Semantic && !v->semantic.empty() && strcasecmp(v->semantic.c_str(), Semantic) == 0) return v;
  return VariableImpl::Invalid();
}

EffectTechnique* EffectImpl::GetTechniqueByIndex(UINT Index) {
  return Index < techniques.size() ? &techniques[Index] : static_cast<EffectTechnique*>(InvalidTechnique());
}

EffectTechnique* EffectImpl::GetTechniqueByName(LPCSTR Name) {
  for (TechniqueImpl& t : techniques)
    if (Name && t.ast_->name == Name) return &t;
  return InvalidTechnique();
}

HRESULT TechniqueImpl::GetDesc(TECHNIQUE_DESC* pDesc) {
  if (!effect_ || !pDesc) return rhi::E_FAIL;
  pDesc->Name = ast_->name.c_str();
  pDesc->Passes = static_cast<UINT>(passes_.size());
  pDesc->Annotations = static_cast<UINT>(ast_->annotations.size());
  return rhi::S_OK;
}

EffectVariable* TechniqueImpl::GetAnnotationByIndex(UINT Index) {
  return effect_ ? effect_->Annotation(ast_->annotations, Index) : VariableImpl::Invalid();
}

EffectVariable* TechniqueImpl::GetAnnotationByName(LPCSTR Name) {
  return effect_ ? effect_->Annotation(ast_->annotations, Name) : VariableImpl::Invalid();
}

EffectPass* TechniqueImpl::GetPassByIndex(UINT Index) {
  return Index < passes_.size() ? &passes_[Index] : static_cast<EffectPass*>(InvalidPass());
}

EffectPass* TechniqueImpl::GetPassByName(LPCSTR Name) {
  for (PassImpl& p : passes_)
    if (Name && p.ast_->name == Name) return &p;
  return InvalidPass();
}

}  // namespace detail

HRESULT CreateEffectFromFile(const char* pFileName, const EFFECT_OPTIONS& options, rhi::Device* pDevice,
                             Effect** ppEffect) {
  if (!pFileName) return rhi::E_INVALIDARG;
  return detail::Guarded(options, pDevice, ppEffect,
                         [&] { return ParseEffectFile(pFileName, detail::ToParseOptions(options)); });
}

HRESULT CreateEffectFromFile(const wchar_t* pFileName, const EFFECT_OPTIONS& options, rhi::Device* pDevice,
                             Effect** ppEffect) {
  if (!pFileName) return rhi::E_INVALIDARG;
  return CreateEffectFromFile(rhi::WidePathToUtf8(pFileName).c_str(), options, pDevice, ppEffect);
}

HRESULT CreateEffectFromFile(const std::filesystem::path& fileName, const EFFECT_OPTIONS& options,
                             rhi::Device* pDevice, Effect** ppEffect) {
  return CreateEffectFromFile(fileName.c_str(), options, pDevice, ppEffect);
}

HRESULT CreateEffectFromMemory(const void* pData, SIZE_T DataLength, const char* pSourceName,
                               const std::filesystem::path& includeFolder, UINT FXFlags, rhi::Device* pDevice,
                               Effect** ppEffect, std::string* pErrors) {
  const char* name = pSourceName ? pSourceName : "<memory>";
  std::string errors;
  HRESULT hr = rhi::S_OK;
  if (FXFlags & COMPILE_EFFECT_CHILD_EFFECT) {
    errors = std::string(name) + ": error: effect pools (COMPILE_EFFECT_CHILD_EFFECT) are not supported, as in FX11\n";
    hr = rhi::E_NOTIMPL;
  } else if (FXFlags & ~(COMPILE_EFFECT_CHILD_EFFECT | COMPILE_EFFECT_ALLOW_SLOW_OPS)) {
    errors = std::string(name) + ": error: unknown FXFlags bits 0x" +
             detail::ToHex(FXFlags & ~(COMPILE_EFFECT_CHILD_EFFECT | COMPILE_EFFECT_ALLOW_SLOW_OPS)) +
             " (only COMPILE_EFFECT_* flags are effect flags)\n";
    hr = rhi::E_INVALIDARG;
  } else {
    EFFECT_OPTIONS options;
    if (!includeFolder.empty()) options.IncludeDirs.push_back(includeFolder.string());
    options.Errors = &errors;
    hr = CreateEffectFromMemory(pData, DataLength, name, options, pDevice, ppEffect);
  }
  if (rhi::FAILED(hr) && ppEffect) *ppEffect = nullptr;
  if (pErrors) {
    *pErrors = errors;
  } else if (!errors.empty()) {
    std::fputs(errors.c_str(), stderr);
  }
  return hr;
}

HRESULT CreateEffectFromMemory(const void* pData, SIZE_T DataLength, const char* pVirtualFileName,
                               const EFFECT_OPTIONS& options, rhi::Device* pDevice, Effect** ppEffect) {
  if (!pData && DataLength) return rhi::E_INVALIDARG;
  std::string source(static_cast<const char*>(pData), DataLength);
  std::string name = pVirtualFileName ? pVirtualFileName : "<memory>";
  return detail::Guarded(options, pDevice, ppEffect,
                         [&] { return ParseEffect(source, name, detail::ToParseOptions(options)); });
}

}  // namespace fx
