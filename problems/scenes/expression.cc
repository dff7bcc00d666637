#include "problems/scenes/expression.h"

#include <cctype>
#include <charconv>
#include <cmath>

#include "solvers/core/problem.h"

namespace smcbench {
namespace {

struct Function {
  std::string_view name;
  double (*apply)(double);
};

constexpr double kPi = 3.14159265358979323846;

const Function kFunctions[] = {
    {"sqrt", [](double x) { return std::sqrt(x); }}, {"exp", [](double x) { return std::exp(x); }},
    {"log", [](double x) { return std::log(x); }},   {"sin", [](double x) { return std::sin(x); }},
    {"cos", [](double x) { return std::cos(x); }},   {"tan", [](double x) { return std::tan(x); }},
    {"atan", [](double x) { return std::atan(x); }}, {"abs", [](double x) { return std::abs(x); }},
};

bool IsNameStart(char c) { return std::isalpha(static_cast<unsigned char>(c)) || c == '_'; }
bool IsNameChar(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; }

// Recursive descent over
//   expr  := term (('+' | '-') term)*
//   term  := unary (('*' | '/') unary)*
//   unary := ('+' | '-') unary | power
//   power := primary ('^' unary)?
//   primary := number | name | name '(' expr ')' | '(' expr ')'
class Parser {
 public:
  Parser(std::string_view text, const SceneParameters& parameters) : text_(text), parameters_(parameters) {}

  double Parse() {
    SkipSpace();
    if (pos_ == text_.size()) Fail("empty expression");
    const double value = Expr();
    SkipSpace();
    if (pos_ != text_.size()) Fail("unexpected '" + std::string(1, text_[pos_]) + "'");
    return value;
  }

 private:
  [[noreturn]] void Fail(const std::string& what) const {
    throw InvalidInputError("expression '" + std::string(text_) + "': " + what + " at column " +
                            std::to_string(pos_ + 1));
  }

  void SkipSpace() {
    while (pos_ < text_.size() && std::isspace(static_cast<unsigned char>(text_[pos_]))) ++pos_;
  }

  bool Accept(char c) {
    SkipSpace();
    if (pos_ < text_.size() && text_[pos_] == c) {
      ++pos_;
      return true;
    }
    return false;
  }

  double Expr() {
    double value = Term();
    for (;;) {
      if (Accept('+')) {
        value += Term();
      } else if (Accept('-')) {
        value -= Term();
      } else {
        return value;
      }
    }
  }

  double Term() {
    double value = Unary();
    for (;;) {
      if (Accept('*')) {
        value *= Unary();
      } else if (Accept('/')) {
        value /= Unary();
      } else {
        return value;
      }
    }
  }

  // Every recursive path (parentheses, function arguments, unary signs, the right operand of ^) passes through
  // here, so this bound keeps a hostile file ("((((...", "----...1") from overflowing the stack.
  double Unary() {
    if (++depth_ > kMaxDepth) Fail("nested deeper than " + std::to_string(kMaxDepth) + " levels");
    double value = 0.0;
    if (Accept('-')) {
      value = -Unary();
    } else if (Accept('+')) {
      value = Unary();
    } else {
      value = Power();
    }
    --depth_;
    return value;
  }

  double Power() {
    const double base = Primary();
    if (Accept('^')) return std::pow(base, Unary());
    return base;
  }

  double Primary() {
    SkipSpace();
    if (pos_ == text_.size()) Fail("expression ends early");
    const char c = text_[pos_];
    if (c == '(') {
      ++pos_;
      const double value = Expr();
      if (!Accept(')')) Fail("missing ')'");
      return value;
    }
    if (std::isdigit(static_cast<unsigned char>(c)) || c == '.') return Number();
    if (IsNameStart(c)) return Name();
    Fail("unexpected '" + std::string(1, c) + "'");
  }

  double Number() {
    double value = 0.0;
    const char* begin = text_.data() + pos_;
    const auto result = std::from_chars(begin, text_.data() + text_.size(), value);
    if (result.ec == std::errc::invalid_argument) Fail("malformed number");
    // Out of range (1e999) is reported as infinite, which the caller's finiteness check names.
    if (result.ec == std::errc::result_out_of_range) value = kInf;
    pos_ += static_cast<std::size_t>(result.ptr - begin);
    return value;
  }

  double Name() {
    const std::size_t start = pos_;
    while (pos_ < text_.size() && IsNameChar(text_[pos_])) ++pos_;
    const std::string_view name = text_.substr(start, pos_ - start);
    for (const Function& f : kFunctions) {
      if (f.name != name) continue;
      if (!Accept('(')) Fail("function " + std::string(name) + " needs '('");
      const double argument = Expr();
      if (!Accept(')')) Fail("missing ')'");
      return f.apply(argument);
    }
    if (name == "pi") return kPi;
    const auto it = parameters_.find(name);
    if (it == parameters_.end()) {
      std::string known;
      for (const auto& [key, value] : parameters_) known += (known.empty() ? "" : ", ") + key;
      pos_ = start;
      Fail("unknown name '" + std::string(name) + "' (parameters: " + (known.empty() ? "none" : known) + ")");
    }
    return it->second;
  }

  static constexpr int kMaxDepth = 200;

  std::string_view text_;
  const SceneParameters& parameters_;
  std::size_t pos_ = 0;
  int depth_ = 0;
};

}  // namespace

double EvaluateExpression(std::string_view text, const SceneParameters& parameters) {
  return Parser(text, parameters).Parse();
}

bool IsValidParameterName(std::string_view name) {
  if (name.empty() || !IsNameStart(name[0])) return false;
  for (char c : name) {
    if (!IsNameChar(c)) return false;
  }
  if (name == "pi") return false;
  for (const Function& f : kFunctions) {
    if (f.name == name) return false;
  }
  return true;
}

}  // namespace smcbench
