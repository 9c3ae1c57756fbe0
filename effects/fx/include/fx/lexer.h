// Splits HLSL / FX source into preprocessing tokens.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace fx {

enum class TokenKind {
  Identifier,
  Number,       // a pp-number: 1, 0x0F, 1.5f, 1e-3, .5h
  String,       // "text", spelled with its quotes
  CharLiteral,  // 'c', spelled with its quotes
  Punctuator,   // { } ( ) ++ <<= ## ...
  Pragma,       // only in preprocessor output: a kept `#pragma` line
  Invalid,      // a byte that starts no token, or an unterminated literal
};

// A token of one file, at its physical position (before any #line).
struct LexToken {
  TokenKind kind = TokenKind::Invalid;
  std::string text;  // spelling, line continuations removed
  int line = 0;
  int column = 0;
  bool startOfLine = false;   // first token of its line: a '#' here starts a directive
  bool leadingSpace = false;  // whitespace or a comment precedes it
};

struct LexError {
  int line = 0;
  int column = 0;
  std::string message;
};

// Never fails on any input: bytes that start no token become Invalid tokens,
// reported by whoever uses them (so junk in #if 0 blocks is harmless); only an
// unterminated block comment lands in `errors`. Comments count as whitespace.
std::vector<LexToken> Lex(std::string_view source, std::vector<LexError>& errors);

bool IsIdentifierStart(char c);
bool IsIdentifierChar(char c);

}  // namespace fx
