// RebaseInstanceIndex: see patches.h.
#include <vector>

#include "spirv/module_editor.h"
#include "spirv/patches.h"

namespace rhi::spirv {
namespace {

// The global Input variable decorated BuiltIn `builtIn`, or 0.
uint32_t FindBuiltInInput(const Module& module, Editor& editor, spv::BuiltIn builtIn) {
  for (const Instruction& inst : module) {
    if (OpOf(inst) == spv::Op::OpFunction) break;
    if (OpOf(inst) != spv::Op::OpVariable || static_cast<spv::StorageClass>(inst.operand(2)) != spv::StorageClass::Input)
      continue;
    if (editor.DecorationValue(inst.resultId(), spv::Decoration::BuiltIn) == static_cast<uint32_t>(builtIn))
      return inst.resultId();
  }
  return 0;
}

bool IsLoadOf(const Instruction& inst, uint32_t variable) {
  return OpOf(inst) == spv::Op::OpLoad && inst.operand(2) == variable;
}

// Uses other than OpLoad would bypass the rebase; glslang never emits them
// for a scalar built-in, so refuse rather than patch half of them.
bool HasOtherPointerUses(const Module& module, uint32_t variable) {
  return module.Find([variable](const Instruction& inst) {
           switch (OpOf(inst)) {
             case spv::Op::OpCopyMemory: return inst.operand(1) == variable;
             case spv::Op::OpCopyObject:
             case spv::Op::OpAccessChain:
             case spv::Op::OpInBoundsAccessChain: return inst.operand(2) == variable;
             case spv::Op::OpFunctionCall:
               for (size_t i = 3; i < inst.operandCount(); ++i)
                 if (inst.operand(i) == variable) return true;
               return false;
             default: return false;
           }
         }) != Module::npos;
}

uint32_t AddBaseInstance(Editor& editor, uint32_t pointerType) {
  const uint32_t var = editor.AddGlobalVariable(pointerType, spv::StorageClass::Input);
  editor.Decorate(var, spv::Decoration::BuiltIn, {static_cast<uint32_t>(spv::BuiltIn::BaseInstance)});
  editor.AddName(var, "gl_BaseInstance");
  editor.AddToInterface(var);
  return var;
}

}  // namespace

WordsResult RebaseInstanceIndex(std::span<const uint32_t> words) {
  Result<Module> parsed = Module::Parse(words);
  if (!parsed) return WordsResult::Failure(parsed.error);
  Module& module = parsed.value;
  Editor editor(module);

  const uint32_t instanceIndex = FindBuiltInInput(module, editor, spv::BuiltIn::InstanceIndex);
  if (!instanceIndex || module.Find([&](const Instruction& i) { return IsLoadOf(i, instanceIndex); }) == Module::npos)
    return WordsResult::Success(std::vector<uint32_t>(words.begin(), words.end()));
  if (HasOtherPointerUses(module, instanceIndex))
    return WordsResult::Failure("RebaseInstanceIndex: InstanceIndex is used other than by OpLoad");

  // Declarations first: they shift the function instructions patched below.
  uint32_t baseInstance = FindBuiltInInput(module, editor, spv::BuiltIn::BaseInstance);
  if (!baseInstance) baseInstance = AddBaseInstance(editor, module.Definition(instanceIndex)->resultType());
  editor.AddCapability(spv::Capability::DrawParameters);
  if (module.version() < 0x00010300) editor.AddExtension("SPV_KHR_shader_draw_parameters");

  // %r = OpLoad %t %InstanceIndex  becomes
  // %a = OpLoad %t %InstanceIndex; %b = OpLoad %t %BaseInstance; %r = OpISub %t %a %b
  // so every user of %r sees the rebased value without being rewritten.
  for (size_t at = 0; at < module.size(); ++at) {
    if (!IsLoadOf(module[at], instanceIndex)) continue;
    const uint32_t type = module[at].resultType(), result = module[at].resultId();
    const uint32_t raw = module.NewId(), base = module.NewId();
    module[at].setOperand(1, raw);  // keeps any memory-access operands
    at = module.Insert(at + 1, {MakeInstruction(spv::Op::OpLoad, {type, base, baseInstance}),
                                MakeInstruction(spv::Op::OpISub, {type, result, raw, base})}) - 1;
  }
  return WordsResult::Success(module.Assemble());
}

}  // namespace rhi::spirv
