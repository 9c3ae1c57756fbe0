// Constant expressions of an effect: initializers, array sizes, state values,
// annotation values. fxc folds these at compile time; so do we.
#pragma once

#include <map>
#include <string>
#include <variant>
#include <vector>

#include "fx/preprocessor.h"

namespace fx {

struct ConstValue {
  std::vector<double> components;  // flattened: vectors, matrices (row by row), {..} lists
  bool integral = true;            // integer-typed (int/uint/bool literals): `/` truncates
};

struct ConstError {
  size_t token = 0;  // index of the offending token
  std::string message;
};

// Named constants visible to expressions (static const globals).
using ConstantTable = std::map<std::string, ConstValue, std::less<>>;

// Evaluates tokens[begin, end) as one constant expression. Supports number and
// bool literals, named constants, numeric constructors (float4(...),
// int2x2(...)), casts, { } lists (flattened), and the C operators on
// components (a scalar broadcasts against a vector).
std::variant<ConstValue, ConstError> EvaluateConstant(const std::vector<Token>& tokens, size_t begin, size_t end,
                                                      const ConstantTable& constants);

// "float3" -> (Float scalar, 3 components); also "bool", "int2x3", "min16float4", ...
// Returns false for names that are not numeric types.
struct NumericTypeName {
  std::string scalar;  // "float", "int", "uint", "bool", "double", "half", "dword", "min16float", ...
  int rows = 1;        // 1 for scalars and vectors
  int columns = 1;
  bool isMatrix = false;
};
bool ParseNumericTypeName(const std::string& name, NumericTypeName& out);

}  // namespace fx
