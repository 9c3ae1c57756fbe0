#include "fx/diagnostics.h"

namespace fx {

std::string ParseError::Format() const {
  return where.file + ":" + std::to_string(where.line) + ":" + std::to_string(where.column) + ": " +
         message;
}

}  // namespace fx
