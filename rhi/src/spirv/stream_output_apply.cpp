// ApplyStreamOutput: see stream_output.h.
#include <algorithm>
#include <vector>

#include "spirv/module_editor.h"
#include "spirv/stream_output.h"

namespace rhi::spirv {
namespace {

// One non-gap entry: the output it reads and the variable transform feedback captures.
struct Capture {
  const InterfaceVariable* source = nullptr;
  UINT stream = 0, start = 0, count = 0;
  uint32_t sourceType = 0;     // type of the original output (scalar or vector)
  uint32_t scalarType = 0;
  uint32_t valueType = 0;      // type of the captured value: scalar or vecN
  uint32_t variable = 0;       // the new Output variable
  uint32_t memberPointer = 0;  // block members: Output pointer to the member type
  uint32_t memberIndex = 0;    // block members: constant member index
};

// Type of the output's value: the variable's pointee, or the block member's type.
uint32_t SourceValueType(const Module& module, Editor& editor, const InterfaceVariable& v) {
  const uint32_t pointee = editor.PointeeType(v.variableId);
  if (!v.member) return pointee;
  const Instruction* block = module.Definition(pointee);
  return block && block->operandCount() > 1 + *v.member ? block->operand(1 + *v.member) : 0;
}

uint32_t ScalarTypeOf(const Module& module, uint32_t type) {
  const Instruction* def = module.Definition(type);
  return def && OpOf(*def) == spv::Op::OpTypeVector ? def->operand(1) : type;
}

// First location no output uses, so the capture variables collide with nothing.
uint32_t FirstFreeLocation(const Reflection& r) {
  uint32_t next = 0;
  for (const InterfaceVariable& v : r.outputs)
    if (v.location) next = std::max(next, *v.location + std::max(v.locationCount, 1u));
  return next;
}

// Declares the capture variable with its transform-feedback decorations.
Capture Declare(Editor& editor, const SO_DECLARATION_ENTRY& e, const InterfaceVariable& source, uint32_t location,
                UINT stride, UINT offset) {
  const Module& module = editor.module();
  Capture c;
  c.source = &source;
  c.stream = e.Stream;
  c.start = e.StartComponent;
  c.count = e.ComponentCount;
  c.sourceType = SourceValueType(module, editor, source);
  c.scalarType = ScalarTypeOf(module, c.sourceType);
  c.valueType = c.count == 1 ? c.scalarType : editor.TypeVector(c.scalarType, c.count);
  c.variable = editor.AddGlobalVariable(editor.TypePointer(spv::StorageClass::Output, c.valueType),
                                        spv::StorageClass::Output);
  if (source.member) {
    c.memberPointer = editor.TypePointer(spv::StorageClass::Output, c.sourceType);
    c.memberIndex = editor.ConstantI32(static_cast<int32_t>(*source.member));
  }
  editor.Decorate(c.variable, spv::Decoration::Location, {location});
  editor.Decorate(c.variable, spv::Decoration::XfbBuffer, {e.OutputSlot});
  editor.Decorate(c.variable, spv::Decoration::XfbStride, {stride});
  editor.Decorate(c.variable, spv::Decoration::Offset, {offset});
  if (e.Stream > 0) editor.Decorate(c.variable, spv::Decoration::Stream, {e.Stream});
  editor.AddName(c.variable, "xfb" + std::to_string(e.OutputSlot) + "." + source.Semantic() + "." +
                                 std::string("xyzw").substr(c.start, c.count));
  editor.AddToInterface(c.variable);
  return c;
}

// Load the original output, pick the components, store them into the capture.
std::vector<Instruction> CopyInstructions(Module& module, const Capture& c) {
  std::vector<Instruction> code;
  uint32_t pointer = c.source->variableId;
  if (c.source->member) {
    pointer = module.NewId();
    code.push_back(MakeInstruction(spv::Op::OpAccessChain, {c.memberPointer, pointer, c.source->variableId, c.memberIndex}));
  }
  const uint32_t whole = module.NewId();
  code.push_back(MakeInstruction(spv::Op::OpLoad, {c.sourceType, whole, pointer}));
  uint32_t value = whole;
  if (c.count < c.source->componentCount) {
    value = module.NewId();
    if (c.count == 1) {
      code.push_back(MakeInstruction(spv::Op::OpCompositeExtract, {c.valueType, value, whole, c.start}));
    } else {
      std::vector<uint32_t> operands{c.valueType, value, whole, whole};
      for (UINT i = 0; i < c.count; ++i) operands.push_back(c.start + i);
      code.push_back(MakeInstruction(spv::Op::OpVectorShuffle, std::move(operands)));
    }
  }
  code.push_back(MakeInstruction(spv::Op::OpStore, {c.variable, value}));
  return code;
}

std::vector<Instruction> CopiesForStream(Module& module, const std::vector<Capture>& captures, UINT stream) {
  std::vector<Instruction> code;
  for (const Capture& c : captures) {
    if (c.stream != stream) continue;
    std::vector<Instruction> copy = CopyInstructions(module, c);
    code.insert(code.end(), std::make_move_iterator(copy.begin()), std::make_move_iterator(copy.end()));
  }
  return code;
}

// GS: a vertex's outputs are read when it is emitted, so copy right before each emit of its stream.
std::string InsertBeforeEmits(Editor& editor, const std::vector<Capture>& captures) {
  Module& module = editor.module();
  for (size_t at = 0; at < module.size(); ++at) {
    const spv::Op op = OpOf(module[at]);
    if (op != spv::Op::OpEmitVertex && op != spv::Op::OpEmitStreamVertex) continue;
    std::optional<uint32_t> stream = 0u;
    if (op == spv::Op::OpEmitStreamVertex) stream = editor.ConstantValue(module[at].operand(0));
    if (!stream) return "ApplyStreamOutput: OpEmitStreamVertex with a non-constant stream";
    at = module.Insert(at, CopiesForStream(module, captures, *stream));
  }
  return {};
}

// VS/DS: outputs are final when the entry function returns.
std::string InsertBeforeReturns(Editor& editor, uint32_t entryFunction, const std::vector<Capture>& captures) {
  Module& module = editor.module();
  auto [start, end] = editor.FunctionRange(entryFunction);
  if (start == Module::npos) return "ApplyStreamOutput: entry function not found";
  for (size_t at = start; at < end; ++at) {
    if (OpOf(module[at]) != spv::Op::OpReturn) continue;
    std::vector<Instruction> code = CopiesForStream(module, captures, 0);
    end += code.size();
    at = module.Insert(at, std::move(code));
  }
  return {};
}

}  // namespace

WordsResult ApplyStreamOutput(std::span<const uint32_t> words, const Reflection& reflection,
                              std::span<const SO_DECLARATION_ENTRY> entries, std::span<const UINT> bufferStrides) {
  const std::string invalid =
      ValidateSoDeclaration(entries.data(), static_cast<UINT>(entries.size()), bufferStrides.data(),
                            static_cast<UINT>(bufferStrides.size()), SO_NO_RASTERIZED_STREAM, reflection);
  if (!invalid.empty()) return WordsResult::Failure(invalid);
  if (entries.empty()) return WordsResult::Success(std::vector<uint32_t>(words.begin(), words.end()));

  Result<Module> parsed = Module::Parse(words);
  if (!parsed) return WordsResult::Failure(parsed.error);
  Module& module = parsed.value;
  Editor editor(module);
  if (editor.EntryPoint().function != reflection.entryFunctionId)
    return WordsResult::Failure("ApplyStreamOutput: the reflection is not of these words");

  // Declarations first (they shift function positions), then the copies.
  const std::array<UINT, SO_BUFFER_SLOT_COUNT> strides = SoBufferStrides(entries, bufferStrides);
  std::array<UINT, SO_BUFFER_SLOT_COUNT> offsets{};
  uint32_t location = FirstFreeLocation(reflection);
  std::vector<Capture> captures;
  bool streams = false;
  for (const SO_DECLARATION_ENTRY& e : entries) {
    if (e.SemanticName) {
      const InterfaceVariable* source = reflection.FindOutput(e.SemanticName, e.SemanticIndex, e.Stream);
      captures.push_back(Declare(editor, e, *source, location++, strides[e.OutputSlot], offsets[e.OutputSlot]));
      streams = streams || e.Stream > 0;
    }
    offsets[e.OutputSlot] += 4u * e.ComponentCount;  // gaps only advance the offset
  }
  editor.AddCapability(spv::Capability::TransformFeedback);
  if (streams) editor.AddCapability(spv::Capability::GeometryStreams);
  editor.AddExecutionMode(reflection.entryFunctionId, spv::ExecutionMode::Xfb);

  const std::string error = reflection.stage == Stage::Geometry
                                ? InsertBeforeEmits(editor, captures)
                                : InsertBeforeReturns(editor, reflection.entryFunctionId, captures);
  if (!error.empty()) return WordsResult::Failure(error);
  return WordsResult::Success(module.Assemble());
}

}  // namespace rhi::spirv
