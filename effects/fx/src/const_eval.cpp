#include "const_eval.h"

#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdlib>

namespace fx {
namespace {

constexpr int kMaxDepth = 200;
constexpr size_t kMaxComponents = 1 << 16;

bool IsPunct(const Token& t, std::string_view p) { return t.kind == TokenKind::Punctuator && t.text == p; }

struct Failure {
  ConstError error;
};

class Evaluator {
 public:
  Evaluator(const std::vector<Token>& t, size_t begin, size_t end, const ConstantTable& constants)
      : t_(t), pos_(begin), end_(end), constants_(constants) {}

  ConstValue Run() {
    if (pos_ >= end_) Fail(pos_, "expected a value");
    ConstValue v = Ternary(0);
    if (pos_ < end_) Fail(pos_, "unexpected '" + t_[pos_].text + "' in constant expression");
    return v;
  }

 private:
  [[noreturn]] void Fail(size_t at, std::string message) {
    throw Failure{ConstError{std::min(at, end_ > 0 ? end_ - 1 : 0), std::move(message)}};
  }
  bool Accept(std::string_view p) {
    if (pos_ < end_ && IsPunct(t_[pos_], p)) {
      ++pos_;
      return true;
    }
    return false;
  }
  void Expect(std::string_view p) {
    if (!Accept(p)) Fail(pos_, "expected '" + std::string(p) + "'");
  }

  static double Scalar(const ConstValue& v) { return v.components.empty() ? 0 : v.components[0]; }

  ConstValue Ternary(int depth) {
    ConstValue c = Binary(0, depth);
    if (!Accept("?")) return c;
    ConstValue a = Ternary(depth + 1);
    Expect(":");
    ConstValue b = Ternary(depth + 1);
    return Scalar(c) != 0 ? a : b;
  }

  static int Precedence(const std::string& op) {
    static const std::map<std::string, int, std::less<>> kPrecedence = {
        {"||", 1}, {"&&", 2}, {"|", 3},  {"^", 4},  {"&", 5},  {"==", 6}, {"!=", 6},
        {"<", 7},  {">", 7},  {"<=", 7}, {">=", 7}, {"<<", 8}, {">>", 8}, {"+", 9},
        {"-", 9},  {"*", 10}, {"/", 10}, {"%", 10}};
    auto it = kPrecedence.find(op);
    return it == kPrecedence.end() ? 0 : it->second;
  }

  ConstValue Binary(int minPrecedence, int depth) {
    ConstValue lhs = Unary(depth + 1);
    while (pos_ < end_ && t_[pos_].kind == TokenKind::Punctuator) {
      size_t at = pos_;
      std::string op = t_[pos_].text;
      int p = Precedence(op);
      if (p == 0 || p <= minPrecedence) break;
      ++pos_;
      ConstValue rhs = Binary(p, depth + 1);
      lhs = Combine(op, lhs, rhs, at);
    }
    return lhs;
  }

  // Component-wise, a single component broadcasting.
  ConstValue Combine(const std::string& op, const ConstValue& a, const ConstValue& b, size_t at) {
    size_t n = std::max(a.components.size(), b.components.size());
    if (a.components.size() != b.components.size() && a.components.size() != 1 && b.components.size() != 1) {
      Fail(at, "operands of '" + op + "' have different sizes");
    }
    ConstValue r;
    r.integral = a.integral && b.integral;
    bool comparison = op == "==" || op == "!=" || op == "<" || op == ">" || op == "<=" || op == ">=" ||
                      op == "&&" || op == "||";
    for (size_t i = 0; i < n; ++i) {
      double x = a.components[a.components.size() == 1 ? 0 : i];
      double y = b.components[b.components.size() == 1 ? 0 : i];
      r.components.push_back(Apply(op, x, y, r.integral, at));
    }
    if (comparison) r.integral = true;
    return r;
  }

  int64_t ToInt(double d, size_t at) {
    if (!(d > -9.3e18 && d < 9.3e18)) Fail(at, "integer operand out of range");
    return static_cast<int64_t>(d);
  }

  double Apply(const std::string& op, double x, double y, bool integral, size_t at) {
    if (op == "+") return x + y;
    if (op == "-") return x - y;
    if (op == "*") return x * y;
    if (op == "/" || op == "%") {
      if (y == 0) Fail(at, "division by zero in constant expression");
      if (integral) {
        int64_t a = ToInt(x, at), b = ToInt(y, at);
        if (b == -1) return op == "/" ? -static_cast<double>(a) : 0;
        return static_cast<double>(op == "/" ? a / b : a % b);
      }
      return op == "/" ? x / y : std::fmod(x, y);
    }
    if (op == "==") return x == y;
    if (op == "!=") return x != y;
    if (op == "<") return x < y;
    if (op == ">") return x > y;
    if (op == "<=") return x <= y;
    if (op == ">=") return x >= y;
    if (op == "&&") return x != 0 && y != 0;
    if (op == "||") return x != 0 || y != 0;
    if (!integral) Fail(at, "'" + op + "' needs integer operands");
    uint64_t a = static_cast<uint64_t>(ToInt(x, at)), b = static_cast<uint64_t>(ToInt(y, at));
    if (op == "|") return static_cast<double>(a | b);
    if (op == "^") return static_cast<double>(a ^ b);
    if (op == "&") return static_cast<double>(a & b);
    if (op == "<<") return static_cast<double>((a << (b & 63)) & 0xFFFFFFFFull);
    return static_cast<double>(a >> (b & 63));  // ">>"
  }

  ConstValue Unary(int depth) {
    if (depth > kMaxDepth) Fail(pos_, "constant expression nested too deeply");
    if (pos_ >= end_) Fail(pos_, "expected a value");
    size_t at = pos_;
    if (Accept("-") || Accept("+") || Accept("!") || Accept("~")) {
      std::string op = t_[at].text;
      ConstValue v = Unary(depth + 1);
      for (double& c : v.components) {
        if (op == "-") c = -c;
        if (op == "!") c = c == 0;
        if (op == "~") {
          if (!v.integral) Fail(at, "'~' needs an integer operand");
          c = static_cast<double>(~static_cast<uint32_t>(ToInt(c, at)));
        }
      }
      if (op == "!") v.integral = true;
      return v;
    }
    return Primary(depth);
  }

  ConstValue Primary(int depth) {
    size_t at = pos_;
    const Token& t = t_[pos_];
    if (t.kind == TokenKind::Number) {
      ++pos_;
      return Number(t.text, at);
    }
    if (IsPunct(t, "(")) {
      ++pos_;
      NumericTypeName cast;
      if (pos_ + 1 < end_ && t_[pos_].kind == TokenKind::Identifier && IsPunct(t_[pos_ + 1], ")") &&
          ParseNumericTypeName(t_[pos_].text, cast)) {
        pos_ += 2;
        ConstValue v = Unary(depth + 1);
        return Convert(v, cast, at);
      }
      ConstValue v = Ternary(depth + 1);
      Expect(")");
      return v;
    }
    if (IsPunct(t, "{")) {
      ++pos_;
      ConstValue list = List("}", depth);
      return list;
    }
    if (t.kind == TokenKind::Identifier) {
      ++pos_;
      if (t.text == "true" || t.text == "false") return ConstValue{{t.text == "true" ? 1.0 : 0.0}, true};
      NumericTypeName type;
      if (ParseNumericTypeName(t.text, type) && pos_ < end_ && IsPunct(t_[pos_], "(")) {
        ++pos_;
        ConstValue args = List(")", depth);
        return Construct(args, type, at);
      }
      auto it = constants_.find(t.text);
      if (it != constants_.end()) return it->second;
      Fail(at, "'" + t.text + "' is not a constant");
    }
    Fail(at, "unexpected '" + t.text + "' in constant expression");
  }

  // Comma-separated values up to `close`, flattened.
  ConstValue List(std::string_view close, int depth) {
    ConstValue r;
    if (Accept(close)) return r;
    while (true) {
      ConstValue v = Ternary(depth + 1);
      r.components.insert(r.components.end(), v.components.begin(), v.components.end());
      r.integral = r.integral && v.integral;
      if (r.components.size() > kMaxComponents) Fail(pos_, "constant too large");
      if (Accept(close)) return r;
      Expect(",");
      if (close == "}" && Accept(close)) return r;  // a trailing comma
    }
  }

  ConstValue Construct(const ConstValue& args, const NumericTypeName& type, size_t at) {
    size_t n = static_cast<size_t>(type.rows * type.columns);
    if (args.components.size() != n && args.components.size() != 1) {
      Fail(at, "'" + t_[at].text + "' needs " + std::to_string(n) + " values, got " +
                   std::to_string(args.components.size()));
    }
    ConstValue v = args;
    v.components.resize(n, args.components.empty() ? 0 : args.components[0]);
    return Convert(v, type, at);
  }

  static ConstValue Convert(ConstValue v, const NumericTypeName& type, size_t) {
    bool isFloat = type.scalar.find("float") != std::string::npos || type.scalar == "half" || type.scalar == "double";
    v.integral = !isFloat;
    for (double& c : v.components) {
      if (type.scalar == "bool") c = c != 0;
      else if (!isFloat) c = std::trunc(c);
    }
    return v;
  }

  ConstValue Number(const std::string& s, size_t at) {
    std::string body = s;
    bool hex = body.size() > 2 && body[0] == '0' && (body[1] == 'x' || body[1] == 'X');
    bool isFloat = !hex && body.find_first_of(".eE") != std::string::npos;
    // Suffixes: u/l for integers, f/h/l for floats.
    while (!body.empty() && std::string_view(hex ? "uUlL" : "uUlLfFhH").find(body.back()) != std::string_view::npos) {
      if (body.back() == 'f' || body.back() == 'F' || body.back() == 'h' || body.back() == 'H') isFloat = true;
      body.pop_back();
    }
    if (body.empty()) Fail(at, "invalid number '" + s + "'");
    char* end = nullptr;
    ConstValue v;
    v.integral = !isFloat;
    if (isFloat) {
      v.components.push_back(std::strtod(body.c_str(), &end));
    } else {
      int base = hex ? 16 : (body.size() > 1 && body[0] == '0') ? 8 : 10;
      errno = 0;
      unsigned long long n = std::strtoull(body.c_str() + (hex ? 2 : 0), &end, base);
      if (errno == ERANGE) Fail(at, "integer constant too large");
      v.components.push_back(static_cast<double>(n));
    }
    if (end == nullptr || *end != '\0') Fail(at, "invalid number '" + s + "'");
    return v;
  }

  const std::vector<Token>& t_;
  size_t pos_;
  size_t end_;
  const ConstantTable& constants_;
};

}  // namespace

std::variant<ConstValue, ConstError> EvaluateConstant(const std::vector<Token>& tokens, size_t begin, size_t end,
                                                      const ConstantTable& constants) {
  try {
    return Evaluator(tokens, begin, std::min(end, tokens.size()), constants).Run();
  } catch (const Failure& f) {
    return f.error;
  }
}

bool ParseNumericTypeName(const std::string& name, NumericTypeName& out) {
  static const char* kScalars[] = {"min16float", "min10float", "min16int", "min12int", "min16uint", "float",
                                   "double",     "dword",      "uint",     "bool",     "half",      "int"};
  for (const char* scalar : kScalars) {
    std::string_view s(scalar);
    if (name.compare(0, s.size(), s) != 0) continue;
    std::string_view rest = std::string_view(name).substr(s.size());
    NumericTypeName r;
    r.scalar = scalar;
    auto dim = [](char c) { return c >= '1' && c <= '4' ? c - '0' : 0; };
    if (rest.empty()) {
      out = r;
      return true;
    }
    if (rest.size() == 1 && dim(rest[0])) {
      r.columns = dim(rest[0]);
      out = r;
      return true;
    }
    if (rest.size() == 3 && dim(rest[0]) && rest[1] == 'x' && dim(rest[2])) {
      r.rows = dim(rest[0]);
      r.columns = dim(rest[2]);
      r.isMatrix = true;
      out = r;
      return true;
    }
  }
  return false;
}

}  // namespace fx
