#include "test_compiler.h"

#include <glslang/Public/ResourceLimits.h>
#include <glslang/Public/ShaderLang.h>
#include <glslang/SPIRV/GlslangToSpv.h>
#include <gtest/gtest.h>

#include <mutex>

namespace spirv_test {
namespace {

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

// glslang's process-wide tables must be created once, before any TShader.
void InitializeOnce() {
  static std::once_flag once;
  std::call_once(once, [] { glslang::InitializeProcess(); });
}

}  // namespace

std::vector<uint32_t> Compile(std::string_view source, Stage stage, std::string_view entry, Language language) {
  InitializeOnce();
  const EShLanguage lang = ToGlslang(stage);
  const bool hlsl = language == Language::Hlsl;
  const glslang::EShSource sourceKind = hlsl ? glslang::EShSourceHlsl : glslang::EShSourceGlsl;
  const std::string text(source);
  const std::string entryName(entry);
  const char* strings[] = {text.c_str()};

  glslang::TShader shader(lang);
  shader.setStrings(strings, 1);
  shader.setEnvInput(sourceKind, lang, glslang::EShClientVulkan, 100);
  shader.setEnvClient(glslang::EShClientVulkan, glslang::EShTargetVulkan_1_3);
  shader.setEnvTarget(glslang::EShTargetSpv, glslang::EShTargetSpv_1_5);
  if (hlsl) {
    shader.setEntryPoint(entryName.c_str());
    shader.setEnvTargetHlslFunctionality1();
    shader.setHlslIoMapping(true);
  }
  shader.setAutoMapLocations(true);
  shader.setAutoMapBindings(true);
  // glslang 12 keeps HLSL buffers in the Uniform+BufferBlock form, invalid in
  // SPIR-V 1.5, unless told (the product compiler does the same).
  shader.getIntermediate()->setUseStorageBuffer();

  auto messages = static_cast<EShMessages>(EShMsgSpvRules | EShMsgVulkanRules | (hlsl ? EShMsgReadHlsl | EShMsgHlslOffsets : 0));
  if (!shader.parse(GetDefaultResources(), hlsl ? 100 : 450, false, messages)) {
    ADD_FAILURE() << "parse failed:\n" << shader.getInfoLog();
    return {};
  }
  glslang::TProgram program;
  program.addShader(&shader);
  if (!program.link(messages) || !program.mapIO()) {
    ADD_FAILURE() << "link failed:\n" << program.getInfoLog();
    return {};
  }
  std::vector<uint32_t> words;
  glslang::SpvOptions options;
  options.validate = false;
  glslang::GlslangToSpv(*program.getIntermediate(lang), words, &options);
  return words;
}

}  // namespace spirv_test
