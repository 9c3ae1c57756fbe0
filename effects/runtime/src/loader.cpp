// AST -> compiled shaders -> RHI objects. Each step appends errors in the
// "file:line:column: error: message" form and the load fails if any step did.
#include <cstdio>
#include <map>

#include "effect_impl.h"
#include "fx/gs_isolation.h"
#include "variables.h"

namespace fx::detail {
namespace {

std::string At(const SourceLocation& where) {
  return where.file + ":" + std::to_string(where.line) + ":" + std::to_string(where.column) + ": error: ";
}

std::string Hex(rhi::HRESULT hr) {
  char text[16];
  std::snprintf(text, sizeof text, "0x%08X", static_cast<unsigned>(hr));
  return text;
}

// Compiler errors keep glslang's positions (the AST's hlsl carries #line);
// those without one (link errors, a missing entry point) get the CompileShader's.
void AddCompileErrors(const CompiledShader& shader, const hlsl::CompileResult& result,
                      std::vector<std::string>& errors) {
  for (const hlsl::Diagnostic& d : result.errors) {
    if (d.line > 0)
      errors.push_back(d.file + ":" + std::to_string(d.line) + ":" + std::to_string(d.column) + ": error: " +
                       d.message);
    else
      errors.push_back(At(shader.where) + shader.profile + " " + shader.function + ": " + d.message);
  }
  if (result.errors.empty()) errors.push_back(At(shader.where) + "compiling " + shader.function + " failed");
}

class Loader {
 public:
  Loader(EffectImpl& effect, const EFFECT_OPTIONS& options, std::vector<std::string>& errors)
      : e_(effect), options_(options), errors_(errors),
        cache_(options.CacheDirectory ? *options.CacheDirectory : ShaderCache::DefaultDirectory()) {
    for (const auto& [name, value] : options.Defines) defines_.push_back({name, value});
  }

  bool Run() {
    CompileShaders();
    if (!errors_.empty()) return false;
    CreateShaderObjects();
    CreateStateObjects();
    BuildConstantBuffers();
    ResolveBindings();
    BuildTechniques();
    BuildVariables(e_);
    return errors_.empty();
  }

 private:
  // One compile per distinct (entry point, profile): the variants of a
  // ConstructGSWithSO over one function share their SPIR-V.
  void CompileShaders() {
    std::map<std::pair<std::string, std::string>, std::shared_ptr<const CompiledCode>> compiled;
    e_.shaders.resize(e_.ast.shaders.size());
    for (size_t i = 0; i < e_.ast.shaders.size(); ++i) {
      const CompiledShader& s = e_.ast.shaders[i];
      e_.shaders[i].ast = &s;
      auto& code = compiled[{s.entryPoint, s.profile}];
      if (!code) code = Compile(s);
      e_.shaders[i].code = code;
    }
  }

  std::shared_ptr<const CompiledCode> Compile(const CompiledShader& s) {
    const std::string source = IsolateGeometryShader(e_.ast.hlsl, {s.entryPoint, s.function});
    const std::string key = ShaderCacheKey(source, s.entryPoint, s.profile, defines_);
    if (auto cached = cache_.Load(key)) {
      ++e_.stats.ShadersFromCache;
      return std::make_shared<const CompiledCode>(std::move(*cached));
    }
    hlsl::CompileRequest request{source, s.where.file, s.entryPoint, s.profile, defines_, options_.IncludeDirs};
    hlsl::CompileResult result = hlsl::CompileHlsl(request);
    ++e_.stats.ShadersCompiled;
    if (!result.ok) {
      AddCompileErrors(s, result, errors_);
      return nullptr;
    }
    auto code = std::make_shared<CompiledCode>(
        CompiledCode{std::move(result.spirv), std::move(result.constantBuffers), std::move(result.resources)});
    cache_.Store(key, *code);
    return code;
  }

  void CreateShaderObjects() {
    for (ShaderState& s : e_.shaders) {
      const auto& spirv = s.code->spirv;
      const void* bytes = spirv.data();
      const SIZE_T size = spirv.size() * 4;
      rhi::Device* d = e_.device.Get();
      rhi::HRESULT hr = rhi::S_OK;
      switch (s.ast->stage) {
        case ShaderStage::Vertex: hr = d->CreateVertexShader(bytes, size, nullptr, s.vs.GetAddressOf()); break;
        case ShaderStage::Hull: hr = d->CreateHullShader(bytes, size, nullptr, s.hs.GetAddressOf()); break;
        case ShaderStage::Domain: hr = d->CreateDomainShader(bytes, size, nullptr, s.ds.GetAddressOf()); break;
        case ShaderStage::Geometry:
          if (!s.ast->hasStreamOutput) hr = d->CreateGeometryShader(bytes, size, nullptr, s.gs.GetAddressOf());
          break;
        case ShaderStage::Pixel: hr = d->CreatePixelShader(bytes, size, nullptr, s.ps.GetAddressOf()); break;
        case ShaderStage::Compute: hr = d->CreateComputeShader(bytes, size, nullptr, s.cs.GetAddressOf()); break;
      }
      if (rhi::FAILED(hr))
        errors_.push_back(At(s.ast->where) + "creating the " + s.ast->profile + " shader " + s.ast->function +
                          " failed (" + Hex(hr) + ")");
      if (s.ast->hasStreamOutput) CreateStreamOutput(s);
    }
  }

  // ConstructGSWithSO, over a geometry shader or (VS-only stream output) a vertex shader.
  void CreateStreamOutput(ShaderState& s) {
    const auto& entries = s.ast->streamOutput.Entries();
    const auto strides = s.ast->streamOutput.Strides();
    UINT numStrides = 0;
    for (UINT i = 0; i < strides.size(); ++i)
      if (strides[i]) numStrides = i + 1;
    rhi::HRESULT hr = e_.device->CreateGeometryShaderWithStreamOutput(
        s.code->spirv.data(), s.code->spirv.size() * 4, entries.data(), static_cast<UINT>(entries.size()),
        strides.data(), numStrides, s.ast->rasterizedStream, nullptr, s.gs.GetAddressOf());
    if (rhi::FAILED(hr)) {
      std::string decls;
      for (const std::string& d : s.ast->soDeclarations)
        if (!d.empty()) decls += (decls.empty() ? "\"" : ", \"") + d + "\"";
      // The RHI gives its reason to the device's OnMessage callback only.
      errors_.push_back(At(s.ast->where) + "CreateGeometryShaderWithStreamOutput refused the stream-output "
                        "declaration " + decls + " of " + s.ast->function + " (" + Hex(hr) +
                        "; the reason went to the device's message callback)");
    }
  }

  template <class Var, class Object, class Create>
  void CreateStates(const std::vector<Var>& vars, std::vector<ObjectSlots<Object>>& slots, const char* what,
                    Create create) {
    slots.resize(vars.size());
    for (size_t v = 0; v < vars.size(); ++v) {
      slots[v].own.resize(vars[v].descs.size());
      for (size_t i = 0; i < vars[v].descs.size(); ++i)
        if (rhi::FAILED(create(&vars[v].descs[i], slots[v].own[i].GetAddressOf())))
          errors_.push_back(At(vars[v].where) + what + " refused the desc of '" + vars[v].name + "'");
    }
  }

  void CreateStateObjects() {
    rhi::Device* d = e_.device.Get();
    CreateStates(e_.ast.blendStates, e_.blendStates, "CreateBlendState",
                 [d](auto* desc, auto** out) { return d->CreateBlendState(desc, out); });
    CreateStates(e_.ast.depthStencilStates, e_.depthStates, "CreateDepthStencilState",
                 [d](auto* desc, auto** out) { return d->CreateDepthStencilState(desc, out); });
    CreateStates(e_.ast.rasterizerStates, e_.rasterStates, "CreateRasterizerState",
                 [d](auto* desc, auto** out) { return d->CreateRasterizerState(desc, out); });
    CreateStates(e_.ast.samplers, e_.samplers, "CreateSamplerState",
                 [d](auto* desc, auto** out) { return d->CreateSamplerState(desc, out); });
    e_.srvs.resize(e_.ast.resources.size());
    e_.uavs.resize(e_.ast.resources.size());
  }

  void BuildConstantBuffers() {
    e_.cbuffers.resize(e_.ast.cbuffers.size());
    for (size_t i = 0; i < e_.ast.cbuffers.size(); ++i) {
      e_.cbuffers[i].ast = &e_.ast.cbuffers[i];
      e_.cbuffers[i].data = e_.ast.cbuffers[i].defaults;
      e_.cbuffers[i].data.resize(e_.ast.cbuffers[i].size);
    }
  }

  // The layout of `compiled` in cbuffer `cb`: an existing one when a shader
  // before agreed on it, else a new buffer holding the defaults already.
  int LayoutFor(int cb, const hlsl::ConstantBufferInfo& compiled) {
    CBufferState& state = e_.cbuffers[cb];
    for (size_t l = 0; l < state.layouts.size(); ++l)
      if (state.layouts[l].compiled.members == compiled.members && state.layouts[l].compiled.size == compiled.size)
        return static_cast<int>(l);
    GpuLayout layout{compiled, BuildCopyPlan(*state.ast, compiled), nullptr, state.version};
    std::vector<uint8_t> initial(std::max<uint32_t>(compiled.size, 16));
    ApplyCopyPlan(layout.plan, state.data, initial);
    rhi::BUFFER_DESC desc{static_cast<UINT>(initial.size()), rhi::USAGE_DEFAULT, rhi::BIND_CONSTANT_BUFFER, 0, 0, 0};
    rhi::SUBRESOURCE_DATA data{initial.data(), 0, 0};
    if (rhi::FAILED(e_.device->CreateBuffer(&desc, &data, layout.buffer.GetAddressOf())))
      errors_.push_back(At(state.ast->where) + "creating constant buffer '" + state.ast->name + "' failed");
    state.layouts.push_back(std::move(layout));
    return static_cast<int>(state.layouts.size() - 1);
  }

  template <class T>
  static int IndexOf(const std::vector<T>& items, const std::string& name) {
    for (size_t i = 0; i < items.size(); ++i)
      if (items[i].name == name) return static_cast<int>(i);
    return -1;
  }

  void ResolveBindings() {
    using RC = rhi::RegisterClass;
    using K = hlsl::ResourceInfo::Kind;
    for (ShaderState& s : e_.shaders) {
      for (const hlsl::ConstantBufferInfo& cb : s.code->constantBuffers) {
        int index = IndexOf(e_.ast.cbuffers, cb.name);
        if (index >= 0) s.bindings.push_back({RC::ConstantBuffer, cb.registerSlot, 1, index, LayoutFor(index, cb)});
      }
      for (const hlsl::ResourceInfo& r : s.code->resources) {
        if (r.isCounter) continue;  // glslang's hidden Append/Consume counters: not bound (see README of this module)
        const bool uav = r.kind == K::RWTexture || r.kind == K::RWBuffer || r.kind == K::RWStructuredBuffer ||
                         r.kind == K::RWByteAddressBuffer;
        if (r.kind == K::Sampler) {
          int index = IndexOf(e_.ast.samplers, r.name);
          if (index >= 0) s.bindings.push_back({RC::Sampler, r.registerSlot, r.bindCount, index, -1});
        } else {
          int index = IndexOf(e_.ast.resources, r.name);
          if (index >= 0)
            s.bindings.push_back({uav ? RC::UnorderedAccess : RC::ShaderResource, r.registerSlot, r.bindCount, index, -1});
          if (uav) CheckUavRegister(s, r);
        }
      }
    }
  }

  // What Apply cannot bind is an error here rather than a UAV silently left
  // unbound: D3D11 (feature level 11_0) gives UAVs to pixel and compute
  // shaders only, in registers u0..u7.
  void CheckUavRegister(const ShaderState& s, const hlsl::ResourceInfo& r) {
    const std::string shader = At(s.ast->where) + s.ast->profile + " " + s.ast->function + ": UAV '" + r.name + "' (u" +
                               std::to_string(r.registerSlot) + ")";
    if (s.ast->stage != ShaderStage::Pixel && s.ast->stage != ShaderStage::Compute)
      errors_.push_back(shader + " cannot be bound: D3D11 binds UAVs to pixel and compute shaders only");
    else if (r.registerSlot + std::max(r.bindCount, 1u) > rhi::PS_CS_UAV_REGISTER_COUNT)
      errors_.push_back(shader + " lies beyond u" + std::to_string(rhi::PS_CS_UAV_REGISTER_COUNT - 1) +
                        ", the last UAV register of feature level 11_0");
  }

  PassAction Resolve(const PassAssignment& a) {
    PassAction action;
    auto stateIndex = [&](const auto& vars, const ObjectRef& ref) {
      if (ref.variable.empty()) return -1;
      int index = IndexOf(vars, ref.variable);
      if (index < 0) errors_.push_back(At(a.where) + "unknown state object '" + ref.variable + "'");
      return index;
    };
    if (auto* s = std::get_if<ShaderAssignment>(&a.value)) {
      action.kind = PassAction::Kind::Shader;
      action.stage = s->stage;
      action.index = s->shader;
    } else if (auto* b = std::get_if<BlendStateAssignment>(&a.value)) {
      action.kind = PassAction::Kind::Blend;
      action.index = stateIndex(e_.ast.blendStates, b->state);
      action.element = b->state.element;
      action.blendFactor = b->blendFactor;
      action.sampleMask = b->sampleMask;
    } else if (auto* d = std::get_if<DepthStencilStateAssignment>(&a.value)) {
      action.kind = PassAction::Kind::DepthStencil;
      action.index = stateIndex(e_.ast.depthStencilStates, d->state);
      action.element = d->state.element;
      action.stencilRef = d->stencilRef;
    } else if (auto* r = std::get_if<RasterizerStateAssignment>(&a.value)) {
      action.kind = PassAction::Kind::Rasterizer;
      action.index = stateIndex(e_.ast.rasterizerStates, r->state);
      action.element = r->state.element;
    }
    return action;
  }

  void BuildTechniques() {
    e_.techniques.resize(e_.ast.techniques.size());
    for (size_t t = 0; t < e_.ast.techniques.size(); ++t) {
      TechniqueImpl& technique = e_.techniques[t];
      technique.effect_ = &e_;
      technique.ast_ = &e_.ast.techniques[t];
      technique.passes_.resize(technique.ast_->passes.size());
      for (size_t p = 0; p < technique.passes_.size(); ++p) {
        PassImpl& pass = technique.passes_[p];
        pass.effect_ = &e_;
        pass.ast_ = &technique.ast_->passes[p];
        pass.marker_ = technique.ast_->name + "/" + pass.ast_->name;
        for (const PassAssignment& a : pass.ast_->assignments) pass.actions_.push_back(Resolve(a));
      }
    }
  }

  EffectImpl& e_;
  const EFFECT_OPTIONS& options_;
  std::vector<std::string>& errors_;
  ShaderCache cache_;
  std::vector<hlsl::Define> defines_;
};

}  // namespace

bool LoadEffect(EffectImpl& effect, const EFFECT_OPTIONS& options, std::vector<std::string>& errors) {
  return Loader(effect, options, errors).Run();
}

}  // namespace fx::detail
