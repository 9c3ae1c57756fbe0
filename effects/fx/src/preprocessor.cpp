#include "fx/preprocessor.h"

#include <algorithm>
#include <cstdint>
#include <deque>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <set>
#include <sstream>
#include <unordered_map>

namespace fx {
namespace {

// Limits that keep hostile input from hanging or exhausting the process.
constexpr size_t kMaxIncludeDepth = 64;
constexpr int kMaxIncludedFiles = 4096;
constexpr size_t kMaxMacroTokens = 500'000;  // tokens all macro expansions may produce
constexpr int kMaxArgumentNesting = 64;         // macro arguments expanded inside arguments
constexpr int kMaxExpressionDepth = 256;        // #if expression nesting
constexpr size_t kMaxErrors = 50;
// A jump of more lines than this is written as a #line directive, not blank lines.
constexpr int kMaxBlankLines = 32;

struct Location {
  const std::string* file = nullptr;
  int line = 0;
  int column = 0;
};

SourceLocation ToSourceLocation(const Location& l) {
  return SourceLocation{l.file ? *l.file : std::string(), l.line, l.column};
}

// A token on its way through macro expansion.
struct PPToken {
  TokenKind kind = TokenKind::Invalid;
  std::string text;
  Location loc;
  bool leadingSpace = false;
  bool fromMacro = false;
  bool noExpand = false;     // named a macro inside that macro's own expansion: stays as is
  std::vector<int> hideSet;  // sorted ids of the macros whose expansion produced it
};

bool IsPunct(const PPToken& t, std::string_view p) {
  return t.kind == TokenKind::Punctuator && t.text == p;
}

struct Macro {
  int id = 0;
  bool functionLike = false;
  bool variadic = false;
  std::vector<std::string> params;  // a variadic macro's last parameter is __VA_ARGS__
  std::vector<PPToken> body;
};

// Pending tokens first (macro results are rescanned from here), then whatever
// the concrete source reads.
class TokenSource {
 public:
  virtual ~TokenSource() = default;
  virtual bool Next(PPToken& t) = 0;
  void PushFront(std::vector<PPToken>&& tokens) {
    pending_.insert(pending_.begin(), std::make_move_iterator(tokens.begin()),
                    std::make_move_iterator(tokens.end()));
  }

 protected:
  bool PopPending(PPToken& t) {
    if (pending_.empty()) return false;
    t = std::move(pending_.front());
    pending_.pop_front();
    return true;
  }

 private:
  std::deque<PPToken> pending_;
};

class ListSource : public TokenSource {
 public:
  explicit ListSource(std::vector<PPToken> tokens) { PushFront(std::move(tokens)); }
  bool Next(PPToken& t) override { return PopPending(t); }
};

bool IsWordChar(char c) { return IsIdentifierChar(c) || c == '.'; }

// Builds the output text. Tokens that came straight from a file go to their
// original line and column (blank lines and spaces fill the gaps, a #line
// directive where that is impossible); macro output follows the previous token.
class OutputWriter {
 public:
  explicit OutputWriter(const std::string* mainFile) : file_(mainFile) {}

  size_t Write(const PPToken& t) {
    if (!t.fromMacro) {
      MoveToLine(t.loc);
      if (column_ < t.loc.column) {
        Append(std::string(t.loc.column - column_, ' '));
      } else if (column_ > 1 && column_ > t.loc.column) {
        Append(" ");  // a macro expansion before it on this line ran past its column
      }
    } else if (column_ > 1 && (t.leadingSpace || NeedsSpace(t.text))) {
      Append(" ");
    }
    size_t offset = text_.size();
    Append(t.text);
    return offset;
  }

  // A kept `#pragma` line, on the pragma's own line.
  size_t WritePragma(const Location& loc, const std::string& body) {
    MoveToLine(loc);
    if (column_ > 1) LineDirective(loc);
    size_t offset = text_.size();
    Append("#pragma " + body);
    return offset;
  }

  std::string Take() { return std::move(text_); }

 private:
  void MoveToLine(const Location& loc) {
    if (loc.file != file_ || loc.line < line_ || loc.line - line_ > kMaxBlankLines) {
      LineDirective(loc);
    }
    while (line_ < loc.line) {
      text_ += '\n';
      ++line_;
      column_ = 1;
    }
  }

  void LineDirective(const Location& loc) {
    if (column_ > 1) text_ += '\n';
    text_ += "#line " + std::to_string(loc.line) + " \"";
    for (char c : *loc.file) {
      if (c == '"' || c == '\\') text_ += '\\';
      text_ += c;
    }
    text_ += "\"\n";
    file_ = loc.file;
    line_ = loc.line;
    column_ = 1;
  }

  // Whether writing `next` right after the previous text would glue two tokens.
  bool NeedsSpace(const std::string& next) const {
    if (text_.empty() || next.empty()) return false;
    char a = text_.back(), b = next.front();
    if (IsWordChar(a) && IsWordChar(b)) return true;
    return !IsWordChar(a) && !IsWordChar(b) && a != ' ' && a != '(' && b != ')' && b != ',' &&
           b != ';' && b != '(';
  }

  void Append(const std::string& s) {
    text_ += s;
    column_ += static_cast<int>(s.size());
  }

  std::string text_;
  const std::string* file_;
  int line_ = 1;
  int column_ = 1;
};

// Integer expressions of #if / #elif, on already macro-expanded tokens.
class ConditionEvaluator {
 public:
  explicit ConditionEvaluator(const std::vector<PPToken>& tokens) : t_(tokens) {}

  // nullopt with `error` set when the expression is malformed.
  std::optional<int64_t> Evaluate(std::string& error) {
    if (t_.empty()) {
      error = "#if with no expression";
      return std::nullopt;
    }
    int64_t v = Ternary(0);
    if (error_.empty() && pos_ < t_.size()) Fail("unexpected '" + t_[pos_].text + "' in #if expression");
    if (!error_.empty()) {
      error = error_;
      return std::nullopt;
    }
    return v;
  }

 private:
  void Fail(const std::string& message) {
    if (error_.empty()) error_ = message;
  }
  bool Accept(std::string_view p) {
    if (pos_ < t_.size() && IsPunct(t_[pos_], p)) {
      ++pos_;
      return true;
    }
    return false;
  }

  int64_t Ternary(int depth) {
    int64_t c = Binary(0, depth);
    if (!Accept("?")) return c;
    int64_t a = Ternary(depth + 1);
    if (!Accept(":")) Fail("expected ':' in #if expression");
    int64_t b = Ternary(depth + 1);
    return c ? a : b;
  }

  static int Precedence(const std::string& op) {
    static const std::map<std::string, int, std::less<>> kPrecedence = {
        {"||", 1}, {"&&", 2}, {"|", 3},  {"^", 4},  {"&", 5},  {"==", 6}, {"!=", 6},
        {"<", 7},  {">", 7},  {"<=", 7}, {">=", 7}, {"<<", 8}, {">>", 8}, {"+", 9},
        {"-", 9},  {"*", 10}, {"/", 10}, {"%", 10}};
    auto it = kPrecedence.find(op);
    return it == kPrecedence.end() ? 0 : it->second;
  }

  int64_t Binary(int minPrecedence, int depth) {
    int64_t lhs = Unary(depth + 1);
    while (error_.empty() && pos_ < t_.size() && t_[pos_].kind == TokenKind::Punctuator) {
      std::string op = t_[pos_].text;
      int p = Precedence(op);
      if (p == 0 || p <= minPrecedence) break;
      ++pos_;
      int64_t rhs = Binary(p, depth + 1);
      lhs = Apply(op, lhs, rhs);
    }
    return lhs;
  }

  // Arithmetic on uint64 wraps instead of overflowing (undefined in int64).
  int64_t Apply(const std::string& op, int64_t a, int64_t b) {
    uint64_t ua = static_cast<uint64_t>(a), ub = static_cast<uint64_t>(b);
    if (op == "||") return a || b;
    if (op == "&&") return a && b;
    if (op == "|") return static_cast<int64_t>(ua | ub);
    if (op == "^") return static_cast<int64_t>(ua ^ ub);
    if (op == "&") return static_cast<int64_t>(ua & ub);
    if (op == "==") return a == b;
    if (op == "!=") return a != b;
    if (op == "<") return a < b;
    if (op == ">") return a > b;
    if (op == "<=") return a <= b;
    if (op == ">=") return a >= b;
    if (op == "<<") return static_cast<int64_t>(ua << (ub & 63));
    if (op == ">>") return a >> (ub & 63);
    if (op == "+") return static_cast<int64_t>(ua + ub);
    if (op == "-") return static_cast<int64_t>(ua - ub);
    if (op == "*") return static_cast<int64_t>(ua * ub);
    if (b == 0) {
      Fail("division by zero in #if expression");
      return 0;
    }
    if (a == INT64_MIN && b == -1) return op == "/" ? a : 0;
    return op == "/" ? a / b : a % b;
  }

  int64_t Unary(int depth) {
    if (depth > kMaxExpressionDepth) {
      Fail("#if expression nested too deeply");
      return 0;
    }
    if (pos_ >= t_.size()) {
      Fail("#if expression ends unexpectedly");
      return 0;
    }
    if (Accept("-")) return static_cast<int64_t>(0 - static_cast<uint64_t>(Unary(depth + 1)));
    if (Accept("+")) return Unary(depth + 1);
    if (Accept("!")) return !Unary(depth + 1);
    if (Accept("~")) return ~Unary(depth + 1);
    if (Accept("(")) {
      int64_t v = Ternary(depth + 1);
      if (!Accept(")")) Fail("expected ')' in #if expression");
      return v;
    }
    const PPToken& t = t_[pos_++];
    if (t.kind == TokenKind::Identifier) return t.text == "true" ? 1 : 0;  // undefined names are 0
    if (t.kind == TokenKind::Number) return Number(t.text);
    Fail("unexpected '" + t.text + "' in #if expression");
    return 0;
  }

  int64_t Number(const std::string& s) {
    size_t end = s.size();
    while (end > 0 && (s[end - 1] == 'u' || s[end - 1] == 'U' || s[end - 1] == 'l' || s[end - 1] == 'L')) {
      --end;
    }
    std::string digits = s.substr(0, end);
    int base = 10;
    size_t start = 0;
    if (digits.size() > 2 && digits[0] == '0' && (digits[1] == 'x' || digits[1] == 'X')) {
      base = 16;
      start = 2;
    } else if (digits.size() > 1 && digits[0] == '0') {
      base = 8;
      start = 1;
    }
    uint64_t v = 0;
    for (size_t i = start; i < digits.size(); ++i) {
      char c = digits[i];
      int d = c >= '0' && c <= '9'   ? c - '0'
              : c >= 'a' && c <= 'f' ? c - 'a' + 10
              : c >= 'A' && c <= 'F' ? c - 'A' + 10
                                     : 99;
      if (d >= base) {
        Fail("invalid integer constant '" + s + "' in #if expression");
        return 0;
      }
      v = v * static_cast<uint64_t>(base) + static_cast<uint64_t>(d);
    }
    return static_cast<int64_t>(v);
  }

  const std::vector<PPToken>& t_;
  size_t pos_ = 0;
  std::string error_;
};

std::string JoinSpelling(const std::vector<PPToken>& tokens) {
  std::string s;
  for (const PPToken& t : tokens) {
    if (!s.empty() && t.leadingSpace) s += ' ';
    s += t.text;
  }
  return s;
}

std::string Unquote(const std::string& literal) {
  if (literal.size() >= 2) return literal.substr(1, literal.size() - 2);
  return literal;
}

class Preprocessor {
 public:
  explicit Preprocessor(const ParseOptions& options) : options_(options) {}

  Result<PreprocessedSource> Run(const std::string& source, const std::string& fileName) {
    const std::string* mainName = Intern(fileName);
    writer_ = std::make_unique<OutputWriter>(mainName);
    DefineFromOptions();
    PushFile(fileName, mainName, source);
    FileSource files(*this);
    PPToken t;
    while (!Failed() && NextExpanded(files, t)) Emit(t);
    if (!errors_.empty()) return errors_;
    out_.text = writer_->Take();
    if (!out_.text.empty() && out_.text.back() != '\n') out_.text += '\n';
    return std::move(out_);
  }

 private:
  // Tokens read from the include stack, with directives executed on the way.
  class FileSource : public TokenSource {
   public:
    explicit FileSource(Preprocessor& pp) : pp_(pp) {}
    bool Next(PPToken& t) override { return PopPending(t) || pp_.ReadFromFiles(t); }

   private:
    Preprocessor& pp_;
  };

  struct FileState {
    std::string path;  // for #include lookups relative to this file
    const std::string* name = nullptr;  // the name positions carry (#line may change it)
    std::vector<LexToken> tokens;
    size_t pos = 0;
    int lineDelta = 0;  // #line: logical line = physical line + lineDelta
    size_t conditionalDepth = 0;  // conditionals_.size() when the file was entered
  };

  struct Conditional {
    bool active = false;        // this branch's lines are compiled
    bool taken = false;         // some branch of this #if was (or can no longer be) chosen
    bool seenElse = false;
    bool parentActive = false;  // the enclosing region is compiled
    Location where;
  };

  // ---- errors ----

  void Error(const Location& where, const std::string& message) {
    if (errors_.size() < kMaxErrors) errors_.push_back({ToSourceLocation(where), message});
  }
  bool Failed() const { return fatal_ || errors_.size() >= kMaxErrors; }

  const std::string* Intern(const std::string& name) {
    auto it = names_.find(name);
    if (it != names_.end()) return it->second.get();
    auto stored = std::make_unique<std::string>(name);
    const std::string* p = stored.get();
    names_.emplace(name, std::move(stored));
    return p;
  }

  // ---- files ----

  void PushFile(const std::string& path, const std::string* name, const std::string& source) {
    std::vector<LexError> lexErrors;
    FileState f;
    f.path = path;
    f.name = name;
    f.tokens = Lex(source, lexErrors);
    f.conditionalDepth = conditionals_.size();
    for (const LexError& e : lexErrors) Error({name, e.line, e.column}, e.message);
    files_.push_back(std::move(f));
  }

  void PopFile() {
    FileState& f = files_.back();
    if (conditionals_.size() > f.conditionalDepth) {
      Error(conditionals_.back().where, "unterminated conditional directive");
      conditionals_.resize(f.conditionalDepth);
    }
    files_.pop_back();
  }

  Location LocationOf(const FileState& f, const LexToken& t) const {
    return Location{f.name, t.line + f.lineDelta, t.column};
  }

  PPToken ToPP(const FileState& f, const LexToken& t) const {
    PPToken p;
    p.kind = t.kind;
    p.text = t.text;
    p.loc = LocationOf(f, t);
    p.leadingSpace = t.leadingSpace;
    return p;
  }

  bool Active() const { return conditionals_.empty() || conditionals_.back().active; }

  // The next token of the current file stack that is compiled; executes directives.
  bool ReadFromFiles(PPToken& t) {
    while (!files_.empty() && !Failed()) {
      FileState& f = files_.back();
      if (f.pos >= f.tokens.size()) {
        PopFile();
        continue;
      }
      const LexToken& lt = f.tokens[f.pos];
      if (lt.startOfLine && lt.kind == TokenKind::Punctuator && lt.text == "#") {
        if (Directive(t)) return true;  // a kept #pragma
        continue;
      }
      ++f.pos;
      if (!Active()) continue;
      t = ToPP(f, lt);
      return true;
    }
    return false;
  }

  // ---- directives ----

  // Consumes one directive line. Returns true when it produced a token (#pragma).
  bool Directive(PPToken& pragma) {
    FileState& f = files_.back();
    Location hashLoc = LocationOf(f, f.tokens[f.pos]);
    std::vector<PPToken> line;
    int lastLine = f.tokens[f.pos].line;
    for (++f.pos; f.pos < f.tokens.size() && !f.tokens[f.pos].startOfLine; ++f.pos) {
      line.push_back(ToPP(f, f.tokens[f.pos]));
      lastLine = f.tokens[f.pos].line;
    }
    if (line.empty()) return false;  // the null directive
    const std::string name = line[0].kind == TokenKind::Identifier ? line[0].text : std::string();
    if (ConditionalDirective(name, line, hashLoc)) return false;
    if (!Active()) return false;
    std::vector<PPToken> args(line.begin() + 1, line.end());
    if (name == "define") {
      Define(args, hashLoc);
    } else if (name == "undef") {
      if (args.empty() || args[0].kind != TokenKind::Identifier) {
        Error(hashLoc, "#undef needs a macro name");
      } else {
        macros_.erase(args[0].text);
      }
    } else if (name == "include") {
      Include(args, hashLoc);
    } else if (name == "error") {
      Error(hashLoc, "#error " + JoinSpelling(args));
    } else if (name == "line") {
      LineDirective(args, hashLoc, lastLine);
    } else if (name == "pragma") {
      if (!args.empty() && args[0].text == "once") {
        onceFiles_.insert(files_.back().path);
        return false;
      }
      pragma = PPToken{};
      pragma.kind = TokenKind::Pragma;
      pragma.text = JoinSpelling(args);
      pragma.loc = hashLoc;
      return true;
    } else {
      Error(line[0].loc, "unknown preprocessor directive '#" + line[0].text + "'");
    }
    return false;
  }

  // #if family; these run in skipped regions too, to keep the nesting right.
  bool ConditionalDirective(const std::string& name, const std::vector<PPToken>& line,
                            const Location& where) {
    std::vector<PPToken> args(line.begin() + 1, line.end());
    if (name == "if" || name == "ifdef" || name == "ifndef") {
      Conditional c;
      c.where = where;
      c.parentActive = Active();
      if (c.parentActive) {
        bool value = name == "if" ? EvaluateCondition(args, where) : IsDefinedTest(args, where, name);
        c.active = value;
        c.taken = value;
      } else {
        c.taken = true;  // no branch of a skipped #if is ever compiled
      }
      conditionals_.push_back(c);
      return true;
    }
    if (name != "elif" && name != "else" && name != "endif") return false;
    if (conditionals_.size() <= files_.back().conditionalDepth) {
      Error(where, "#" + name + " without #if");
      return true;
    }
    Conditional& c = conditionals_.back();
    if (name == "endif") {
      conditionals_.pop_back();
    } else if (c.seenElse) {
      Error(where, "#" + name + " after #else");
    } else if (name == "else") {
      c.seenElse = true;
      c.active = c.parentActive && !c.taken;
      c.taken = true;
    } else if (!c.parentActive || c.taken) {
      c.active = false;
    } else {
      c.active = EvaluateCondition(args, where);
      c.taken = c.active;
    }
    return true;
  }

  bool IsDefinedTest(const std::vector<PPToken>& args, const Location& where, const std::string& name) {
    if (args.empty() || args[0].kind != TokenKind::Identifier) {
      Error(where, "#" + name + " needs a macro name");
      return false;
    }
    bool defined = IsDefined(args[0].text);
    return name == "ifdef" ? defined : !defined;
  }

  bool IsDefined(const std::string& name) const {
    return macros_.count(name) != 0 || name == "__LINE__" || name == "__FILE__";
  }

  bool EvaluateCondition(const std::vector<PPToken>& args, const Location& where) {
    // `defined X` must be resolved before expansion would replace X.
    std::vector<PPToken> resolved;
    for (size_t i = 0; i < args.size(); ++i) {
      if (args[i].kind != TokenKind::Identifier || args[i].text != "defined") {
        resolved.push_back(args[i]);
        continue;
      }
      bool paren = i + 1 < args.size() && IsPunct(args[i + 1], "(");
      size_t nameIndex = i + (paren ? 2 : 1);
      if (nameIndex >= args.size() || args[nameIndex].kind != TokenKind::Identifier ||
          (paren && (nameIndex + 1 >= args.size() || !IsPunct(args[nameIndex + 1], ")")))) {
        Error(args[i].loc, "'defined' needs a macro name");
        return false;
      }
      PPToken value = args[i];
      value.kind = TokenKind::Number;
      value.text = IsDefined(args[nameIndex].text) ? "1" : "0";
      resolved.push_back(value);
      i = nameIndex + (paren ? 1 : 0);
    }
    std::vector<PPToken> expanded = ExpandList(std::move(resolved));
    std::string error;
    std::optional<int64_t> v = ConditionEvaluator(expanded).Evaluate(error);
    if (!v) {
      Error(where, error);
      return false;
    }
    return *v != 0;
  }

  void Define(const std::vector<PPToken>& args, const Location& where) {
    if (args.empty() || args[0].kind != TokenKind::Identifier) {
      Error(where, "#define needs a macro name");
      return;
    }
    const std::string& name = args[0].text;
    if (name == "defined") {
      Error(args[0].loc, "'defined' cannot be a macro name");
      return;
    }
    auto m = std::make_shared<Macro>();
    m->id = nextMacroId_++;
    size_t i = 1;
    if (i < args.size() && IsPunct(args[i], "(") && !args[i].leadingSpace) {
      m->functionLike = true;
      if (!ParseParameters(args, i, *m)) return;
    }
    m->body.assign(args.begin() + static_cast<std::ptrdiff_t>(i), args.end());
    if (!m->body.empty()) m->body.front().leadingSpace = false;
    if (!ValidateBody(*m, name)) return;
    macros_[name] = std::move(m);
  }

  // `i` is at '('; leaves it after ')'.
  bool ParseParameters(const std::vector<PPToken>& args, size_t& i, Macro& m) {
    ++i;
    if (i < args.size() && IsPunct(args[i], ")")) {
      ++i;
      return true;
    }
    while (i < args.size()) {
      if (IsPunct(args[i], "...")) {
        m.variadic = true;
        m.params.push_back("__VA_ARGS__");
        ++i;
      } else if (args[i].kind == TokenKind::Identifier &&
                 std::find(m.params.begin(), m.params.end(), args[i].text) == m.params.end()) {
        m.params.push_back(args[i++].text);
      } else {
        break;
      }
      if (i < args.size() && IsPunct(args[i], ")")) {
        ++i;
        return true;
      }
      if (m.variadic || i >= args.size() || !IsPunct(args[i], ",")) break;
      ++i;
    }
    Error(i < args.size() ? args[i].loc : args[0].loc, "invalid macro parameter list");
    return false;
  }

  int ParamIndex(const Macro& m, const PPToken& t) const {
    if (!m.functionLike || t.kind != TokenKind::Identifier) return -1;
    for (size_t i = 0; i < m.params.size(); ++i) {
      if (m.params[i] == t.text) return static_cast<int>(i);
    }
    return -1;
  }

  bool ValidateBody(const Macro& m, const std::string& name) {
    const auto& b = m.body;
    if (!b.empty() && (IsPunct(b.front(), "##") || IsPunct(b.back(), "##"))) {
      Error(b.front().loc, "'##' cannot be at either end of macro '" + name + "'");
      return false;
    }
    for (size_t i = 0; m.functionLike && i < b.size(); ++i) {
      if (IsPunct(b[i], "#") && (i + 1 >= b.size() || ParamIndex(m, b[i + 1]) < 0)) {
        Error(b[i].loc, "'#' is not followed by a macro parameter");
        return false;
      }
    }
    return true;
  }

  void DefineFromOptions() {
    const std::string* where = Intern("<command line>");
    for (const auto& [name, value] : options_.defines) {
      std::vector<LexError> lexErrors;
      std::vector<LexToken> lexed = Lex(name + " " + (value.empty() ? "1" : value), lexErrors);
      std::vector<PPToken> args;
      for (const LexToken& t : lexed) {
        PPToken p;
        p.kind = t.kind;
        p.text = t.text;
        p.loc = Location{where, 1, t.column};
        p.leadingSpace = t.leadingSpace;
        args.push_back(std::move(p));
      }
      Define(args, Location{where, 1, 1});
    }
  }

  void LineDirective(const std::vector<PPToken>& args, const Location& where, int lastPhysicalLine) {
    std::vector<PPToken> expanded = ExpandList(args);
    if (expanded.empty() || expanded[0].kind != TokenKind::Number ||
        expanded[0].text.find_first_not_of("0123456789") != std::string::npos ||
        expanded[0].text.size() > 9 || (expanded.size() > 1 && expanded[1].kind != TokenKind::String) ||
        expanded.size() > 2) {
      Error(where, "#line needs a line number and an optional \"file name\"");
      return;
    }
    int line = std::stoi(expanded[0].text);
    if (line < 1) {
      Error(where, "#line number must be positive");
      return;
    }
    FileState& f = files_.back();
    f.lineDelta = line - (lastPhysicalLine + 1);
    if (expanded.size() == 2) f.name = Intern(Unquote(expanded[1].text));
  }

  void Include(const std::vector<PPToken>& args, const Location& where) {
    std::vector<PPToken> tokens = args;
    if (!tokens.empty() && tokens[0].kind == TokenKind::Identifier) tokens = ExpandList(tokens);
    std::string name;
    bool angled = false;
    if (tokens.size() == 1 && tokens[0].kind == TokenKind::String) {
      name = Unquote(tokens[0].text);
    } else if (tokens.size() >= 2 && IsPunct(tokens[0], "<") && IsPunct(tokens.back(), ">")) {
      angled = true;
      for (size_t i = 1; i + 1 < tokens.size(); ++i) {
        if (i > 1 && tokens[i].leadingSpace) name += ' ';
        name += tokens[i].text;
      }
    }
    if (name.empty()) {
      Error(where, "#include expects \"file\" or <file>");
      return;
    }
    std::optional<std::string> content;
    std::string path = ResolveInclude(name, angled, content);
    if (!content) {
      Error(where, "cannot open include file '" + name + "'");
      return;
    }
    for (const FileState& f : files_) {
      if (f.path == path) {
        Error(where, "recursive #include of '" + path + "'");
        return;
      }
    }
    if (files_.size() >= kMaxIncludeDepth) {
      Error(where, "#include nested too deeply");
      return;
    }
    if (onceFiles_.count(path)) return;
    if (++includedFiles_ > kMaxIncludedFiles) {
      Error(where, "too many #include files");
      fatal_ = true;
      return;
    }
    PushFile(path, Intern(path), *content);
  }

  // "x": the including file's folder first, then the include directories;
  // <x>: the other way round.
  std::string ResolveInclude(const std::string& name, bool angled, std::optional<std::string>& content) {
    namespace fs = std::filesystem;
    std::vector<std::string> candidates;
    std::string relative = fs::path(files_.back().path).parent_path().generic_string();
    if (fs::path(name).is_absolute()) {
      candidates.push_back(name);
    } else {
      if (!angled) candidates.push_back(relative);
      for (const std::string& dir : options_.includeDirs) candidates.push_back(dir);
      if (angled) candidates.push_back(relative);
      for (std::string& dir : candidates) {
        dir = (dir.empty() ? fs::path(name) : fs::path(dir) / name).lexically_normal().generic_string();
      }
    }
    for (const std::string& path : candidates) {
      content = ReadSourceFile(path, options_);
      if (content) return path;
    }
    return {};
  }

  // ---- macro expansion ----

  // The next token of `src` that is not a macro invocation (those are expanded
  // and rescanned).
  bool NextExpanded(TokenSource& src, PPToken& t) {
    while (!Failed() && src.Next(t)) {
      if (!ExpandInvocation(src, t)) return true;
    }
    return false;
  }

  std::vector<PPToken> ExpandList(std::vector<PPToken> tokens) {
    if (argumentNesting_ >= kMaxArgumentNesting) {
      Error(tokens.empty() ? Location{} : tokens[0].loc, "macro arguments nested too deeply");
      fatal_ = true;
      return {};
    }
    ++argumentNesting_;
    ListSource src(std::move(tokens));
    std::vector<PPToken> out;
    PPToken t;
    while (NextExpanded(src, t)) out.push_back(std::move(t));
    --argumentNesting_;
    return out;
  }

  static bool Hidden(const PPToken& t, int id) {
    return std::binary_search(t.hideSet.begin(), t.hideSet.end(), id);
  }

  // If `t` invokes a macro, pushes the expansion back onto `src` and returns true.
  bool ExpandInvocation(TokenSource& src, PPToken& t) {
    if (t.kind != TokenKind::Identifier || t.noExpand) return false;
    if (t.text == "__LINE__" || t.text == "__FILE__") {
      bool line = t.text == "__LINE__";
      t.kind = line ? TokenKind::Number : TokenKind::String;
      t.text = line ? std::to_string(t.loc.line) : "\"" + (t.loc.file ? *t.loc.file : "") + "\"";
      return false;
    }
    auto it = macros_.find(t.text);
    if (it == macros_.end()) return false;
    std::shared_ptr<const Macro> m = it->second;  // a directive met while reading arguments may #undef it
    if (Hidden(t, m->id)) {
      t.noExpand = true;
      return false;
    }
    std::vector<std::vector<PPToken>> args;
    if (m->functionLike) {
      PPToken next;
      if (!src.Next(next)) return false;
      if (!IsPunct(next, "(")) {
        src.PushFront({std::move(next)});
        return false;
      }
      if (!CollectArguments(src, *m, t, args)) return true;
    }
    std::vector<PPToken> result = Substitute(*m, args, t);
    macroTokens_ += result.size();
    if (macroTokens_ > kMaxMacroTokens) {
      Error(t.loc, "macro expansion too large");
      fatal_ = true;
      return true;
    }
    std::vector<int> hideSet = t.hideSet;
    hideSet.insert(std::upper_bound(hideSet.begin(), hideSet.end(), m->id), m->id);
    for (PPToken& r : result) {
      std::vector<int> merged;
      std::set_union(r.hideSet.begin(), r.hideSet.end(), hideSet.begin(), hideSet.end(),
                     std::back_inserter(merged));
      r.hideSet = std::move(merged);
      r.fromMacro = true;
    }
    if (!result.empty()) result.front().leadingSpace = t.leadingSpace;
    src.PushFront(std::move(result));
    return true;
  }

  bool CollectArguments(TokenSource& src, const Macro& m, const PPToken& name,
                        std::vector<std::vector<PPToken>>& args) {
    args.assign(1, {});
    int depth = 0;
    size_t count = 0;
    while (true) {
      PPToken a;
      if (!src.Next(a)) {
        Error(name.loc, "unterminated argument list invoking macro '" + name.text + "'");
        return false;
      }
      if (a.kind == TokenKind::Pragma) {
        Error(a.loc, "#pragma inside the arguments of macro '" + name.text + "'");
        return false;
      }
      if (++count > kMaxMacroTokens) {
        Error(name.loc, "macro argument list too long");
        fatal_ = true;
        return false;
      }
      if (IsPunct(a, "(")) {
        ++depth;
      } else if (IsPunct(a, ")")) {
        if (depth == 0) break;
        --depth;
      } else if (IsPunct(a, ",") && depth == 0 && !(m.variadic && args.size() == m.params.size())) {
        args.emplace_back();
        continue;
      }
      args.back().push_back(std::move(a));
    }
    if (m.params.empty() && args.size() == 1 && args[0].empty()) {
      args.clear();
      return true;
    }
    if (m.variadic && args.size() + 1 == m.params.size()) args.emplace_back();
    if (args.size() != m.params.size()) {
      Error(name.loc, "macro '" + name.text + "' expects " + std::to_string(m.params.size()) +
                          " arguments, got " + std::to_string(args.size()));
      return false;
    }
    return true;
  }

  PPToken Stringize(const std::vector<PPToken>& arg, const Location& where) const {
    PPToken s;
    s.kind = TokenKind::String;
    s.loc = where;
    s.text = "\"";
    for (char c : JoinSpelling(arg)) {
      if (c == '"' || c == '\\') s.text += '\\';
      s.text += c;
    }
    s.text += '"';
    return s;
  }

  // Glues `rhs` onto `lhs` (the ## operator); the result must be one token.
  void Paste(PPToken& lhs, const PPToken& rhs) {
    std::vector<LexError> lexErrors;
    std::vector<LexToken> lexed = Lex(lhs.text + rhs.text, lexErrors);
    if (lexed.size() != 1 || !lexErrors.empty() || lexed[0].kind == TokenKind::Invalid) {
      Error(lhs.loc, "pasting '" + lhs.text + "' and '" + rhs.text + "' does not give a valid token");
      return;
    }
    lhs.kind = lexed[0].kind;
    lhs.text = lexed[0].text;
  }

  // The macro body with its parameters replaced. Body tokens are placed at the
  // invocation; argument tokens keep their own positions.
  std::vector<PPToken> Substitute(const Macro& m, const std::vector<std::vector<PPToken>>& args,
                                  const PPToken& invocation) {
    std::vector<std::optional<std::vector<PPToken>>> expandedArgs(args.size());
    std::vector<PPToken> out;
    bool lastWasEmptyArg = false;  // the left side of a following ## is a placemarker
    const auto& body = m.body;
    for (size_t i = 0; i < body.size(); ++i) {
      const PPToken& b = body[i];
      int p = ParamIndex(m, b);
      if (m.functionLike && IsPunct(b, "#") && i + 1 < body.size()) {
        out.push_back(Stringize(args[ParamIndex(m, body[i + 1])], invocation.loc));
        out.back().leadingSpace = b.leadingSpace;
        ++i;
        lastWasEmptyArg = false;
      } else if (IsPunct(b, "##") && i + 1 < body.size()) {
        int q = ParamIndex(m, body[i + 1]);
        std::vector<PPToken> rhs = q >= 0 ? args[q] : std::vector<PPToken>{Placed(body[i + 1], invocation)};
        ++i;
        if (rhs.empty()) continue;
        size_t from = 0;
        if (!lastWasEmptyArg && !out.empty()) {
          Paste(out.back(), rhs[0]);
          from = 1;
        }
        for (size_t k = from; k < rhs.size(); ++k) out.push_back(rhs[k]);
        lastWasEmptyArg = false;
      } else if (p >= 0) {
        bool pasted = i + 1 < body.size() && IsPunct(body[i + 1], "##");
        if (!pasted && !expandedArgs[p]) expandedArgs[p] = ExpandList(args[p]);
        const std::vector<PPToken>& a = pasted ? args[p] : *expandedArgs[p];
        for (size_t k = 0; k < a.size(); ++k) {
          out.push_back(a[k]);
          if (k == 0) out.back().leadingSpace = b.leadingSpace;
        }
        lastWasEmptyArg = a.empty();
      } else {
        out.push_back(Placed(b, invocation));
        lastWasEmptyArg = false;
      }
    }
    return out;
  }

  static PPToken Placed(const PPToken& bodyToken, const PPToken& invocation) {
    PPToken t = bodyToken;
    t.loc = invocation.loc;
    return t;
  }

  // ---- output ----

  void Emit(const PPToken& t) {
    if (t.kind == TokenKind::Invalid) {
      bool quoted = !t.text.empty() && (t.text[0] == '"' || t.text[0] == '\'');
      Error(t.loc, quoted ? "missing terminating " + t.text.substr(0, 1) + " character"
                          : "unexpected character '" + Printable(t.text) + "'");
      return;
    }
    Token out;
    out.kind = t.kind;
    out.text = t.text;
    out.where = ToSourceLocation(t.loc);
    out.fromMacro = t.fromMacro;
    out.offset = t.kind == TokenKind::Pragma ? writer_->WritePragma(t.loc, t.text) : writer_->Write(t);
    out_.tokens.push_back(std::move(out));
  }

  static std::string Printable(const std::string& s) {
    std::string r;
    for (unsigned char c : s) {
      if (c >= 0x20 && c < 0x7f) {
        r += static_cast<char>(c);
      } else {
        static const char* kHex = "0123456789abcdef";
        r += "\\x";
        r += kHex[c >> 4];
        r += kHex[c & 15];
      }
    }
    return r;
  }

  const ParseOptions& options_;
  std::map<std::string, std::unique_ptr<std::string>> names_;
  std::unordered_map<std::string, std::shared_ptr<const Macro>> macros_;
  int nextMacroId_ = 1;
  std::vector<FileState> files_;
  std::vector<Conditional> conditionals_;
  std::set<std::string> onceFiles_;
  int includedFiles_ = 0;
  size_t macroTokens_ = 0;
  int argumentNesting_ = 0;
  bool fatal_ = false;
  std::vector<ParseError> errors_;
  std::unique_ptr<OutputWriter> writer_;
  PreprocessedSource out_;
};

}  // namespace

std::optional<std::string> ReadSourceFile(const std::string& path, const ParseOptions& options) {
  if (options.readFile) return options.readFile(path);
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) return std::nullopt;
  std::ifstream in(path, std::ios::binary);
  if (!in) return std::nullopt;
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

Result<PreprocessedSource> Preprocess(const std::string& source, const std::string& fileName,
                                      const ParseOptions& options) {
  return Preprocessor(options).Run(source, fileName);
}

}  // namespace fx
