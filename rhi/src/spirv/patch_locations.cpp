// RemapLocations: see patches.h.
#include <set>

#include "spirv/module_editor.h"
#include "spirv/patches.h"

namespace rhi::spirv {
namespace {

// The struct type of an IO block variable (through one level of per-vertex array), or 0.
uint32_t BlockType(const Module& module, const Instruction& var) {
  const Instruction* pointer = module.Definition(var.resultType());
  const Instruction* type = pointer ? module.Definition(pointer->operand(2)) : nullptr;
  if (type && OpOf(*type) == spv::Op::OpTypeArray) type = module.Definition(type->operand(1));
  return type && OpOf(*type) == spv::Op::OpTypeStruct ? type->resultId() : 0;
}

// Variables of `storage`, and the block types only variables of `storage` use.
struct Targets {
  std::set<uint32_t> variables;
  std::set<uint32_t> blockTypes;
};

Targets FindTargets(const Module& module, spv::StorageClass storage) {
  Targets targets;
  std::set<uint32_t> otherBlocks;
  for (const Instruction& inst : module) {
    if (OpOf(inst) == spv::Op::OpFunction) break;
    if (OpOf(inst) != spv::Op::OpVariable) continue;
    const bool match = static_cast<spv::StorageClass>(inst.operand(2)) == storage;
    if (match) targets.variables.insert(inst.resultId());
    if (const uint32_t block = BlockType(module, inst)) (match ? targets.blockTypes : otherBlocks).insert(block);
  }
  for (uint32_t block : otherBlocks) targets.blockTypes.erase(block);
  return targets;
}

void Remap(Instruction& inst, size_t valueOperand, const std::map<uint32_t, uint32_t>& oldToNew) {
  const auto it = oldToNew.find(inst.operand(valueOperand));
  if (it != oldToNew.end()) inst.setOperand(valueOperand, it->second);
}

}  // namespace

WordsResult RemapLocations(std::span<const uint32_t> words, StorageClass storage,
                           const std::map<uint32_t, uint32_t>& oldToNew) {
  Result<Module> parsed = Module::Parse(words);
  if (!parsed) return WordsResult::Failure(parsed.error);
  Module& module = parsed.value;
  const Targets targets = FindTargets(module, static_cast<spv::StorageClass>(storage));
  constexpr auto kLocation = static_cast<uint32_t>(spv::Decoration::Location);

  // Rewrite in place; every location is looked up in the original map, so
  // swaps (0->1, 1->0) work.
  for (Instruction& inst : module) {
    if (OpOf(inst) == spv::Op::OpFunction) break;
    if (OpOf(inst) == spv::Op::OpDecorate && inst.operandCount() >= 3 && inst.operand(1) == kLocation &&
        targets.variables.count(inst.operand(0)))
      Remap(inst, 2, oldToNew);
    if (OpOf(inst) == spv::Op::OpMemberDecorate && inst.operandCount() >= 4 && inst.operand(2) == kLocation &&
        targets.blockTypes.count(inst.operand(0)))
      Remap(inst, 3, oldToNew);
  }
  return WordsResult::Success(module.Assemble());
}

}  // namespace rhi::spirv
