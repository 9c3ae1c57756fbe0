// AddPointSizeOutput: see patches.h.
#include <algorithm>
#include <vector>

#include "spirv/module_editor.h"
#include "spirv/patches.h"
#include "spirv/reflection.h"

namespace rhi::spirv {
namespace {

constexpr auto kPointSize = static_cast<uint32_t>(spv::BuiltIn::PointSize);

// Where 1.0 is stored: a plain variable, or a member of an output block.
struct PointSizeTarget {
  uint32_t variable = 0;
  std::optional<uint32_t> member;
};

// An output block (struct with built-in members, as glslang emits
// gl_PerVertex for GLSL) whose struct type no other variable uses, so a
// member can be appended without changing anything else.
const InterfaceVariable* FindPrivateOutputBlock(Editor& editor, const Reflection& r) {
  const Module& module = editor.module();
  for (const InterfaceVariable& v : r.outputs) {
    if (!v.member || v.perVertexArray) continue;
    const uint32_t block = editor.PointeeType(v.variableId);
    const auto pointers = std::count_if(module.begin(), module.end(), [block](const Instruction& i) {
      return OpOf(i) == spv::Op::OpTypePointer && i.operand(2) == block;
    });
    const auto variables = std::count_if(module.begin(), module.end(), [&](const Instruction& i) {
      return OpOf(i) == spv::Op::OpVariable && editor.PointeeType(i.resultId()) == block;
    });
    if (pointers == 1 && variables == 1) return &v;
  }
  return nullptr;
}

// Appends a float member decorated BuiltIn PointSize to the block's struct.
PointSizeTarget AppendBlockMember(Editor& editor, uint32_t blockVariable) {
  Module& module = editor.module();
  const uint32_t structType = editor.PointeeType(blockVariable);
  const uint32_t floatType = editor.TypeFloat(32);
  Instruction& type = module[module.FindDefinition(structType)];
  const auto member = static_cast<uint32_t>(type.operandCount() - 1);
  type.appendOperand(floatType);
  editor.MemberDecorate(structType, member, spv::Decoration::BuiltIn, {kPointSize});
  return {blockVariable, member};
}

PointSizeTarget AddPointSizeVariable(Editor& editor) {
  const uint32_t pointer = editor.TypePointer(spv::StorageClass::Output, editor.TypeFloat(32));
  const uint32_t var = editor.AddGlobalVariable(pointer, spv::StorageClass::Output);
  editor.Decorate(var, spv::Decoration::BuiltIn, {kPointSize});
  editor.AddName(var, "gl_PointSize");
  editor.AddToInterface(var);
  return {var, std::nullopt};
}

PointSizeTarget ChooseTarget(Editor& editor, const Reflection& r) {
  for (const InterfaceVariable& v : r.outputs)
    if (v.builtIn == kPointSize) return {v.variableId, v.member};  // declared but never written
  if (const InterfaceVariable* block = FindPrivateOutputBlock(editor, r))
    return AppendBlockMember(editor, block->variableId);
  return AddPointSizeVariable(editor);
}

// The store of 1.0, with its types and constants declared up front so that
// emitting it into functions adds no global instructions (which would shift
// the function positions being patched).
class PointSizeStore {
 public:
  PointSizeStore(Editor& editor, PointSizeTarget target) : module_(editor.module()), target_(target) {
    one_ = editor.ConstantF32(1.0f);
    if (target_.member) {
      pointer_ = editor.TypePointer(spv::StorageClass::Output, editor.TypeFloat(32));
      memberIndex_ = editor.ConstantI32(static_cast<int32_t>(*target_.member));
    }
  }

  // Fresh result ids on every call.
  std::vector<Instruction> Instructions() const {
    if (!target_.member) return {MakeInstruction(spv::Op::OpStore, {target_.variable, one_})};
    const uint32_t chain = module_.NewId();
    return {MakeInstruction(spv::Op::OpAccessChain, {pointer_, chain, target_.variable, memberIndex_}),
            MakeInstruction(spv::Op::OpStore, {chain, one_})};
  }

 private:
  Module& module_;
  PointSizeTarget target_;
  uint32_t one_ = 0, pointer_ = 0, memberIndex_ = 0;
};

bool IsEmit(const Instruction& inst) {
  return OpOf(inst) == spv::Op::OpEmitVertex || OpOf(inst) == spv::Op::OpEmitStreamVertex;
}

}  // namespace

WordsResult AddPointSizeOutput(std::span<const uint32_t> words) {
  const Result<Reflection> reflected = Reflect(words);
  if (!reflected) return WordsResult::Failure(reflected.error);
  const Reflection& r = reflected.value;
  if (r.stage != Stage::Vertex && r.stage != Stage::Geometry && r.stage != Stage::Domain)
    return WordsResult::Failure(std::string("AddPointSizeOutput: a ") + StageName(r.stage) +
                                " has no point size output (VS, DS or GS only)");
  if (r.writesPointSize) return WordsResult::Success(std::vector<uint32_t>(words.begin(), words.end()));

  Result<Module> parsed = Module::Parse(words);
  if (!parsed) return WordsResult::Failure(parsed.error);
  Editor editor(parsed.value);
  Module& module = parsed.value;
  if (r.stage == Stage::Geometry) editor.AddCapability(spv::Capability::GeometryPointSize);
  if (r.stage == Stage::Domain) editor.AddCapability(spv::Capability::TessellationPointSize);
  const PointSizeStore store(editor, ChooseTarget(editor, r));

  if (r.stage != Stage::Geometry) {
    const size_t bodyStart = editor.FunctionBodyStart(r.entryFunctionId);
    if (bodyStart == Module::npos) return WordsResult::Failure("AddPointSizeOutput: entry function has no body");
    module.Insert(bodyStart, store.Instructions());
    return WordsResult::Success(module.Assemble());
  }
  // Outputs are undefined after each emit, so every emitted vertex needs its own store.
  for (size_t at = 0; at < module.size(); ++at)
    if (IsEmit(module[at])) at = module.Insert(at, store.Instructions());
  return WordsResult::Success(module.Assemble());
}

}  // namespace rhi::spirv
