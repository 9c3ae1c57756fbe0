// StripHlslDecorations: see patches.h.
#include <string>

#include "spirv/module_editor.h"
#include "spirv/patches.h"

namespace rhi::spirv {
namespace {

bool IsHlslDecoration(uint32_t decoration) {
  const auto d = static_cast<spv::Decoration>(decoration);
  return d == spv::Decoration::UserSemantic || d == spv::Decoration::UserTypeGOOGLE ||
         d == spv::Decoration::CounterBuffer;
}

// Where the decoration enum sits: OpDecorate* target, decoration; member forms target, member, decoration.
bool IsHlslAnnotation(const Instruction& inst) {
  switch (OpOf(inst)) {
    case spv::Op::OpDecorate:
    case spv::Op::OpDecorateId:
    case spv::Op::OpDecorateString: return inst.operandCount() > 1 && IsHlslDecoration(inst.operand(1));
    case spv::Op::OpMemberDecorate:
    case spv::Op::OpMemberDecorateString: return inst.operandCount() > 2 && IsHlslDecoration(inst.operand(2));
    default: return false;
  }
}

bool IsExtension(const Instruction& inst, std::string_view name) {
  return OpOf(inst) == spv::Op::OpExtension && inst.stringAt(0) == name;
}

}  // namespace

WordsResult StripHlslDecorations(std::span<const uint32_t> words) {
  Result<Module> parsed = Module::Parse(words);
  if (!parsed) return WordsResult::Failure(parsed.error);
  Module& module = parsed.value;

  module.RemoveIf(IsHlslAnnotation);
  module.RemoveIf([](const Instruction& inst) {
    return IsExtension(inst, "SPV_GOOGLE_hlsl_functionality1") || IsExtension(inst, "SPV_GOOGLE_user_type");
  });
  // OpDecorateString is core since SPIR-V 1.4; below that other users of it
  // still need the extension.
  const bool stringDecorationsLeft = module.Find([](const Instruction& inst) {
    return OpOf(inst) == spv::Op::OpDecorateString || OpOf(inst) == spv::Op::OpMemberDecorateString;
  }) != Module::npos;
  if (!stringDecorationsLeft)
    module.RemoveIf([](const Instruction& inst) { return IsExtension(inst, "SPV_GOOGLE_decorate_string"); });
  return WordsResult::Success(module.Assemble());
}

}  // namespace rhi::spirv
