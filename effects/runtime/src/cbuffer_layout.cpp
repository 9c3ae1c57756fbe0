#include "cbuffer_layout.h"

#include <algorithm>
#include <cstring>
#include <map>
#include <string>

namespace fx::detail {
namespace {

uint32_t Round16(uint32_t n) { return (n + 15) / 16 * 16; }

using MemberMap = std::map<std::string, const hlsl::ConstantBufferMember*>;

// Register-sized pieces of one non-array, non-struct element: {offset, bytes}.
std::vector<std::pair<uint32_t, uint32_t>> Pieces(const VariableType& t) {
  if (t.cls != VariableType::Class::Matrix) return {{0, t.columns * 4}};
  std::vector<std::pair<uint32_t, uint32_t>> pieces;
  const uint32_t registers = t.rowMajor ? t.rows : t.columns;
  const uint32_t perRegister = t.rowMajor ? t.columns : t.rows;
  for (uint32_t r = 0; r < registers; ++r) pieces.push_back({r * 16, perRegister * 4});
  return pieces;
}

void AddLeaf(const VariableType& t, const std::string& name, uint32_t fxOffset, const MemberMap& members,
             std::vector<CopyRange>& plan);

void AddStruct(const VariableType& t, const std::string& name, uint32_t fxOffset, const MemberMap& members,
               std::vector<CopyRange>& plan) {
  const uint32_t count = t.ElementCount();
  const uint32_t stride = Round16(t.elementSize);
  for (uint32_t i = 0; i < count; ++i) {
    // glslang's reflection flattens struct members: "s.m", "arr[1].m".
    const std::string prefix = t.arrayDims.empty() ? name : name + "[" + std::to_string(i) + "]";
    for (const StructMember& m : t.members) AddLeaf(m.type, prefix + "." + m.name, fxOffset + i * stride + m.offset,
                                                    members, plan);
  }
}

void AddLeaf(const VariableType& t, const std::string& name, uint32_t fxOffset, const MemberMap& members,
             std::vector<CopyRange>& plan) {
  if (t.cls == VariableType::Class::Struct) return AddStruct(t, name, fxOffset, members, plan);
  auto it = members.find(name);
  if (it == members.end()) return;  // not in this shader's buffer (unused or optimized out)
  const uint32_t stride = Round16(PackedElementSize(t));
  for (uint32_t i = 0; i < t.ElementCount(); ++i)
    for (auto [offset, bytes] : Pieces(t))
      plan.push_back({fxOffset + i * stride + offset, it->second->offset + i * stride + offset, bytes});
}

}  // namespace

uint32_t PackedElementSize(const VariableType& t) {
  if (t.cls == VariableType::Class::Struct) return t.elementSize;
  auto pieces = Pieces(t);
  return pieces.back().first + pieces.back().second;
}

std::vector<CopyRange> BuildCopyPlan(const ConstantBuffer& cb, const hlsl::ConstantBufferInfo& compiled) {
  MemberMap members;
  for (const auto& m : compiled.members) members[m.name] = &m;
  std::vector<CopyRange> plan;
  for (const ConstantVariable& v : cb.variables) AddLeaf(v.type, v.name, v.offset, members, plan);
  // Drop anything outside either buffer (a malformed reflection must not overrun).
  std::erase_if(plan, [&](const CopyRange& r) {
    return r.fxOffset + r.size > cb.size || r.gpuOffset + r.size > compiled.size;
  });
  return plan;
}

void ApplyCopyPlan(const std::vector<CopyRange>& plan, const std::vector<uint8_t>& fx, std::vector<uint8_t>& gpu) {
  for (const CopyRange& r : plan) std::memcpy(gpu.data() + r.gpuOffset, fx.data() + r.fxOffset, r.size);
}

}  // namespace fx::detail
