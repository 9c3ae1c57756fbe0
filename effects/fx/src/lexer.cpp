#include "fx/lexer.h"

#include <array>

namespace fx {

bool IsIdentifierStart(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_';
}

bool IsIdentifierChar(char c) { return IsIdentifierStart(c) || (c >= '0' && c <= '9'); }

namespace {

bool IsDigit(char c) { return c >= '0' && c <= '9'; }

// Longest first, so that the first match is the longest punctuator.
constexpr std::array<std::string_view, 24> kMultiCharPunctuators = {
    "<<=", ">>=", "...", "##", "::", "->", "++", "--", "<<", ">>", "<=", ">=",
    "==",  "!=",  "&&",  "||", "+=", "-=", "*=", "/=", "%=", "&=", "|=", "^="};
constexpr std::string_view kSingleCharPunctuators = "{}[]()<>;:,.?~!+-*/%^&|=#";

// Reads characters with line continuations (backslash-newline) spliced out,
// keeping the physical line and column of every character.
class CharReader {
 public:
  explicit CharReader(std::string_view s) : s_(s) { SkipContinuations(); }

  bool AtEnd() const { return pos_ >= s_.size(); }
  char Peek(size_t ahead = 0) const {
    size_t p = pos_;
    for (size_t i = 0; i < ahead && p < s_.size(); ++i) p = After(p);
    return p < s_.size() ? s_[p] : '\0';
  }
  void Advance() {
    if (AtEnd()) return;
    if (s_[pos_] == '\n') {
      ++line_;
      column_ = 1;
    } else {
      ++column_;
    }
    ++pos_;
    SkipContinuations();
  }
  int line() const { return line_; }
  int column() const { return column_; }

 private:
  // Position of the character after p, skipping continuations.
  size_t After(size_t p) const {
    ++p;
    while (true) {
      size_t n = ContinuationLength(p);
      if (n == 0) return p;
      p += n;
    }
  }
  size_t ContinuationLength(size_t p) const {
    if (p >= s_.size() || s_[p] != '\\') return 0;
    if (p + 1 < s_.size() && s_[p + 1] == '\n') return 2;
    if (p + 2 < s_.size() && s_[p + 1] == '\r' && s_[p + 2] == '\n') return 3;
    return 0;
  }
  void SkipContinuations() {
    while (size_t n = ContinuationLength(pos_)) {
      pos_ += n;
      ++line_;
      column_ = 1;
    }
  }

  std::string_view s_;
  size_t pos_ = 0;
  int line_ = 1;
  int column_ = 1;
};

class Lexer {
 public:
  Lexer(std::string_view source, std::vector<LexError>& errors) : in_(source), errors_(errors) {}

  std::vector<LexToken> Run() {
    std::vector<LexToken> tokens;
    bool startOfLine = true;
    bool space = false;
    while (true) {
      SkipWhitespaceAndComments(startOfLine, space);
      if (in_.AtEnd()) break;
      LexToken t;
      t.line = in_.line();
      t.column = in_.column();
      t.startOfLine = startOfLine;
      t.leadingSpace = space;
      ReadToken(t);
      tokens.push_back(std::move(t));
      startOfLine = false;
      space = false;
    }
    return tokens;
  }

 private:
  void SkipWhitespaceAndComments(bool& startOfLine, bool& space) {
    while (!in_.AtEnd()) {
      char c = in_.Peek();
      if (c == '\n') {
        startOfLine = true;
        space = true;
        in_.Advance();
      } else if (c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f') {
        space = true;
        in_.Advance();
      } else if (c == '/' && in_.Peek(1) == '/') {
        while (!in_.AtEnd() && in_.Peek() != '\n') in_.Advance();
        space = true;
      } else if (c == '/' && in_.Peek(1) == '*') {
        SkipBlockComment();
        space = true;
      } else {
        return;
      }
    }
  }

  void SkipBlockComment() {
    int line = in_.line(), column = in_.column();
    in_.Advance();
    in_.Advance();
    while (!in_.AtEnd()) {
      if (in_.Peek() == '*' && in_.Peek(1) == '/') {
        in_.Advance();
        in_.Advance();
        return;
      }
      in_.Advance();
    }
    errors_.push_back({line, column, "unterminated comment"});
  }

  void Take(LexToken& t) {
    t.text.push_back(in_.Peek());
    in_.Advance();
  }

  void ReadToken(LexToken& t) {
    char c = in_.Peek();
    if (IsIdentifierStart(c)) {
      t.kind = TokenKind::Identifier;
      while (!in_.AtEnd() && IsIdentifierChar(in_.Peek())) Take(t);
    } else if (IsDigit(c) || (c == '.' && IsDigit(in_.Peek(1)))) {
      ReadNumber(t);
    } else if (c == '"' || c == '\'') {
      ReadQuoted(t, c);
    } else {
      ReadPunctuator(t);
    }
  }

  // pp-number: digits, letters, '_', '.', and a sign right after an exponent.
  void ReadNumber(LexToken& t) {
    t.kind = TokenKind::Number;
    while (!in_.AtEnd()) {
      char c = in_.Peek();
      char prev = t.text.empty() ? '\0' : t.text.back();
      bool exponentSign = (c == '+' || c == '-') && (prev == 'e' || prev == 'E') &&
                          !(t.text.size() > 1 && (t.text[1] == 'x' || t.text[1] == 'X'));
      if (IsIdentifierChar(c) || c == '.' || exponentSign) {
        Take(t);
      } else {
        break;
      }
    }
  }

  // A literal may not cross a line; without its closing quote it is Invalid.
  void ReadQuoted(LexToken& t, char quote) {
    t.kind = quote == '"' ? TokenKind::String : TokenKind::CharLiteral;
    Take(t);
    while (!in_.AtEnd() && in_.Peek() != '\n') {
      char c = in_.Peek();
      Take(t);
      if (c == '\\' && !in_.AtEnd() && in_.Peek() != '\n') {
        Take(t);
      } else if (c == quote) {
        return;
      }
    }
    t.kind = TokenKind::Invalid;
  }

  void ReadPunctuator(LexToken& t) {
    t.kind = TokenKind::Punctuator;
    for (std::string_view p : kMultiCharPunctuators) {
      bool match = true;
      for (size_t i = 0; i < p.size() && match; ++i) match = in_.Peek(i) == p[i];
      if (match) {
        for (size_t i = 0; i < p.size(); ++i) Take(t);
        return;
      }
    }
    if (kSingleCharPunctuators.find(in_.Peek()) == std::string_view::npos) {
      t.kind = TokenKind::Invalid;
    }
    Take(t);
  }

  CharReader in_;
  std::vector<LexError>& errors_;
};

}  // namespace

std::vector<LexToken> Lex(std::string_view source, std::vector<LexError>& errors) {
  return Lexer(source, errors).Run();
}

}  // namespace fx
