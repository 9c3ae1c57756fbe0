#include "spirv/reflection.h"

#include <algorithm>
#include <cctype>
#include <map>
#include <set>
#include <tuple>
#include <unordered_map>

#include "spirv/module_editor.h"

namespace rhi::spirv {
namespace {

// Definitions, names and decorations indexed once, so reflection is linear.
class ModuleIndex {
 public:
  explicit ModuleIndex(const Module& module) {
    for (const Instruction& inst : module) {
      if (const uint32_t id = inst.resultId()) defs_[id] = &inst;
      IndexDebugAndAnnotations(inst);
    }
  }

  const Instruction* Def(uint32_t id) const {
    const auto it = defs_.find(id);
    return it == defs_.end() ? nullptr : it->second;
  }
  spv::Op OpAt(uint32_t id) const {
    const Instruction* def = Def(id);
    return def ? OpOf(*def) : spv::Op::OpNop;
  }
  std::optional<uint32_t> Decoration(uint32_t id, spv::Decoration d, uint32_t member = kNoMember) const {
    const auto it = decorations_.find({id, member, static_cast<uint32_t>(d)});
    if (it == decorations_.end()) return std::nullopt;
    return it->second;
  }
  bool Has(uint32_t id, spv::Decoration d, uint32_t member = kNoMember) const {
    return Decoration(id, d, member).has_value();
  }
  std::string Semantic(uint32_t id, uint32_t member = kNoMember) const {
    const auto it = semantics_.find({id, member});
    return it == semantics_.end() ? std::string() : it->second;
  }
  // The UAV whose CounterBuffer decoration names `counter`, or 0.
  uint32_t CounterOf(uint32_t counter) const {
    const auto it = counterOf_.find(counter);
    return it == counterOf_.end() ? 0 : it->second;
  }
  std::string Name(uint32_t id) const {
    const auto it = names_.find(id);
    return it == names_.end() ? std::string() : it->second;
  }
  std::optional<uint32_t> ConstantValue(uint32_t id) const {
    const Instruction* def = Def(id);
    if (!def || OpOf(*def) != spv::Op::OpConstant || def->operandCount() < 3) return std::nullopt;
    return def->operand(2);
  }

  static constexpr uint32_t kNoMember = ~0u;

 private:
  using Key = std::tuple<uint32_t, uint32_t, uint32_t>;  // id, member, decoration

  void IndexDebugAndAnnotations(const Instruction& inst) {
    switch (OpOf(inst)) {
      case spv::Op::OpName: names_[inst.operand(0)] = inst.stringAt(1); break;
      case spv::Op::OpDecorate:  // flag decorations record 0 as their value
        decorations_[{inst.operand(0), kNoMember, inst.operand(1)}] = inst.operandCount() > 2 ? inst.operand(2) : 0;
        break;
      case spv::Op::OpMemberDecorate:
        decorations_[{inst.operand(0), inst.operand(1), inst.operand(2)}] =
            inst.operandCount() > 3 ? inst.operand(3) : 0;
        break;
      case spv::Op::OpDecorateId:  // OpDecorateId %uav CounterBuffer %counter
        if (inst.operandCount() > 2 && inst.operand(1) == static_cast<uint32_t>(spv::Decoration::CounterBuffer))
          counterOf_[inst.operand(2)] = inst.operand(0);
        break;
      case spv::Op::OpDecorateString:
        if (inst.operand(1) == static_cast<uint32_t>(spv::Decoration::UserSemantic))
          semantics_[{inst.operand(0), kNoMember}] = inst.stringAt(2);
        break;
      case spv::Op::OpMemberDecorateString:
        if (inst.operand(2) == static_cast<uint32_t>(spv::Decoration::UserSemantic))
          semantics_[{inst.operand(0), inst.operand(1)}] = inst.stringAt(3);
        break;
      default: break;
    }
  }

  std::unordered_map<uint32_t, const Instruction*> defs_;
  std::map<Key, uint32_t> decorations_;
  std::map<std::pair<uint32_t, uint32_t>, std::string> semantics_;
  std::unordered_map<uint32_t, std::string> names_;
  std::unordered_map<uint32_t, uint32_t> counterOf_;
};

Stage StageOf(spv::ExecutionModel model) {
  switch (model) {
    case spv::ExecutionModel::Vertex: return Stage::Vertex;
    case spv::ExecutionModel::TessellationControl: return Stage::Hull;
    case spv::ExecutionModel::TessellationEvaluation: return Stage::Domain;
    case spv::ExecutionModel::Geometry: return Stage::Geometry;
    case spv::ExecutionModel::Fragment: return Stage::Pixel;
    case spv::ExecutionModel::GLCompute: return Stage::Compute;
    default: return Stage::Unknown;
  }
}

// Per-vertex arrayed IO: the outermost array indexes vertices / control points.
bool IsArrayedIo(Stage stage, bool isOutput, bool patch) {
  if (patch) return false;
  if (stage == Stage::Geometry || stage == Stage::Domain) return !isOutput;
  return stage == Stage::Hull;
}

// Scalar kind, width, components and locations of an IO type.
struct Shape {
  ScalarKind kind = ScalarKind::Unknown;
  uint32_t width = 0;
  uint32_t components = 0;
  uint32_t locations = 1;
  uint32_t outerArraySize = 0;
};

Shape ShapeOf(const ModuleIndex& index, uint32_t type) {
  const Instruction* def = index.Def(type);
  if (!def) return {};
  switch (OpOf(*def)) {
    case spv::Op::OpTypeFloat: return {ScalarKind::Float, def->operand(1), 1, 1, 0};
    case spv::Op::OpTypeInt:
      return {def->operand(2) ? ScalarKind::SInt : ScalarKind::UInt, def->operand(1), 1, 1, 0};
    case spv::Op::OpTypeBool: return {ScalarKind::Bool, 32, 1, 1, 0};
    case spv::Op::OpTypeVector: {
      Shape s = ShapeOf(index, def->operand(1));
      s.components = def->operand(2);
      return s;
    }
    case spv::Op::OpTypeMatrix: {  // one location per column
      Shape s = ShapeOf(index, def->operand(1));
      s.locations *= def->operand(2);
      return s;
    }
    case spv::Op::OpTypeArray: {
      Shape s = ShapeOf(index, def->operand(1));
      const uint32_t length = index.ConstantValue(def->operand(2)).value_or(0);
      s.locations *= length;
      s.outerArraySize = length;
      return s;
    }
    default: return {};
  }
}

std::string Upper(std::string_view text) {
  std::string out(text);
  for (char& c : out) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return out;
}

class InterfaceReflector {
 public:
  InterfaceReflector(const ModuleIndex& index, Stage stage) : index_(index), stage_(stage) {}

  // Appends the variable (or each member of an IO block) to `out`.
  void Add(uint32_t variable, bool isOutput, std::vector<InterfaceVariable>& out) const {
    const Instruction* var = index_.Def(variable);
    const Instruction* pointer = var ? index_.Def(var->resultType()) : nullptr;
    if (!pointer) return;
    uint32_t type = pointer->operand(2);
    const bool patch = index_.Has(variable, spv::Decoration::Patch);

    InterfaceVariable base;
    base.variableId = variable;
    base.patch = patch;
    base.stream = index_.Decoration(variable, spv::Decoration::Stream).value_or(0);
    if (IsArrayedIo(stage_, isOutput, patch) && index_.OpAt(type) == spv::Op::OpTypeArray) {
      const Instruction* array = index_.Def(type);
      base.perVertexArray = true;
      base.arraySize = index_.ConstantValue(array->operand(2)).value_or(0);
      type = array->operand(1);
    }

    if (index_.OpAt(type) == spv::Op::OpTypeStruct) {
      const Instruction* block = index_.Def(type);
      for (uint32_t m = 0; m + 1 < block->operandCount(); ++m)
        out.push_back(Describe(base, block->operand(1 + m), type, m));
      return;
    }
    out.push_back(Describe(base, type, variable, ModuleIndex::kNoMember));
  }

 private:
  // `target`/`member` say where the decorations are: on the variable, or on a block member.
  InterfaceVariable Describe(InterfaceVariable v, uint32_t type, uint32_t target, uint32_t member) const {
    if (member != ModuleIndex::kNoMember) {
      v.member = member;
      v.stream = index_.Decoration(target, spv::Decoration::Stream, member).value_or(v.stream);
    }
    v.location = index_.Decoration(target, spv::Decoration::Location, member);
    v.component = index_.Decoration(target, spv::Decoration::Component, member);
    v.builtIn = index_.Decoration(target, spv::Decoration::BuiltIn, member);

    const Shape shape = ShapeOf(index_, type);
    v.scalarKind = shape.kind;
    v.scalarWidth = shape.width;
    v.componentCount = shape.components;
    v.locationCount = shape.locations;
    if (!v.perVertexArray) v.arraySize = shape.outerArraySize;

    std::string semantic = index_.Semantic(target, member);
    if (semantic.empty() && v.builtIn) semantic = BuiltInSemantic(*v.builtIn, stage_);
    const SplitSemanticResult split = SplitSemantic(semantic);
    v.semanticName = split.name;
    v.semanticIndex = split.index;
    return v;
  }

  const ModuleIndex& index_;
  Stage stage_;
};

void ReflectExecutionModes(const Module& module, const ModuleIndex& index, Reflection& r) {
  for (const Instruction& inst : module) {
    const spv::Op op = OpOf(inst);
    if (op == spv::Op::OpFunction) break;
    if ((op != spv::Op::OpExecutionMode && op != spv::Op::OpExecutionModeId) || inst.operand(0) != r.entryFunctionId)
      continue;
    const auto literal = [&inst](size_t i) { return inst.operandCount() > i ? inst.operand(i) : 0u; };
    switch (static_cast<spv::ExecutionMode>(inst.operand(1))) {
      case spv::ExecutionMode::InputPoints: r.gsInput = GsInputPrimitive::Points; break;
      case spv::ExecutionMode::InputLines: r.gsInput = GsInputPrimitive::Lines; break;
      case spv::ExecutionMode::InputLinesAdjacency: r.gsInput = GsInputPrimitive::LinesAdjacency; break;
      case spv::ExecutionMode::Triangles:
        if (r.stage == Stage::Geometry) r.gsInput = GsInputPrimitive::Triangles;
        break;
      case spv::ExecutionMode::InputTrianglesAdjacency: r.gsInput = GsInputPrimitive::TrianglesAdjacency; break;
      case spv::ExecutionMode::OutputPoints: r.gsOutput = GsOutputPrimitive::Points; break;
      case spv::ExecutionMode::OutputLineStrip: r.gsOutput = GsOutputPrimitive::LineStrip; break;
      case spv::ExecutionMode::OutputTriangleStrip: r.gsOutput = GsOutputPrimitive::TriangleStrip; break;
      case spv::ExecutionMode::OutputVertices: r.gsMaxVertices = literal(2); break;
      case spv::ExecutionMode::Invocations: r.gsInvocations = literal(2); break;
      case spv::ExecutionMode::LocalSize: r.localSize = {literal(2), literal(3), literal(4)}; break;
      case spv::ExecutionMode::LocalSizeId:
        for (size_t i = 0; i < 3; ++i) r.localSize[i] = index.ConstantValue(literal(2 + i)).value_or(0);
        break;
      default: break;
    }
  }
}

DescriptorKind ImageKind(const Instruction& image) {
  // OpTypeImage operands: result, sampled type, Dim, Depth, Arrayed, MS, Sampled, Format.
  const auto dim = static_cast<spv::Dim>(image.operand(2));
  const bool storage = image.operand(6) == 2;
  if (dim == spv::Dim::SubpassData) return DescriptorKind::InputAttachment;
  if (dim == spv::Dim::Buffer) return storage ? DescriptorKind::StorageTexelBuffer : DescriptorKind::UniformTexelBuffer;
  return storage ? DescriptorKind::StorageImage : DescriptorKind::SampledImage;
}

bool AllMembersNonWritable(const ModuleIndex& index, const Instruction& block) {
  for (uint32_t m = 0; m + 1 < block.operandCount(); ++m)
    if (!index.Has(block.resultId(), spv::Decoration::NonWritable, m)) return false;
  return block.operandCount() > 1;
}

std::optional<DescriptorBinding> DescribeBinding(const ModuleIndex& index, const Instruction& var) {
  const auto storage = static_cast<spv::StorageClass>(var.operand(2));
  if (storage != spv::StorageClass::Uniform && storage != spv::StorageClass::UniformConstant &&
      storage != spv::StorageClass::StorageBuffer)
    return std::nullopt;
  const uint32_t id = var.resultId();
  if (!index.Has(id, spv::Decoration::Binding) && !index.Has(id, spv::Decoration::DescriptorSet)) return std::nullopt;

  DescriptorBinding b;
  b.variableId = id;
  b.set = index.Decoration(id, spv::Decoration::DescriptorSet).value_or(0);
  b.binding = index.Decoration(id, spv::Decoration::Binding).value_or(0);
  b.nonWritable = index.Has(id, spv::Decoration::NonWritable);
  b.counterOf = index.CounterOf(id);
  const Instruction* pointer = index.Def(var.resultType());
  const Instruction* type = pointer ? index.Def(pointer->operand(2)) : nullptr;
  if (type && OpOf(*type) == spv::Op::OpTypeArray) {
    b.arrayCount = index.ConstantValue(type->operand(2)).value_or(1);
    type = index.Def(type->operand(1));
  } else if (type && OpOf(*type) == spv::Op::OpTypeRuntimeArray) {
    b.arrayCount = 0;
    type = index.Def(type->operand(1));
  }
  if (!type) return b;
  switch (OpOf(*type)) {
    case spv::Op::OpTypeStruct: {
      const bool storageBlock =
          storage == spv::StorageClass::StorageBuffer || index.Has(type->resultId(), spv::Decoration::BufferBlock);
      b.kind = storageBlock ? DescriptorKind::StorageBuffer : DescriptorKind::UniformBuffer;
      b.nonWritable = b.nonWritable || (storageBlock && AllMembersNonWritable(index, *type));
      break;
    }
    case spv::Op::OpTypeImage: b.kind = ImageKind(*type); break;
    case spv::Op::OpTypeSampler: b.kind = DescriptorKind::Sampler; break;
    case spv::Op::OpTypeSampledImage: b.kind = DescriptorKind::CombinedImageSampler; break;
    case spv::Op::OpTypeAccelerationStructureKHR: b.kind = DescriptorKind::AccelerationStructure; break;
    default: break;
  }
  b.name = index.Name(id);
  if (b.name.empty()) b.name = index.Name(type->resultId());  // glslang: cbuffer variables are unnamed
  return b;
}

// Which (variable, member) pairs some OpStore / OpCopyMemory writes through.
// A store to a whole block variable writes every member (kNoMember).
class StoreTargets {
 public:
  StoreTargets(const Module& module, const ModuleIndex& index, const Reflection& r) : index_(index) {
    for (const InterfaceVariable& v : r.outputs)
      if (v.perVertexArray) arrayed_.insert(v.variableId);
    for (const Instruction& inst : module) {
      const spv::Op op = OpOf(inst);
      if (op == spv::Op::OpStore || op == spv::Op::OpCopyMemory) Record(inst.operand(0));
    }
  }

  bool Written(const InterfaceVariable& v) const {
    const uint32_t member = v.member.value_or(ModuleIndex::kNoMember);
    return written_.count({v.variableId, ModuleIndex::kNoMember}) || written_.count({v.variableId, member});
  }

 private:
  void Record(uint32_t pointer) {
    // Walk access chains down to the variable, remembering the index that
    // picks the block member (the first, or the second for arrayed IO).
    std::vector<uint32_t> indices;
    uint32_t at = pointer;
    while (const Instruction* def = index_.Def(at)) {
      const spv::Op op = OpOf(*def);
      if (op == spv::Op::OpVariable) break;
      if (op != spv::Op::OpAccessChain && op != spv::Op::OpInBoundsAccessChain) return;
      std::vector<uint32_t> chain(def->operands().begin() + 3, def->operands().end());
      indices.insert(indices.begin(), chain.begin(), chain.end());
      at = def->operand(2);
    }
    const size_t memberAt = arrayed_.count(at) ? 1 : 0;
    uint32_t member = ModuleIndex::kNoMember;
    if (indices.size() > memberAt) member = index_.ConstantValue(indices[memberAt]).value_or(ModuleIndex::kNoMember);
    written_.insert({at, member});
  }

  const ModuleIndex& index_;
  std::set<uint32_t> arrayed_;
  std::set<std::pair<uint32_t, uint32_t>> written_;
};

void ReflectPositionAndPointSize(const Module& module, const ModuleIndex& index, Reflection& r) {
  const StoreTargets stores(module, index, r);
  for (const InterfaceVariable& v : r.outputs) {
    if (v.builtIn == static_cast<uint32_t>(spv::BuiltIn::Position)) {
      r.hasPositionOutput = true;
      r.writesPosition = r.writesPosition || stores.Written(v);
    } else if (v.builtIn == static_cast<uint32_t>(spv::BuiltIn::PointSize)) {
      r.hasPointSizeOutput = true;
      r.writesPointSize = r.writesPointSize || stores.Written(v);
    }
  }
}

const InterfaceVariable* FindBySemantic(const std::vector<InterfaceVariable>& list, std::string_view name,
                                        uint32_t semanticIndex, std::optional<uint32_t> stream) {
  const InterfaceVariable* fallback = nullptr;
  for (const InterfaceVariable& v : list) {
    if (v.semanticName.empty() || !SemanticEquals(v.semanticName, name)) continue;
    if (semanticIndex < v.semanticIndex || semanticIndex - v.semanticIndex >= std::max(v.locationCount, 1u)) continue;
    if (!stream || v.stream == *stream) return &v;
    if (!fallback) fallback = &v;
  }
  return fallback;
}

}  // namespace

const char* StageName(Stage stage) {
  switch (stage) {
    case Stage::Vertex: return "VS";
    case Stage::Hull: return "HS";
    case Stage::Domain: return "DS";
    case Stage::Geometry: return "GS";
    case Stage::Pixel: return "PS";
    case Stage::Compute: return "CS";
    case Stage::Unknown: break;
  }
  return "unknown stage";
}

const char* DescriptorKindName(DescriptorKind kind) {
  switch (kind) {
    case DescriptorKind::UniformBuffer: return "uniform buffer";
    case DescriptorKind::StorageBuffer: return "storage buffer";
    case DescriptorKind::SampledImage: return "sampled image";
    case DescriptorKind::StorageImage: return "storage image";
    case DescriptorKind::Sampler: return "sampler";
    case DescriptorKind::CombinedImageSampler: return "combined image sampler";
    case DescriptorKind::UniformTexelBuffer: return "uniform texel buffer";
    case DescriptorKind::StorageTexelBuffer: return "storage texel buffer";
    case DescriptorKind::InputAttachment: return "input attachment";
    case DescriptorKind::AccelerationStructure: return "acceleration structure";
    case DescriptorKind::Unknown: break;
  }
  return "unknown";
}

bool SemanticEquals(std::string_view a, std::string_view b) {
  return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](char x, char y) {
           return std::toupper(static_cast<unsigned char>(x)) == std::toupper(static_cast<unsigned char>(y));
         });
}

SplitSemanticResult SplitSemantic(std::string_view semantic) {
  size_t digits = semantic.size();
  while (digits > 0 && std::isdigit(static_cast<unsigned char>(semantic[digits - 1]))) --digits;
  SplitSemanticResult out{Upper(semantic.substr(0, digits)), 0};
  // A semantic that is all digits is malformed; keep it whole as the name.
  if (digits == 0) return {Upper(semantic), 0};
  for (char c : semantic.substr(digits)) out.index = out.index * 10 + static_cast<uint32_t>(c - '0');
  return out;
}

std::string BuiltInSemantic(uint32_t builtIn, Stage stage) {
  using spv::BuiltIn;
  switch (static_cast<BuiltIn>(builtIn)) {
    case BuiltIn::Position:
    case BuiltIn::FragCoord: return "SV_POSITION";
    case BuiltIn::ClipDistance: return "SV_CLIPDISTANCE";
    case BuiltIn::CullDistance: return "SV_CULLDISTANCE";
    case BuiltIn::VertexIndex: return "SV_VERTEXID";
    case BuiltIn::InstanceIndex: return "SV_INSTANCEID";
    case BuiltIn::PrimitiveId: return "SV_PRIMITIVEID";
    case BuiltIn::Layer: return "SV_RENDERTARGETARRAYINDEX";
    case BuiltIn::ViewportIndex: return "SV_VIEWPORTARRAYINDEX";
    case BuiltIn::FrontFacing: return "SV_ISFRONTFACE";
    case BuiltIn::SampleId: return "SV_SAMPLEINDEX";
    case BuiltIn::SampleMask: return "SV_COVERAGE";
    case BuiltIn::FragDepth: return "SV_DEPTH";
    case BuiltIn::GlobalInvocationId: return "SV_DISPATCHTHREADID";
    case BuiltIn::LocalInvocationId: return "SV_GROUPTHREADID";
    case BuiltIn::WorkgroupId: return "SV_GROUPID";
    case BuiltIn::LocalInvocationIndex: return "SV_GROUPINDEX";
    case BuiltIn::InvocationId: return stage == Stage::Hull ? "SV_OUTPUTCONTROLPOINTID" : "SV_GSINSTANCEID";
    case BuiltIn::TessCoord: return "SV_DOMAINLOCATION";
    case BuiltIn::TessLevelOuter: return "SV_TESSFACTOR";
    case BuiltIn::TessLevelInner: return "SV_INSIDETESSFACTOR";
    default: return "";
  }
}

const InterfaceVariable* Reflection::FindInput(std::string_view semanticName, uint32_t semanticIndex) const {
  return FindBySemantic(inputs, semanticName, semanticIndex, std::nullopt);
}

const InterfaceVariable* Reflection::FindOutput(std::string_view semanticName, uint32_t semanticIndex,
                                                std::optional<uint32_t> stream) const {
  return FindBySemantic(outputs, semanticName, semanticIndex, stream);
}

Result<Reflection> Reflect(std::span<const uint32_t> words) {
  Result<Module> parsed = Module::Parse(words);
  if (!parsed) return Result<Reflection>::Failure(parsed.error);
  Module& module = parsed.value;
  const ModuleIndex index(module);
  Editor editor(module);
  const EntryPointInfo entry = editor.EntryPoint();
  if (entry.index == Module::npos) return Result<Reflection>::Failure("SPIR-V module has no OpEntryPoint");

  Reflection r;
  r.stage = StageOf(entry.model);
  if (r.stage == Stage::Unknown)
    return Result<Reflection>::Failure("unsupported execution model " + std::to_string(static_cast<uint32_t>(entry.model)));
  r.entryPoint = entry.name;
  r.entryFunctionId = entry.function;
  r.spirvVersion = module.version();

  const InterfaceReflector io(index, r.stage);
  for (uint32_t id : editor.Interface(entry)) {
    const Instruction* var = index.Def(id);
    if (!var || OpOf(*var) != spv::Op::OpVariable) continue;
    const auto storage = static_cast<spv::StorageClass>(var->operand(2));
    if (storage == spv::StorageClass::Input) io.Add(id, false, r.inputs);
    if (storage == spv::StorageClass::Output) io.Add(id, true, r.outputs);
  }
  // Descriptors: every global variable, since before SPIR-V 1.4 the
  // interface lists only inputs and outputs.
  for (const Instruction& inst : module) {
    if (OpOf(inst) == spv::Op::OpFunction) break;
    if (OpOf(inst) != spv::Op::OpVariable) continue;
    if (auto binding = DescribeBinding(index, inst)) r.bindings.push_back(std::move(*binding));
  }
  ReflectExecutionModes(module, index, r);
  ReflectPositionAndPointSize(module, index, r);
  return Result<Reflection>::Success(std::move(r));
}

}  // namespace rhi::spirv
