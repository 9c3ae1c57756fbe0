// Where the renderer's effect files are, and loading them with defines: the
// effects of transparency methods and of translucent objects (renderer/oit).
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "fx/effect.h"
#include "renderer/oit/method.h"
#include "rhi/rhi.h"

namespace renderer {

using EffectDefines = std::vector<std::pair<std::string, std::string>>;

// The project's effect folder (fx::ShaderDirectory: found beside the executable or the
// install prefix, or $D3D11VK_SHADER_DIR), the include directory of every effect.
const std::string& ShaderDirectory();

// shaders_hlsl/<file> with `defines`; null on failure, with `error` naming the
// file and the compiler's file:line:column message.
rhi::ComPtr<fx::Effect> LoadEffect(rhi::Device* device, const std::string& file, const EffectDefines& defines,
                                   std::string* error);

// The pass `pass` of the technique `technique` (null: the effect's first technique);
// null with `error` set when there is none.
fx::EffectPass* FindPass(fx::Effect* effect, const char* technique, const char* pass, std::string* error);

namespace oit {

// An object's effect for a method: shaders_hlsl/<objectFile> built with
// OIT_METHOD="<method.include>" (and `defines`); with objectFile null, the
// method's own passes (shaders_hlsl/oit/method.fx). Its first technique is the method's.
rhi::ComPtr<fx::Effect> LoadMethodEffect(rhi::Device* device, const MethodInfo& method, const char* objectFile,
                                         EffectDefines defines, std::string* error);

}  // namespace oit
}  // namespace renderer
