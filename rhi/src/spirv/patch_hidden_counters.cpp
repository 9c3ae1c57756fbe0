// MoveHiddenCounters: see patches.h.
#include <map>
#include <string>

#include "spirv/module_editor.h"
#include "spirv/patches.h"

namespace rhi::spirv {

WordsResult MoveHiddenCounters(std::span<const uint32_t> words, uint32_t bindingOffset) {
  Result<Module> parsed = Module::Parse(words);
  if (!parsed) return WordsResult::Failure(parsed.error);
  Module& module = parsed.value;
  Editor editor(module);
  // OpDecorateId %uav CounterBuffer %counter: the counter's new binding.
  std::map<uint32_t, uint32_t> counterBindings;
  for (const Instruction& inst : module) {
    if (OpOf(inst) != spv::Op::OpDecorateId || inst.operandCount() < 3 ||
        static_cast<spv::Decoration>(inst.operand(1)) != spv::Decoration::CounterBuffer)
      continue;
    const std::optional<uint32_t> uavBinding = editor.DecorationValue(inst.operand(0), spv::Decoration::Binding);
    if (!uavBinding) return WordsResult::Failure("a UAV with a hidden counter has no Binding decoration");
    counterBindings[inst.operand(2)] = *uavBinding + bindingOffset;
  }
  // glslang leaves a UAV that the shader uses only through its counter out of
  // the module, and the counter without its CounterBuffer link: the UAV's
  // register, and so the counter's binding, is unknown.
  for (const Instruction& inst : module) {
    if (OpOf(inst) != spv::Op::OpName) continue;
    const std::string name = inst.stringAt(1);
    const Instruction* named = module.Definition(inst.operand(0));
    if (name.ends_with("@count") && named && OpOf(*named) == spv::Op::OpVariable &&
        !counterBindings.contains(inst.operand(0)))
      return WordsResult::Failure("the hidden counter '" + name +
                                  "' is not linked to its UAV: glslang drops a UAV that the shader uses only through "
                                  "IncrementCounter/DecrementCounter; access the buffer itself too");
  }
  if (counterBindings.empty()) return WordsResult::Success({words.begin(), words.end()});
  for (Instruction& inst : module) {
    if (OpOf(inst) != spv::Op::OpDecorate || inst.operandCount() < 3 ||
        static_cast<spv::Decoration>(inst.operand(1)) != spv::Decoration::Binding)
      continue;
    if (const auto it = counterBindings.find(inst.operand(0)); it != counterBindings.end())
      inst.setOperand(2, it->second);
  }
  return WordsResult::Success(module.Assemble());
}

}  // namespace rhi::spirv
