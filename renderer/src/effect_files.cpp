#include "renderer/effect_files.h"

#include "fx/shader_directory.h"

namespace renderer {

const std::string& ShaderDirectory() { return fx::ShaderDirectory(); }

rhi::ComPtr<fx::Effect> LoadEffect(rhi::Device* device, const std::string& file, const EffectDefines& defines,
                                   std::string* error) {
  fx::EFFECT_OPTIONS options;
  options.IncludeDirs = {ShaderDirectory()};
  options.Defines = defines;
  std::string errors;
  options.Errors = &errors;
  rhi::ComPtr<fx::Effect> effect;
  if (rhi::FAILED(fx::CreateEffectFromFile((ShaderDirectory() + "/" + file).c_str(), options, device,
                                      effect.GetAddressOf()))) {
    *error = file + ": " + errors;
    return nullptr;
  }
  return effect;
}

fx::EffectPass* FindPass(fx::Effect* effect, const char* technique, const char* pass, std::string* error) {
  fx::EffectTechnique* t = technique ? effect->GetTechniqueByName(technique) : effect->GetTechniqueByIndex(0);
  fx::EffectPass* p = t->GetPassByName(pass);
  if (!p->IsValid()) {
    *error = std::string("no pass ") + (technique ? technique : "<first technique>") + "/" + pass;
    return nullptr;
  }
  return p;
}

namespace oit {

rhi::ComPtr<fx::Effect> LoadMethodEffect(rhi::Device* device, const MethodInfo& method, const char* objectFile,
                                         EffectDefines defines, std::string* error) {
  defines.emplace_back("OIT_METHOD", std::string("\"") + method.include + "\"");
  return LoadEffect(device, objectFile ? objectFile : "oit/method.fx", defines, error);
}

}  // namespace oit
}  // namespace renderer
