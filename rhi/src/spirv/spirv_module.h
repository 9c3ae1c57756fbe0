// A tiny SPIR-V word-stream reader/editor: the module is split into one word
// vector per instruction, so instructions can be iterated, inserted and
// removed by index, and put back together with Assemble(). It knows nothing
// about what the instructions mean beyond result ids; typed helpers for adding
// types, constants and decorations live in module_editor.h.
//
// Opcodes are plain uint32_t here (values of spv::Op): this public header does
// not include SPIRV-Headers' spirv.hpp11 because glslang ships its own
// spirv.hpp with the same include guard, and users may include both.
#pragma once

#include <cstdint>
#include <functional>
#include <initializer_list>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "spirv/result.h"

namespace rhi::spirv {

inline constexpr uint32_t kMagicNumber = 0x07230203;
inline constexpr size_t kHeaderWords = 5;  // magic, version, generator, id bound, schema

// Literal strings are nul-terminated UTF-8 packed little-endian into words.
// DecodeString stops at the first nul (or at the end of `words`) and reports
// how many words the literal occupied, nul padding included.
std::string DecodeString(std::span<const uint32_t> words, size_t* wordCount = nullptr);
std::vector<uint32_t> EncodeString(std::string_view text);

// One instruction. words[0] is (word count << 16) | opcode; the word count is
// kept up to date by the mutators below.
struct Instruction {
  std::vector<uint32_t> words;

  Instruction() = default;
  Instruction(uint32_t opcode, std::vector<uint32_t> operands);
  Instruction(uint32_t opcode, std::initializer_list<uint32_t> operands)
      : Instruction(opcode, std::vector<uint32_t>(operands)) {}

  uint32_t opcode() const { return words[0] & 0xffffu; }
  size_t operandCount() const { return words.size() - 1; }
  uint32_t operand(size_t i) const { return words.at(1 + i); }
  std::span<const uint32_t> operands() const { return std::span(words).subspan(1); }
  void setOperand(size_t i, uint32_t value) { words.at(1 + i) = value; }
  void appendOperand(uint32_t value);
  void insertOperand(size_t i, uint32_t value);
  // The literal string starting at operand i; *next gets the operand after it.
  std::string stringAt(size_t i, size_t* next = nullptr) const;

  // Result id and result type (0 when the opcode has none), from the grammar.
  uint32_t resultId() const;
  uint32_t resultType() const;

  bool operator==(const Instruction&) const = default;
};

class Module {
 public:
  // Splits the word stream; fails on a bad header or a truncated instruction.
  static Result<Module> Parse(std::span<const uint32_t> words);
  std::vector<uint32_t> Assemble() const;

  uint32_t version() const { return header_[1]; }  // 0x00MMmm00
  uint32_t bound() const { return header_[3]; }
  uint32_t NewId() { return header_[3]++; }  // fresh result id, raises the bound

  size_t size() const { return instructions_.size(); }
  Instruction& operator[](size_t i) { return instructions_[i]; }
  const Instruction& operator[](size_t i) const { return instructions_[i]; }
  auto begin() { return instructions_.begin(); }
  auto end() { return instructions_.end(); }
  auto begin() const { return instructions_.begin(); }
  auto end() const { return instructions_.end(); }

  static constexpr size_t npos = static_cast<size_t>(-1);
  // Index of the first instruction at or after `from` matching, or npos.
  size_t Find(const std::function<bool(const Instruction&)>& match, size_t from = 0) const;
  size_t FindOpcode(uint32_t opcode, size_t from = 0) const;
  // Index of the instruction whose result id is `id`, or npos (linear scan).
  size_t FindDefinition(uint32_t id) const;
  const Instruction* Definition(uint32_t id) const;

  // Insertion shifts later instructions up; returns the index after the last inserted.
  size_t Insert(size_t at, Instruction instruction);
  size_t Insert(size_t at, std::vector<Instruction> instructions);
  void Remove(size_t at);
  size_t RemoveIf(const std::function<bool(const Instruction&)>& match);  // returns how many

 private:
  uint32_t header_[kHeaderWords] = {};
  std::vector<Instruction> instructions_;
};

}  // namespace rhi::spirv
