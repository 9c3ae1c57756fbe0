#include "spirv/spirv_module.h"

#include <algorithm>

#define SPV_ENABLE_UTILITY_CODE  // spv::HasResultAndType
#include <spirv/unified1/spirv.hpp11>

namespace rhi::spirv {

std::string DecodeString(std::span<const uint32_t> words, size_t* wordCount) {
  std::string text;
  size_t used = 0;
  for (uint32_t word : words) {
    ++used;
    for (int byte = 0; byte < 4; ++byte) {
      const char c = static_cast<char>((word >> (8 * byte)) & 0xffu);
      if (c == '\0') {
        if (wordCount) *wordCount = used;
        return text;
      }
      text += c;
    }
  }
  if (wordCount) *wordCount = used;  // unterminated: the literal ran to the end
  return text;
}

std::vector<uint32_t> EncodeString(std::string_view text) {
  // text.size() + 1 bytes (the nul), rounded up to whole words; byte i of the
  // string is byte (i % 4) of word i / 4, counted from the least significant.
  std::vector<uint32_t> words(text.size() / 4 + 1, 0u);
  for (size_t i = 0; i < text.size(); ++i)
    words[i / 4] |= static_cast<uint32_t>(static_cast<unsigned char>(text[i])) << (8 * (i % 4));
  return words;
}

Instruction::Instruction(uint32_t opcode, std::vector<uint32_t> operands) {
  words.reserve(operands.size() + 1);
  words.push_back((static_cast<uint32_t>(operands.size() + 1) << 16) | (opcode & 0xffffu));
  words.insert(words.end(), operands.begin(), operands.end());
}

void Instruction::appendOperand(uint32_t value) {
  words.push_back(value);
  words[0] = (static_cast<uint32_t>(words.size()) << 16) | opcode();
}

void Instruction::insertOperand(size_t i, uint32_t value) {
  words.insert(words.begin() + static_cast<std::ptrdiff_t>(1 + i), value);
  words[0] = (static_cast<uint32_t>(words.size()) << 16) | opcode();
}

std::string Instruction::stringAt(size_t i, size_t* next) const {
  size_t used = 0;
  std::string text = DecodeString(operands().subspan(std::min(i, operandCount())), &used);
  if (next) *next = i + used;
  return text;
}

uint32_t Instruction::resultId() const {
  bool hasResult = false, hasType = false;
  spv::HasResultAndType(static_cast<spv::Op>(opcode()), &hasResult, &hasType);
  const size_t at = hasType ? 1 : 0;
  return hasResult && operandCount() > at ? operand(at) : 0;
}

uint32_t Instruction::resultType() const {
  bool hasResult = false, hasType = false;
  spv::HasResultAndType(static_cast<spv::Op>(opcode()), &hasResult, &hasType);
  return hasType && operandCount() > 0 ? operand(0) : 0;
}

Result<Module> Module::Parse(std::span<const uint32_t> words) {
  if (words.size() < kHeaderWords) return Result<Module>::Failure("SPIR-V module shorter than its header");
  if (words[0] != kMagicNumber) return Result<Module>::Failure("not a SPIR-V module (bad magic number)");
  Module module;
  std::copy_n(words.begin(), kHeaderWords, module.header_);
  for (size_t at = kHeaderWords; at < words.size();) {
    const uint32_t count = words[at] >> 16;
    if (count == 0 || at + count > words.size())
      return Result<Module>::Failure("truncated SPIR-V instruction at word " + std::to_string(at));
    Instruction inst;
    inst.words.assign(words.begin() + static_cast<std::ptrdiff_t>(at),
                      words.begin() + static_cast<std::ptrdiff_t>(at + count));
    module.instructions_.push_back(std::move(inst));
    at += count;
  }
  return Result<Module>::Success(std::move(module));
}

std::vector<uint32_t> Module::Assemble() const {
  std::vector<uint32_t> words(std::begin(header_), std::end(header_));
  for (const Instruction& inst : instructions_) words.insert(words.end(), inst.words.begin(), inst.words.end());
  return words;
}

size_t Module::Find(const std::function<bool(const Instruction&)>& match, size_t from) const {
  for (size_t i = from; i < instructions_.size(); ++i)
    if (match(instructions_[i])) return i;
  return npos;
}

size_t Module::FindOpcode(uint32_t opcode, size_t from) const {
  return Find([opcode](const Instruction& inst) { return inst.opcode() == opcode; }, from);
}

size_t Module::FindDefinition(uint32_t id) const {
  if (id == 0) return npos;
  return Find([id](const Instruction& inst) { return inst.resultId() == id; });
}

const Instruction* Module::Definition(uint32_t id) const {
  const size_t at = FindDefinition(id);
  return at == npos ? nullptr : &instructions_[at];
}

size_t Module::Insert(size_t at, Instruction instruction) {
  instructions_.insert(instructions_.begin() + static_cast<std::ptrdiff_t>(at), std::move(instruction));
  return at + 1;
}

size_t Module::Insert(size_t at, std::vector<Instruction> instructions) {
  const size_t count = instructions.size();
  instructions_.insert(instructions_.begin() + static_cast<std::ptrdiff_t>(at),
                       std::make_move_iterator(instructions.begin()), std::make_move_iterator(instructions.end()));
  return at + count;
}

void Module::Remove(size_t at) { instructions_.erase(instructions_.begin() + static_cast<std::ptrdiff_t>(at)); }

size_t Module::RemoveIf(const std::function<bool(const Instruction&)>& match) {
  return static_cast<size_t>(std::erase_if(instructions_, match));
}

}  // namespace rhi::spirv
