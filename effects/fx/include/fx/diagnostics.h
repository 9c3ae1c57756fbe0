// Source positions and errors shared by every stage of the effect front end.
#pragma once

#include <string>
#include <variant>
#include <vector>

namespace fx {

// A position in an original source file, after #include and #line resolution.
// Lines and columns are 1-based; a tab counts as one column (as in glslang).
struct SourceLocation {
  std::string file;
  int line = 0;
  int column = 0;

  bool operator==(const SourceLocation&) const = default;
};

struct ParseError {
  SourceLocation where;
  std::string message;

  // "file:line:column: message"
  std::string Format() const;
};

// The value, or every error found (at least one), in the order they were found.
template <class T>
using Result = std::variant<T, std::vector<ParseError>>;

}  // namespace fx
