// SPIRV-Tools wrappers and SPIR-V queries shared by the spirv tests.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "spirv/spirv_module.h"

namespace spirv_test {

// "" when `words` passes spirv-val for Vulkan 1.3, else the validator's messages.
std::string ValidationErrors(const std::vector<uint32_t>& words);
std::string Disassemble(const std::vector<uint32_t>& words);
// Assembles SPIR-V text (spirv-as syntax, SPIR-V 1.5); ADD_FAILUREs on errors.
std::vector<uint32_t> Assemble(const std::string& text);
// SPIRV-Tools' legalization recipe, as the product compiler runs it.
std::vector<uint32_t> Legalize(const std::vector<uint32_t>& words);

// Instructions of `words` with this opcode (spv::Op value).
std::vector<rhi::spirv::Instruction> InstructionsWithOpcode(const std::vector<uint32_t>& words, uint32_t opcode);
size_t CountOpcode(const std::vector<uint32_t>& words, uint32_t opcode);
// First literal of OpDecorate `target` `decoration` (spv::Decoration value).
std::optional<uint32_t> DecorationOf(const std::vector<uint32_t>& words, uint32_t target, uint32_t decoration);
// The global variable with this OpName, or 0.
uint32_t VariableNamed(const std::vector<uint32_t>& words, const std::string& name);

}  // namespace spirv_test

// Asserts that a module validates, printing the validator's output and the disassembly otherwise.
#define EXPECT_VALID_SPIRV(words)                                                         \
  do {                                                                                    \
    const std::string spirvErrors_ = ::spirv_test::ValidationErrors(words);               \
    EXPECT_EQ(spirvErrors_, "") << ::spirv_test::Disassemble(words);                      \
  } while (0)
