#include "test_util.h"

#include <gtest/gtest.h>

#include <spirv-tools/libspirv.hpp>
#include <spirv-tools/optimizer.hpp>
#include <spirv/unified1/spirv.hpp11>

namespace spirv_test {
namespace {

spvtools::MessageConsumer CollectInto(std::string& sink) {
  return [&sink](spv_message_level_t level, const char*, const spv_position_t&, const char* message) {
    if (level > SPV_MSG_ERROR) return;
    sink += message;
    sink += "\n";
  };
}

rhi::spirv::Module Parse(const std::vector<uint32_t>& words) {
  auto parsed = rhi::spirv::Module::Parse(words);
  EXPECT_TRUE(parsed.ok()) << parsed.error;
  return std::move(parsed.value);
}

}  // namespace

std::string ValidationErrors(const std::vector<uint32_t>& words) {
  if (words.empty()) return "empty module";
  std::string errors;
  spvtools::SpirvTools tools(SPV_ENV_VULKAN_1_3);
  tools.SetMessageConsumer(CollectInto(errors));
  if (tools.Validate(words)) return "";
  return errors.empty() ? "invalid" : errors;
}

std::string Disassemble(const std::vector<uint32_t>& words) {
  std::string text;
  spvtools::SpirvTools tools(SPV_ENV_VULKAN_1_3);
  tools.Disassemble(words, &text, SPV_BINARY_TO_TEXT_OPTION_FRIENDLY_NAMES | SPV_BINARY_TO_TEXT_OPTION_INDENT);
  return text;
}

std::vector<uint32_t> Assemble(const std::string& text) {
  std::string errors;
  spvtools::SpirvTools tools(SPV_ENV_UNIVERSAL_1_5);
  tools.SetMessageConsumer(CollectInto(errors));
  std::vector<uint32_t> words;
  if (!tools.Assemble(text, &words)) ADD_FAILURE() << "assembly failed: " << errors;
  return words;
}

std::vector<uint32_t> Legalize(const std::vector<uint32_t>& words) {
  std::string errors;
  spvtools::Optimizer optimizer(SPV_ENV_VULKAN_1_3);
  optimizer.SetMessageConsumer(CollectInto(errors));
  optimizer.RegisterLegalizationPasses();
  spvtools::OptimizerOptions options;
  options.set_run_validator(false);
  std::vector<uint32_t> legal;
  if (!optimizer.Run(words.data(), words.size(), &legal, options)) ADD_FAILURE() << "legalization failed: " << errors;
  return legal;
}

std::vector<rhi::spirv::Instruction> InstructionsWithOpcode(const std::vector<uint32_t>& words, uint32_t opcode) {
  std::vector<rhi::spirv::Instruction> found;
  for (const auto& inst : Parse(words))
    if (inst.opcode() == opcode) found.push_back(inst);
  return found;
}

size_t CountOpcode(const std::vector<uint32_t>& words, uint32_t opcode) {
  return InstructionsWithOpcode(words, opcode).size();
}

std::optional<uint32_t> DecorationOf(const std::vector<uint32_t>& words, uint32_t target, uint32_t decoration) {
  for (const auto& inst : InstructionsWithOpcode(words, static_cast<uint32_t>(spv::Op::OpDecorate)))
    if (inst.operand(0) == target && inst.operand(1) == decoration && inst.operandCount() > 2) return inst.operand(2);
  return std::nullopt;
}

uint32_t VariableNamed(const std::vector<uint32_t>& words, const std::string& name) {
  const rhi::spirv::Module module = Parse(words);
  for (const auto& inst : module) {
    if (inst.opcode() != static_cast<uint32_t>(spv::Op::OpName) || inst.stringAt(1) != name) continue;
    const auto* def = module.Definition(inst.operand(0));
    if (def && def->opcode() == static_cast<uint32_t>(spv::Op::OpVariable)) return def->resultId();
  }
  return 0;
}

}  // namespace spirv_test
