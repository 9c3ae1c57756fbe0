// D3D-style reflection (cbuffers with members, t/s/u resources) from
// glslang's reflection database, after the IO mapper assigned bindings.
// glslang 12's reflection computes cbuffer member offsets with GLSL vector
// alignment (a float2 after a float lands at 8), while its SPIR-V generator
// applies the HLSL rule (4); offsets are therefore read from the SPIR-V.
#include <glslang/Include/Types.h>
#include <glslang/Public/ShaderLang.h>

#include <rhi/shader_bindings.h>
#include <algorithm>
#include <charconv>
#include <cstring>
#include <optional>
#include <regex>
#include <set>
#include <unordered_map>

#include "internal.h"

namespace hlsl::detail {
namespace {

using rhi::RegisterClass;

uint32_t RoundUp16(uint32_t n) { return (n + 15u) & ~15u; }

uint32_t RegisterSlot(Stage stage, RegisterClass c, int binding) {
  const uint32_t base = rhi::BindingFor(static_cast<rhi::ShaderStage>(stage), c, 0);
  return binding >= 0 && static_cast<uint32_t>(binding) >= base ? binding - base : 0;
}

BaseType ToBaseType(glslang::TBasicType t) {
  switch (t) {
    case glslang::EbtFloat: return BaseType::Float;
    case glslang::EbtInt: return BaseType::Int;
    case glslang::EbtUint: return BaseType::Uint;
    case glslang::EbtBool: return BaseType::Bool;
    case glslang::EbtDouble: return BaseType::Double;
    case glslang::EbtFloat16: return BaseType::Half;
    case glslang::EbtStruct: return BaseType::Struct;
    default: return BaseType::Other;
  }
}

// glslang stores an HLSL floatRxC as a matrix of R "columns" and C "rows", and
// HLSL's default column_major as its row_major, so the names swap twice.
bool IsHlslRowMajor(const glslang::TType& t) { return t.getQualifier().layoutMatrix == glslang::ElmColumnMajor; }

uint32_t HlslSize(const glslang::TType& type);

// HLSL packing: structs, arrays and matrices start a new 16-byte register;
// anything else starts one only when it would straddle a register.
uint32_t HlslStructSize(const glslang::TTypeList& members) {
  uint32_t offset = 0;
  for (const glslang::TTypeLoc& m : members) {
    const uint32_t size = HlslSize(*m.type);
    if (m.type->isStruct() || m.type->isArray() || m.type->isMatrix() || offset % 16 + size > 16)
      offset = RoundUp16(offset);
    offset += size;
  }
  return offset;
}

uint32_t HlslSize(const glslang::TType& type) {
  if (type.isArray()) {
    if (!type.isSizedArray()) return 0;
    const glslang::TType element(type, 0);
    const uint32_t elementSize = HlslSize(element);
    return RoundUp16(elementSize) * (type.getOuterArraySize() - 1) + elementSize;
  }
  if (type.isStruct()) return HlslStructSize(*type.getStruct());
  const uint32_t component = type.getBasicType() == glslang::EbtDouble ? 8 : 4;
  if (!type.isMatrix()) return component * type.getVectorSize();
  const uint32_t hlslRows = type.getMatrixCols(), hlslColumns = type.getMatrixRows();
  const bool rowMajor = IsHlslRowMajor(type);
  const uint32_t registers = rowMajor ? hlslRows : hlslColumns;
  const uint32_t perRegister = rowMajor ? hlslColumns : hlslRows;
  return 16 * (registers - 1) + component * perRegister;
}

// The few SPIR-V facts needed to find a cbuffer member's Offset by its
// glslang reflection name ("m", "light.color", "lights[1].color").
class SpirvLayout {
 public:
  explicit SpirvLayout(const std::vector<uint32_t>& spirv) {
    for (size_t at = 5; at < spirv.size();) {
      const uint32_t count = spirv[at] >> 16;
      if (count == 0 || at + count > spirv.size()) break;
      Record(spirv[at] & 0xffff, &spirv[at], count);
      at += count;
    }
  }

  bool HasBlock(int binding) const { return blocks_.count(binding) != 0; }

  // The member `path` of the block at `binding`. Blocks a shader does not use keep
  // the registers written in the source, so another block of the shader may sit at
  // the same binding (an unused cbuffer : register(b2) beside one glslang put in
  // b2): the one named `block` (its type's OpName) is meant, else the only one.
  std::optional<uint32_t> Offset(int binding, const std::string& block, const std::string& path) const {
    const auto [first, end] = blocks_.equal_range(binding);
    for (auto it = first; it != end; ++it)
      if (std::distance(first, end) == 1 || Get(names_, it->second) == block) return MemberOffset(it->second, path);
    return std::nullopt;
  }

 private:
  struct Member {
    uint32_t type = 0, offset = 0;
  };
  static uint32_t Get(const std::unordered_map<uint32_t, uint32_t>& map, uint32_t key) {
    const auto it = map.find(key);
    return it == map.end() ? 0 : it->second;
  }
  static std::string Get(const std::unordered_map<uint32_t, std::string>& map, uint32_t key) {
    const auto it = map.find(key);
    return it == map.end() ? std::string() : it->second;
  }

  std::optional<uint32_t> MemberOffset(uint32_t type, const std::string& path) const {
    uint32_t offset = 0;
    for (size_t i = 0; i < path.size();) {
      if (path[i] == '.') ++i;
      if (path[i] == '[') {  // array element: index * ArrayStride
        uint32_t index = 0;
        const auto [end, ec] = std::from_chars(path.data() + i + 1, path.data() + path.size(), index);
        if (ec != std::errc() || !arrayElement_.count(type)) return std::nullopt;
        offset += index * Get(arrayStride_, type);
        type = arrayElement_.at(type);
        i = end - path.data() + 1;
        continue;
      }
      const size_t end = std::min(path.find_first_of(".[", i), path.size());
      const auto member = members_.find({type, path.substr(i, end - i)});
      if (member == members_.end()) return std::nullopt;
      offset += member->second.offset;
      type = member->second.type;
      i = end;
    }
    return offset;
  }

  static std::string String(const uint32_t* words, size_t count) {
    const char* text = reinterpret_cast<const char*>(words);
    return std::string(text, strnlen(text, count * 4));
  }

  void Record(uint32_t op, const uint32_t* w, uint32_t count) {
    constexpr uint32_t kName = 5, kMemberName = 6, kTypeArray = 28, kTypeStruct = 30, kTypePointer = 32, kVariable = 59,
                       kDecorate = 71, kMemberDecorate = 72;
    constexpr uint32_t kArrayStride = 6, kBinding = 33, kOffset = 35, kUniform = 2;
    if (op == kName && count > 2) names_[w[1]] = String(w + 2, count - 2);
    if (op == kMemberName && count > 3) memberNames_[{w[1], w[2]}] = String(w + 3, count - 3);
    if (op == kMemberDecorate && count > 4 && w[3] == kOffset) offsets_[{w[1], w[2]}] = w[4];
    if (op == kDecorate && count > 3 && w[2] == kArrayStride) arrayStride_[w[1]] = w[3];
    if (op == kDecorate && count > 3 && w[2] == kBinding) bindings_[w[1]] = w[3];
    if (op == kTypeArray && count > 3) arrayElement_[w[1]] = w[2];
    if (op == kTypePointer && count > 3) pointee_[w[1]] = w[3];
    if (op == kTypeStruct) {
      for (uint32_t m = 0; m + 2 < count; ++m) {
        members_[{w[1], memberNames_[{w[1], m}]}] = {w[2 + m], offsets_[{w[1], m}]};
      }
    }
    if (op == kVariable && count > 3 && w[3] == kUniform && bindings_.count(w[2])) {
      blocks_.emplace(static_cast<int>(bindings_[w[2]]), Get(pointee_, w[1]));
    }
  }

  // Names and decorations precede types, and types precede variables.
  std::map<std::pair<uint32_t, uint32_t>, std::string> memberNames_;
  std::map<std::pair<uint32_t, uint32_t>, uint32_t> offsets_;
  std::map<std::pair<uint32_t, std::string>, Member> members_;
  std::unordered_map<uint32_t, uint32_t> arrayStride_, bindings_, arrayElement_, pointee_;
  std::unordered_map<uint32_t, std::string> names_;
  std::unordered_multimap<int, uint32_t> blocks_;  // binding -> block struct types
};

ConstantBufferMember ToMember(const glslang::TObjectReflection& u) {
  const glslang::TType& type = *u.getType();
  ConstantBufferMember m;
  m.name = u.name;
  m.offset = static_cast<uint32_t>(u.offset);
  m.size = HlslSize(type);
  m.baseType = ToBaseType(type.getBasicType());
  if (type.isMatrix()) {
    m.rows = type.getMatrixCols();
    m.columns = type.getMatrixRows();
  } else if (!type.isStruct()) {
    m.columns = type.getVectorSize();
  }
  m.arrayElements = type.isSizedArray() ? type.getOuterArraySize() : 0;
  return m;
}

ResourceInfo::Dimension ToDimension(const glslang::TSampler& s) {
  using D = ResourceInfo::Dimension;
  switch (s.dim) {
    case glslang::Esd1D: return s.isArrayed() ? D::Tex1DArray : D::Tex1D;
    case glslang::Esd2D:
      if (s.isMultiSample()) return s.isArrayed() ? D::Tex2DMSArray : D::Tex2DMS;
      return s.isArrayed() ? D::Tex2DArray : D::Tex2D;
    case glslang::Esd3D: return D::Tex3D;
    case glslang::EsdCube: return s.isArrayed() ? D::TexCubeArray : D::TexCube;
    case glslang::EsdBuffer: return D::Buffer;
    default: return D::Unknown;
  }
}

// Texture2D / SamplerState / RWTexture2D / Buffer / RWBuffer (glslang opaque types).
ResourceInfo ToOpaqueResource(const glslang::TObjectReflection& u, Stage stage) {
  using K = ResourceInfo::Kind;
  const glslang::TType& type = *u.getType();
  const glslang::TSampler& s = type.getSampler();
  ResourceInfo r;
  r.name = u.name;
  r.binding = static_cast<uint32_t>(u.getBinding());
  r.bindCount = type.isSizedArray() ? type.getCumulativeArraySize() : 1;
  r.dimension = s.isPureSampler() ? ResourceInfo::Dimension::Unknown : ToDimension(s);
  RegisterClass c = RegisterClass::ShaderResource;
  r.kind = s.isBuffer() ? K::Buffer : K::Texture;
  if (s.isPureSampler()) {
    r.kind = K::Sampler;
    r.comparisonSampler = s.isShadow();
    c = RegisterClass::Sampler;
  } else if (s.isImage()) {
    r.kind = s.isBuffer() ? K::RWBuffer : K::RWTexture;
    c = RegisterClass::UnorderedAccess;
  }
  r.registerSlot = RegisterSlot(stage, c, u.getBinding());
  return r;
}

// glslang 12 turns (RW)ByteAddressBuffer into the same storage block as a
// (RW)StructuredBuffer<uint> and forgets which it was, so the names declared
// as byte address buffers are found in the source text.
std::set<std::string> ByteAddressBufferNames(const SourceFiles& files) {
  static const std::regex kDeclaration(R"(\b(?:RW)?ByteAddressBuffer\s+(\w+))");
  std::set<std::string> names;
  for (const auto& [file, text] : files) {
    for (auto it = std::sregex_iterator(text.begin(), text.end(), kDeclaration); it != std::sregex_iterator(); ++it)
      names.insert((*it)[1]);
  }
  return names;
}

// (RW)StructuredBuffer, Append/ConsumeStructuredBuffer, (RW)ByteAddressBuffer
// and tbuffer: storage blocks, read-only for the t# kinds.
ResourceInfo ToBufferResource(const glslang::TObjectReflection& b, Stage stage,
                              const std::set<std::string>& byteAddress) {
  using K = ResourceInfo::Kind;
  const bool readOnly = b.getType()->getQualifier().isReadOnly();
  ResourceInfo r;
  r.name = b.name;
  r.binding = static_cast<uint32_t>(b.getBinding());
  r.dimension = ResourceInfo::Dimension::Buffer;
  r.isCounter = r.name.ends_with("@count");
  if (byteAddress.count(r.name) != 0) {
    r.kind = readOnly ? K::ByteAddressBuffer : K::RWByteAddressBuffer;
  } else {
    r.kind = readOnly ? K::StructuredBuffer : K::RWStructuredBuffer;
  }
  r.registerSlot =
      RegisterSlot(stage, readOnly ? RegisterClass::ShaderResource : RegisterClass::UnorderedAccess, b.getBinding());
  return r;
}

ConstantBufferInfo ToConstantBuffer(const glslang::TObjectReflection& b, Stage stage) {
  ConstantBufferInfo cb;
  cb.name = b.name == "$Global" ? "$Globals" : b.name;  // glslang's name -> D3D's name
  cb.binding = static_cast<uint32_t>(b.getBinding());
  cb.registerSlot = RegisterSlot(stage, RegisterClass::ConstantBuffer, b.getBinding());
  cb.size = RoundUp16(static_cast<uint32_t>(b.size));
  return cb;
}

// Adds a member at its SPIR-V offset. Names that do not resolve in the SPIR-V
// (glslang also lists "lights.i" for an array of structs next to
// "lights[0].i", ...) are left out.
void AddMember(const glslang::TObjectReflection& u, const SpirvLayout& layout, ConstantBufferInfo& cb) {
  ConstantBufferMember member = ToMember(u);
  if (layout.HasBlock(static_cast<int>(cb.binding))) {
    const std::optional<uint32_t> offset = layout.Offset(static_cast<int>(cb.binding), cb.name, u.name);
    if (!offset) return;
    member.offset = *offset;
  }
  cb.members.push_back(std::move(member));
}

// D3D reports a cbuffer's size as its packed end rounded up to a register.
void FinishSize(ConstantBufferInfo& cb) {
  uint32_t end = 0;
  for (const ConstantBufferMember& m : cb.members) end = std::max(end, m.offset + m.size);
  if (!cb.members.empty()) cb.size = RoundUp16(end);
}

}  // namespace

void Reflect(const glslang::TProgram& program, Stage stage, const SourceFiles& files,
             const std::vector<uint32_t>& spirv, CompileResult& result) {
  const SpirvLayout layout(spirv);
  const int blockCount = program.getNumUniformBlocks();
  for (int i = 0; i < blockCount; ++i)
    result.constantBuffers.push_back(ToConstantBuffer(program.getUniformBlock(i), stage));
  for (int i = 0; i < program.getNumUniformVariables(); ++i) {
    const glslang::TObjectReflection& u = program.getUniform(i);
    if (u.index >= 0 && u.index < blockCount) {
      AddMember(u, layout, result.constantBuffers[u.index]);
    } else if (u.getType() && u.getType()->getBasicType() == glslang::EbtSampler) {
      result.resources.push_back(ToOpaqueResource(u, stage));
    }
  }
  for (ConstantBufferInfo& cb : result.constantBuffers) FinishSize(cb);
  const std::set<std::string> byteAddress = ByteAddressBufferNames(files);
  for (int i = 0; i < program.getNumBufferBlocks(); ++i)
    result.resources.push_back(ToBufferResource(program.getBufferBlock(i), stage, byteAddress));
}

}  // namespace hlsl::detail
