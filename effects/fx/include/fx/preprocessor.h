// The C-style preprocessor fxc runs before parsing an effect, with a source map.
//
// Supported: #include "x" / <x> (relative to the including file, then the
// include directories; a cycle, a missing file or more than 64 nested levels is
// an error), #define object-like and function-like macros (# and ##, variadic
// __VA_ARGS__), #undef, #if/#ifdef/#ifndef/#elif/#else/#endif with integer
// expressions and defined(), #error, #line N ["file"], #pragma (kept in the
// output; #pragma once honoured), __FILE__ and __LINE__.
#pragma once

#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "fx/diagnostics.h"
#include "fx/lexer.h"

namespace fx {

struct ParseOptions {
  std::vector<std::string> includeDirs;
  // NAME, value; an empty value defines NAME as 1, like fxc's /D NAME.
  std::vector<std::pair<std::string, std::string>> defines;
  // Reads the file at a path, nullopt when there is none. Empty: the file system.
  // (Tests and tools with in-memory files substitute their own.)
  std::function<std::optional<std::string>(const std::string& path)> readFile;
};

// One token of the preprocessed output.
struct Token {
  TokenKind kind = TokenKind::Invalid;
  std::string text;  // for Pragma: what follows "#pragma", e.g. "pack_matrix(row_major)"
  // Where it was written: through #include and #line, and for a token a macro
  // body produced, the position of the macro's invocation.
  SourceLocation where;
  size_t offset = 0;       // where it starts in PreprocessedSource::text
  bool fromMacro = false;  // came out of a macro expansion
};

struct PreprocessedSource {
  // Macro-expanded text. Directive lines, skipped lines and comments become
  // blanks, so every token outside a macro expansion sits at its original
  // line and column; `#line N "file"` lines are inserted where the file (or the
  // line numbering) switches, e.g. where an include starts and ends; kept
  // #pragma lines stay on their lines. Line N of the main file before its
  // first #include is line N here.
  std::string text;
  std::vector<Token> tokens;  // every token of `text`, in order
};

Result<PreprocessedSource> Preprocess(const std::string& source, const std::string& fileName,
                                      const ParseOptions& options);

// Reads `path` with options.readFile (or from disk).
std::optional<std::string> ReadSourceFile(const std::string& path, const ParseOptions& options);

}  // namespace fx
