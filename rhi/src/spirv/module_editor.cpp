#include "spirv/module_editor.h"

#include <algorithm>
#include <bit>

namespace rhi::spirv {

Section SectionOf(spv::Op op) {
  using spv::Op;
  switch (op) {
    case Op::OpCapability: return Section::Capability;
    case Op::OpExtension: return Section::Extension;
    case Op::OpExtInstImport: return Section::ExtInstImport;
    case Op::OpMemoryModel: return Section::MemoryModel;
    case Op::OpEntryPoint: return Section::EntryPoint;
    case Op::OpExecutionMode:
    case Op::OpExecutionModeId: return Section::ExecutionMode;
    case Op::OpString:
    case Op::OpSourceExtension:
    case Op::OpSource:
    case Op::OpSourceContinued: return Section::DebugSource;
    case Op::OpName:
    case Op::OpMemberName: return Section::DebugName;
    case Op::OpModuleProcessed: return Section::DebugModuleProcessed;
    case Op::OpDecorate:
    case Op::OpMemberDecorate:
    case Op::OpDecorationGroup:
    case Op::OpGroupDecorate:
    case Op::OpGroupMemberDecorate:
    case Op::OpDecorateId:
    case Op::OpDecorateString:
    case Op::OpMemberDecorateString: return Section::Annotation;
    case Op::OpFunction: return Section::Function;
    default: return Section::Global;
  }
}

size_t Editor::EndOf(Section section) const {
  // Sections appear in order, so the first instruction of a later section is
  // where this one ends. Everything from the first OpFunction on is Function.
  for (size_t i = 0; i < m_.size(); ++i) {
    const Section s = SectionOf(OpOf(m_[i]));
    if (s == Section::Function) return section == Section::Function ? m_.size() : i;
    if (s > section) return i;
  }
  return m_.size();
}

EntryPointInfo Editor::EntryPoint() const {
  EntryPointInfo info;
  info.index = m_.FindOpcode(static_cast<uint32_t>(spv::Op::OpEntryPoint));
  if (info.index == Module::npos) return info;
  const Instruction& inst = m_[info.index];
  if (inst.operandCount() < 3) return EntryPointInfo{};
  info.model = static_cast<spv::ExecutionModel>(inst.operand(0));
  info.function = inst.operand(1);
  info.name = inst.stringAt(2, &info.firstInterfaceOperand);
  return info;
}

std::vector<uint32_t> Editor::Interface(const EntryPointInfo& entry) const {
  if (entry.index == Module::npos) return {};
  const auto operands = m_[entry.index].operands();
  return {operands.begin() + static_cast<std::ptrdiff_t>(std::min(entry.firstInterfaceOperand, operands.size())),
          operands.end()};
}

void Editor::AddToInterface(uint32_t variable) {
  const EntryPointInfo entry = EntryPoint();
  if (entry.index == Module::npos) return;
  const std::vector<uint32_t> ids = Interface(entry);
  if (std::find(ids.begin(), ids.end(), variable) == ids.end()) m_[entry.index].appendOperand(variable);
}

bool Editor::HasCapability(spv::Capability capability) const {
  const uint32_t value = static_cast<uint32_t>(capability);
  return m_.Find([value](const Instruction& inst) {
           return OpOf(inst) == spv::Op::OpCapability && inst.operand(0) == value;
         }) != Module::npos;
}

void Editor::AddCapability(spv::Capability capability) {
  if (HasCapability(capability)) return;
  m_.Insert(EndOf(Section::Capability), MakeInstruction(spv::Op::OpCapability, {static_cast<uint32_t>(capability)}));
}

void Editor::AddExtension(std::string_view name) {
  const bool present = m_.Find([name](const Instruction& inst) {
                         return OpOf(inst) == spv::Op::OpExtension && inst.stringAt(0) == name;
                       }) != Module::npos;
  if (!present) m_.Insert(EndOf(Section::Extension), MakeInstruction(spv::Op::OpExtension, EncodeString(name)));
}

void Editor::AddExecutionMode(uint32_t function, spv::ExecutionMode mode, std::initializer_list<uint32_t> literals) {
  std::vector<uint32_t> operands{function, static_cast<uint32_t>(mode)};
  operands.insert(operands.end(), literals);
  m_.Insert(EndOf(Section::ExecutionMode), MakeInstruction(spv::Op::OpExecutionMode, std::move(operands)));
}

void Editor::AddName(uint32_t id, std::string_view name) {
  std::vector<uint32_t> operands{id};
  const std::vector<uint32_t> text = EncodeString(name);
  operands.insert(operands.end(), text.begin(), text.end());
  m_.Insert(EndOf(Section::DebugName), MakeInstruction(spv::Op::OpName, std::move(operands)));
}

void Editor::Decorate(uint32_t target, spv::Decoration decoration, std::initializer_list<uint32_t> literals) {
  std::vector<uint32_t> operands{target, static_cast<uint32_t>(decoration)};
  operands.insert(operands.end(), literals);
  m_.Insert(EndOf(Section::Annotation), MakeInstruction(spv::Op::OpDecorate, std::move(operands)));
}

void Editor::MemberDecorate(uint32_t structType, uint32_t member, spv::Decoration decoration,
                            std::initializer_list<uint32_t> literals) {
  std::vector<uint32_t> operands{structType, member, static_cast<uint32_t>(decoration)};
  operands.insert(operands.end(), literals);
  m_.Insert(EndOf(Section::Annotation), MakeInstruction(spv::Op::OpMemberDecorate, std::move(operands)));
}

std::optional<uint32_t> Editor::DecorationValue(uint32_t target, spv::Decoration decoration) const {
  for (const Instruction& inst : m_) {
    if (OpOf(inst) == spv::Op::OpFunction) break;
    if (OpOf(inst) == spv::Op::OpDecorate && inst.operandCount() >= 3 && inst.operand(0) == target &&
        inst.operand(1) == static_cast<uint32_t>(decoration))
      return inst.operand(2);
  }
  return std::nullopt;
}

bool Editor::HasFlagDecoration(uint32_t target, spv::Decoration decoration) const {
  for (const Instruction& inst : m_) {
    if (OpOf(inst) == spv::Op::OpFunction) break;
    if (OpOf(inst) == spv::Op::OpDecorate && inst.operandCount() >= 2 && inst.operand(0) == target &&
        inst.operand(1) == static_cast<uint32_t>(decoration))
      return true;
  }
  return false;
}

std::optional<uint32_t> Editor::MemberDecorationValue(uint32_t structType, uint32_t member,
                                                      spv::Decoration decoration) const {
  for (const Instruction& inst : m_) {
    if (OpOf(inst) == spv::Op::OpFunction) break;
    if (OpOf(inst) == spv::Op::OpMemberDecorate && inst.operandCount() >= 4 && inst.operand(0) == structType &&
        inst.operand(1) == member && inst.operand(2) == static_cast<uint32_t>(decoration))
      return inst.operand(3);
  }
  return std::nullopt;
}

uint32_t Editor::FindOrAddGlobal(spv::Op op, uint32_t resultType, std::vector<uint32_t> operands) {
  // Layout of the instruction: [result type] result-id operands...
  const size_t skip = resultType ? 2 : 1;
  for (const Instruction& inst : m_) {
    if (OpOf(inst) == spv::Op::OpFunction) break;
    if (OpOf(inst) != op || inst.resultType() != resultType || inst.operandCount() != skip + operands.size()) continue;
    if (std::equal(operands.begin(), operands.end(), inst.operands().begin() + static_cast<std::ptrdiff_t>(skip)))
      return inst.resultId();
  }
  const uint32_t id = m_.NewId();
  operands.insert(operands.begin(), id);
  if (resultType) operands.insert(operands.begin(), resultType);
  m_.Insert(EndOf(Section::Global), MakeInstruction(op, std::move(operands)));
  return id;
}

uint32_t Editor::TypeInt(uint32_t width, bool isSigned) {
  return FindOrAddGlobal(spv::Op::OpTypeInt, 0, {width, isSigned ? 1u : 0u});
}
uint32_t Editor::TypeFloat(uint32_t width) { return FindOrAddGlobal(spv::Op::OpTypeFloat, 0, {width}); }
uint32_t Editor::TypeVector(uint32_t componentType, uint32_t count) {
  return FindOrAddGlobal(spv::Op::OpTypeVector, 0, {componentType, count});
}
uint32_t Editor::TypePointer(spv::StorageClass storage, uint32_t pointee) {
  return FindOrAddGlobal(spv::Op::OpTypePointer, 0, {static_cast<uint32_t>(storage), pointee});
}
uint32_t Editor::ConstantU32(uint32_t value) {
  return FindOrAddGlobal(spv::Op::OpConstant, TypeInt(32, false), {value});
}
uint32_t Editor::ConstantI32(int32_t value) {
  return FindOrAddGlobal(spv::Op::OpConstant, TypeInt(32, true), {static_cast<uint32_t>(value)});
}
uint32_t Editor::ConstantF32(float value) {
  return FindOrAddGlobal(spv::Op::OpConstant, TypeFloat(32), {std::bit_cast<uint32_t>(value)});
}

uint32_t Editor::AddGlobalVariable(uint32_t pointerType, spv::StorageClass storage) {
  const uint32_t id = m_.NewId();
  m_.Insert(EndOf(Section::Global),
            MakeInstruction(spv::Op::OpVariable, {pointerType, id, static_cast<uint32_t>(storage)}));
  return id;
}

std::optional<spv::StorageClass> Editor::StorageClassOf(uint32_t variable) const {
  const Instruction* def = m_.Definition(variable);
  if (!def || OpOf(*def) != spv::Op::OpVariable) return std::nullopt;
  return static_cast<spv::StorageClass>(def->operand(2));
}

uint32_t Editor::PointeeType(uint32_t variable) const {
  const Instruction* def = m_.Definition(variable);
  if (!def || OpOf(*def) != spv::Op::OpVariable) return 0;
  const Instruction* pointer = m_.Definition(def->resultType());
  return pointer && OpOf(*pointer) == spv::Op::OpTypePointer ? pointer->operand(2) : 0;
}

std::optional<uint32_t> Editor::ConstantValue(uint32_t id) const {
  const Instruction* def = m_.Definition(id);
  if (!def || OpOf(*def) != spv::Op::OpConstant || def->operandCount() < 3) return std::nullopt;
  return def->operand(2);
}

std::pair<size_t, size_t> Editor::FunctionRange(uint32_t function) const {
  const size_t start = m_.Find([function](const Instruction& inst) {
    return OpOf(inst) == spv::Op::OpFunction && inst.resultId() == function;
  });
  if (start == Module::npos) return {Module::npos, Module::npos};
  return {start, m_.FindOpcode(static_cast<uint32_t>(spv::Op::OpFunctionEnd), start)};
}

size_t Editor::FunctionBodyStart(uint32_t function) const {
  const auto [start, end] = FunctionRange(function);
  if (start == Module::npos) return Module::npos;
  const size_t label = m_.FindOpcode(static_cast<uint32_t>(spv::Op::OpLabel), start);
  if (label == Module::npos || label > end) return Module::npos;
  // Function-scope OpVariables must stay first in the entry block.
  size_t at = label + 1;
  while (at < end && (OpOf(m_[at]) == spv::Op::OpVariable || OpOf(m_[at]) == spv::Op::OpLine ||
                      OpOf(m_[at]) == spv::Op::OpNoLine))
    ++at;
  return at;
}

}  // namespace rhi::spirv
