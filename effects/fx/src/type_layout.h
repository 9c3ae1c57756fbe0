// HLSL numeric types of constant-buffer variables: resolving names, packing
// them by the cbuffer rules, and writing initializer values as bytes.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "fx/effect_ast.h"

namespace fx {

// D3D11 caps a constant buffer at 4096 registers.
constexpr uint64_t kMaxConstantBufferBytes = 4096 * 16;

// Struct and typedef names seen so far.
class TypeTable {
 public:
  void Add(const std::string& name, const VariableType& type) { named_[name] = type; }

  // A numeric type name ("float3", "matrix", "bool"), a `vector`/`matrix`
  // template (templateArgs "float", "3"), or a struct or typedef name. nullopt
  // if `name` is none of these. Matrices get `rowMajor`.
  std::optional<VariableType> Resolve(const std::string& name, const std::vector<std::string>& templateArgs,
                                      bool rowMajor) const;

 private:
  std::map<std::string, VariableType> named_;
};

// Fills elementSize and size (and, for structs, member offsets) of a type
// whose members and arrayDims are set. Returns an error message when it would
// not fit in a constant buffer.
std::optional<std::string> ComputeLayout(VariableType& type);

// The offset at which a variable of `type` goes when `used` bytes are taken.
uint32_t PlaceVariable(uint32_t used, const VariableType& type);

// Writes `values` (flattened in declaration order: array elements, struct
// members, matrix rows) into `bytes` at `offset`. A single value fills every
// component of a non-array, non-struct type. Returns an error message when the
// count does not fit the type.
std::optional<std::string> WriteInitializer(const VariableType& type, const std::vector<double>& values,
                                            std::vector<uint8_t>& bytes, uint32_t offset);

}  // namespace fx
