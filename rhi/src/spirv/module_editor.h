// Typed editing helpers over a Module: where each kind of instruction goes in
// SPIR-V's logical layout, find-or-add for types and constants, decorations,
// entry-point interfaces and function bodies. Shared by the patches in this
// folder.
//
// Internal to rhi_spirv: this header includes SPIRV-Headers' spirv.hpp11,
// which must not meet glslang's spirv.hpp (same include guard) in one
// translation unit, so code outside this folder includes only the public
// headers (spirv_module.h, reflection.h, patches.h, stream_output.h).
#pragma once

#include <initializer_list>
#include <optional>
#include <spirv/unified1/spirv.hpp11>
#include <string_view>
#include <utility>
#include <vector>

#include "spirv/spirv_module.h"

namespace rhi::spirv {

// Sections of the logical layout (SPIR-V spec 2.4), in module order.
enum class Section {
  Capability,
  Extension,
  ExtInstImport,
  MemoryModel,
  EntryPoint,
  ExecutionMode,
  DebugSource,
  DebugName,
  DebugModuleProcessed,
  Annotation,
  Global,  // types, constants, global variables, undefs, global OpLine/OpExtInst
  Function,
};
Section SectionOf(spv::Op op);

inline spv::Op OpOf(const Instruction& inst) { return static_cast<spv::Op>(inst.opcode()); }
inline Instruction MakeInstruction(spv::Op op, std::vector<uint32_t> operands) {
  return Instruction(static_cast<uint32_t>(op), std::move(operands));
}

// The first OpEntryPoint: glslang emits exactly one per module.
struct EntryPointInfo {
  size_t index = Module::npos;  // of the OpEntryPoint instruction
  spv::ExecutionModel model = spv::ExecutionModel::Max;
  uint32_t function = 0;
  std::string name;
  size_t firstInterfaceOperand = 0;
};

class Editor {
 public:
  explicit Editor(Module& module) : m_(module) {}
  Module& module() { return m_; }

  // Index at which a new instruction of `section` is appended.
  size_t EndOf(Section section) const;

  EntryPointInfo EntryPoint() const;
  std::vector<uint32_t> Interface(const EntryPointInfo& entry) const;
  void AddToInterface(uint32_t variable);  // of the first entry point; no duplicates

  bool HasCapability(spv::Capability capability) const;
  void AddCapability(spv::Capability capability);  // no-op when present
  void AddExtension(std::string_view name);         // no-op when present
  void AddExecutionMode(uint32_t function, spv::ExecutionMode mode, std::initializer_list<uint32_t> literals = {});
  void AddName(uint32_t id, std::string_view name);
  void Decorate(uint32_t target, spv::Decoration decoration, std::initializer_list<uint32_t> literals = {});
  void MemberDecorate(uint32_t structType, uint32_t member, spv::Decoration decoration,
                      std::initializer_list<uint32_t> literals = {});

  // First literal of a decoration on `target` (of a struct member), if present.
  std::optional<uint32_t> DecorationValue(uint32_t target, spv::Decoration decoration) const;
  std::optional<uint32_t> MemberDecorationValue(uint32_t structType, uint32_t member, spv::Decoration decoration) const;
  bool HasDecoration(uint32_t target, spv::Decoration decoration) const {
    return DecorationValue(target, decoration).has_value() || HasFlagDecoration(target, decoration);
  }
  bool HasFlagDecoration(uint32_t target, spv::Decoration decoration) const;  // decorations without literals

  // Types and constants are reused when an identical one exists.
  uint32_t TypeInt(uint32_t width, bool isSigned);
  uint32_t TypeFloat(uint32_t width);
  uint32_t TypeVector(uint32_t componentType, uint32_t count);
  uint32_t TypePointer(spv::StorageClass storage, uint32_t pointee);
  uint32_t ConstantU32(uint32_t value);
  uint32_t ConstantI32(int32_t value);
  uint32_t ConstantF32(float value);
  // A new global OpVariable (never reused).
  uint32_t AddGlobalVariable(uint32_t pointerType, spv::StorageClass storage);

  // For an OpVariable: its storage class and pointee type (0 when not a variable).
  std::optional<spv::StorageClass> StorageClassOf(uint32_t variable) const;
  uint32_t PointeeType(uint32_t variable) const;
  // Literal value of an OpConstant (integer constants up to 32 bits).
  std::optional<uint32_t> ConstantValue(uint32_t id) const;

  // [OpFunction index, OpFunctionEnd index] of a function, or {npos, npos}.
  std::pair<size_t, size_t> FunctionRange(uint32_t function) const;
  // First index in the function's entry block after its OpVariables: where
  // code that runs before anything else in the function goes.
  size_t FunctionBodyStart(uint32_t function) const;

 private:
  // Finds an instruction before the first function with this opcode and
  // operands (result id excluded), or appends one to the globals; returns its id.
  uint32_t FindOrAddGlobal(spv::Op op, uint32_t resultType, std::vector<uint32_t> operands);

  Module& m_;
};

}  // namespace rhi::spirv
