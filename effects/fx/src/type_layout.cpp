#include "type_layout.h"

#include <cmath>
#include <cstring>

#include "const_eval.h"

namespace fx {
namespace {

constexpr uint32_t kRegister = 16;

uint64_t AlignUp(uint64_t v, uint64_t a) { return (v + a - 1) / a * a; }

uint32_t ComponentSize(ScalarType s) { return s == ScalarType::Double ? 8 : 4; }

ScalarType ScalarOf(const std::string& scalar) {
  if (scalar == "bool") return ScalarType::Bool;
  if (scalar == "int" || scalar == "min16int" || scalar == "min12int") return ScalarType::Int;
  if (scalar == "uint" || scalar == "dword" || scalar == "min16uint") return ScalarType::UInt;
  if (scalar == "double") return ScalarType::Double;
  return ScalarType::Float;  // float, half, min16float, min10float
}

VariableType FromNumericName(const NumericTypeName& n, bool rowMajor) {
  VariableType t;
  t.scalar = ScalarOf(n.scalar);
  t.rows = static_cast<uint32_t>(n.rows);
  t.columns = static_cast<uint32_t>(n.columns);
  if (n.isMatrix) {
    t.cls = VariableType::Class::Matrix;
    t.rowMajor = rowMajor;
    t.name = n.scalar + std::to_string(n.rows) + "x" + std::to_string(n.columns);
  } else if (n.columns > 1) {
    t.cls = VariableType::Class::Vector;
    t.name = n.scalar + std::to_string(n.columns);
  } else {
    t.name = n.scalar;
  }
  return t;
}

// Number of flattened values one element of `t` takes.
uint64_t ValuesPerElement(const VariableType& t) {
  if (t.cls != VariableType::Class::Struct) return uint64_t{t.rows} * t.columns;
  uint64_t n = 0;
  for (const StructMember& m : t.members) n += ValuesPerElement(m.type) * m.type.ElementCount();
  return n;
}

void WriteScalar(ScalarType s, double v, std::vector<uint8_t>& bytes, uint64_t offset) {
  uint8_t raw[8] = {};
  size_t n = 4;
  auto clampInt = [](double d) -> int64_t {
    if (std::isnan(d)) return 0;
    return static_cast<int64_t>(std::fmax(-9.0e18, std::fmin(9.0e18, d)));
  };
  switch (s) {
    case ScalarType::Float: {
      float f = static_cast<float>(v);
      std::memcpy(raw, &f, 4);
      break;
    }
    case ScalarType::Double:
      std::memcpy(raw, &v, 8);
      n = 8;
      break;
    case ScalarType::Bool: {
      uint32_t b = v != 0 ? 0xFFFFFFFFu : 0u;
      std::memcpy(raw, &b, 4);
      break;
    }
    case ScalarType::Int:
    case ScalarType::UInt: {
      uint32_t i = static_cast<uint32_t>(static_cast<uint64_t>(clampInt(v)));
      std::memcpy(raw, &i, 4);
      break;
    }
  }
  if (offset + n <= bytes.size()) std::memcpy(bytes.data() + offset, raw, n);
}

void WriteElement(const VariableType& t, const std::vector<double>& values, size_t& next,
                  std::vector<uint8_t>& bytes, uint64_t offset);

void WriteVariable(const VariableType& t, const std::vector<double>& values, size_t& next,
                   std::vector<uint8_t>& bytes, uint64_t offset) {
  uint64_t stride = AlignUp(t.elementSize, kRegister);
  for (uint32_t e = 0; e < t.ElementCount(); ++e) WriteElement(t, values, next, bytes, offset + e * stride);
}

void WriteElement(const VariableType& t, const std::vector<double>& values, size_t& next,
                  std::vector<uint8_t>& bytes, uint64_t offset) {
  uint32_t cs = ComponentSize(t.scalar);
  switch (t.cls) {
    case VariableType::Class::Struct:
      for (const StructMember& m : t.members) WriteVariable(m.type, values, next, bytes, offset + m.offset);
      return;
    case VariableType::Class::Matrix:
      // Values come row by row (_11 _12 ...); column_major stores a column per register.
      for (uint32_t r = 0; r < t.rows; ++r) {
        for (uint32_t c = 0; c < t.columns; ++c) {
          uint64_t at = t.rowMajor ? r * kRegister + c * cs : c * kRegister + r * cs;
          WriteScalar(t.scalar, values[next++], bytes, offset + at);
        }
      }
      return;
    default:
      for (uint32_t c = 0; c < t.columns; ++c) WriteScalar(t.scalar, values[next++], bytes, offset + c * cs);
      return;
  }
}

}  // namespace

std::optional<VariableType> TypeTable::Resolve(const std::string& name, const std::vector<std::string>& templateArgs,
                                               bool rowMajor) const {
  NumericTypeName n;
  if ((name == "vector" || name == "matrix") && !templateArgs.empty()) {
    bool vector = name == "vector";
    if (templateArgs.size() != (vector ? 2u : 3u) || !ParseNumericTypeName(templateArgs[0], n) || n.columns != 1) {
      return std::nullopt;
    }
    auto dim = [](const std::string& s) { return s.size() == 1 && s[0] >= '1' && s[0] <= '4' ? s[0] - '0' : 0; };
    n.rows = vector ? 1 : dim(templateArgs[1]);
    n.columns = dim(templateArgs[vector ? 1 : 2]);
    n.isMatrix = !vector;
    if (n.rows == 0 || n.columns == 0) return std::nullopt;
    return FromNumericName(n, rowMajor);
  }
  if (!templateArgs.empty()) return std::nullopt;
  if (name == "vector") return FromNumericName(NumericTypeName{"float", 1, 4, false}, rowMajor);
  if (name == "matrix") return FromNumericName(NumericTypeName{"float", 4, 4, true}, rowMajor);
  if (ParseNumericTypeName(name, n)) return FromNumericName(n, rowMajor);
  auto it = named_.find(name);
  if (it == named_.end()) return std::nullopt;
  return it->second;
}

std::optional<std::string> ComputeLayout(VariableType& t) {
  uint32_t cs = ComponentSize(t.scalar);
  uint64_t element = 0;
  switch (t.cls) {
    case VariableType::Class::Scalar:
      element = cs;
      break;
    case VariableType::Class::Vector:
      element = uint64_t{t.columns} * cs;
      break;
    case VariableType::Class::Matrix: {
      uint32_t registers = t.rowMajor ? t.rows : t.columns;
      uint32_t perRegister = t.rowMajor ? t.columns : t.rows;
      element = uint64_t{registers - 1} * kRegister + uint64_t{perRegister} * cs;
      break;
    }
    case VariableType::Class::Struct: {
      uint32_t used = 0;
      for (StructMember& m : t.members) {
        m.offset = PlaceVariable(used, m.type);
        used = m.offset + m.type.size;
      }
      element = used;
      break;
    }
  }
  uint64_t count = 1;
  for (uint32_t d : t.arrayDims) {
    count *= d;
    if (count > kMaxConstantBufferBytes) return "array too large for a constant buffer";
  }
  uint64_t size = count == 0 ? 0 : (count - 1) * AlignUp(element, kRegister) + element;
  if (size > kMaxConstantBufferBytes) return "'" + t.name + "' is too large for a constant buffer (64 KB)";
  t.elementSize = static_cast<uint32_t>(element);
  t.size = static_cast<uint32_t>(size);
  return std::nullopt;
}

uint32_t PlaceVariable(uint32_t used, const VariableType& t) {
  // As fxc: arrays and structs start a register; anything else (matrices too)
  // moves to the next register only when it would straddle one.
  bool newRegister = !t.arrayDims.empty() || t.cls == VariableType::Class::Struct;
  uint64_t offset = AlignUp(used, ComponentSize(t.scalar));
  if (newRegister || offset % kRegister + t.size > kRegister) offset = AlignUp(offset, kRegister);
  return static_cast<uint32_t>(offset);
}

std::optional<std::string> WriteInitializer(const VariableType& type, const std::vector<double>& values,
                                            std::vector<uint8_t>& bytes, uint32_t offset) {
  uint64_t expected = ValuesPerElement(type) * type.ElementCount();
  bool splat = values.size() == 1 && type.arrayDims.empty() && type.cls != VariableType::Class::Struct;
  if (values.size() != expected && !splat) {
    return "initializer has " + std::to_string(values.size()) + " values, '" + type.name + "' needs " +
           std::to_string(expected);
  }
  std::vector<double> all = splat ? std::vector<double>(expected, values[0]) : values;
  size_t next = 0;
  WriteVariable(type, all, next, bytes, offset);
  return std::nullopt;
}

}  // namespace fx
