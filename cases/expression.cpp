#include "sympathy/cases/expression.hpp"

#include <array>
#include <charconv>
#include <cmath>
#include <stdexcept>

namespace sympathy {

namespace {

constexpr std::array<FunctionInfo, 19> kFunctions{{
    {Function::Sin, "sin", 1},     {Function::Cos, "cos", 1},
    {Function::Tan, "tan", 1},     {Function::Exp, "exp", 1},
    {Function::Log, "log", 1},     {Function::Sqrt, "sqrt", 1},
    {Function::Abs, "abs", 1},     {Function::Tanh, "tanh", 1},
    {Function::Atan, "atan", 1},   {Function::Asin, "asin", 1},
    {Function::Acos, "acos", 1},   {Function::Sinh, "sinh", 1},
    {Function::Cosh, "cosh", 1},   {Function::Pow, "pow", 2},
    {Function::Atan2, "atan2", 2}, {Function::Min, "min", 2},
    {Function::Max, "max", 2},     {Function::SignSmooth, "sign_smooth", 2},
    {Function::Sign, "sign", 1},
}};

bool is_letter(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_';
}
bool is_digit(char c) {
  return c >= '0' && c <= '9';
}

// What stands at `offset`, for a message: a printable ASCII character quoted, a byte outside it
// by its code (a message must not carry the file's raw bytes either).
std::string describe_at(std::string_view text, std::size_t offset) {
  if (offset >= text.size()) return "the end of the expression";
  const auto c = static_cast<unsigned char>(text[offset]);
  if (c >= 0x20 && c < 0x7f) return std::string("'") + static_cast<char>(c) + "'";
  static const char* hex = "0123456789abcdef";
  std::string code = "byte 0x";
  code += hex[c >> 4];
  code += hex[c & 15];
  if (c >= 0x80) code += " (not ASCII)";
  if (c == '\n') code = "a line break";
  if (c == '\t') code = "a tab";
  return code;
}

class Parser {
 public:
  explicit Parser(std::string_view text) : text_(text) {}

  Expression parse() {
    if (text_.size() > kMaxExpressionLength)
      throw ExpressionError{kMaxExpressionLength,
                            "at most " + std::to_string(kMaxExpressionLength) + " characters",
                            std::to_string(text_.size()) + " characters"};
    skip_space();
    Expression e = expression();
    skip_space();
    if (pos_ < text_.size()) fail("an operator (+ - * / ^) or the end of the expression");
    return e;
  }

 private:
  [[noreturn]] void fail(const std::string& expected) const {
    throw ExpressionError{pos_, expected, describe_at(text_, pos_)};
  }

  void skip_space() {
    while (pos_ < text_.size() && (text_[pos_] == ' ' || text_[pos_] == '\t' ||
                                   text_[pos_] == '\n' || text_[pos_] == '\r'))
      ++pos_;
  }
  bool at(char c) const { return pos_ < text_.size() && text_[pos_] == c; }
  bool at_power() const {
    return at('^') || (at('*') && pos_ + 1 < text_.size() && text_[pos_ + 1] == '*');
  }

  struct Depth {
    explicit Depth(Parser& p) : parser(p) {
      if (++parser.depth_ > kMaxExpressionDepth)
        parser.fail("at most " + std::to_string(kMaxExpressionDepth) + " levels of nesting");
    }
    ~Depth() { --parser.depth_; }
    Parser& parser;
  };

  static Expression binary(Expression::Kind kind, Expression a, Expression b) {
    Expression e;
    e.kind = kind;
    e.offset = a.offset;
    e.operands.push_back(std::move(a));
    e.operands.push_back(std::move(b));
    return e;
  }

  Expression expression() {
    Depth depth(*this);
    Expression e = term();
    for (skip_space(); at('+') || at('-'); skip_space()) {
      const auto kind = at('+') ? Expression::Kind::Add : Expression::Kind::Subtract;
      ++pos_;
      skip_space();
      e = binary(kind, std::move(e), term());
    }
    return e;
  }

  Expression term() {
    Expression e = unary();
    for (skip_space(); (at('*') && !at_power()) || at('/'); skip_space()) {
      const auto kind = at('*') ? Expression::Kind::Multiply : Expression::Kind::Divide;
      ++pos_;
      skip_space();
      e = binary(kind, std::move(e), unary());
    }
    return e;
  }

  Expression unary() {
    Depth depth(*this);
    if (at('-') || at('+')) {
      const bool negate = at('-');
      const std::size_t start = pos_++;
      skip_space();
      Expression operand = unary();
      if (!negate) return operand;
      Expression e;
      e.kind = Expression::Kind::Negate;
      e.offset = start;
      e.operands.push_back(std::move(operand));
      return e;
    }
    return power();
  }

  Expression power() {
    Expression base = primary();
    skip_space();
    if (!at_power()) return base;
    pos_ += at('^') ? 1 : 2;
    skip_space();
    return binary(Expression::Kind::Power, std::move(base), unary());
  }

  Expression primary() {
    Depth depth(*this);
    Expression e;
    e.offset = pos_;
    if (at('(')) {
      const std::size_t open = pos_++;
      skip_space();
      e = expression();
      skip_space();
      if (!at(')'))
        fail("')' closing the '(' " + std::to_string(pos_ - open) + " characters before");
      ++pos_;
      return e;
    }
    if (pos_ < text_.size() && (is_digit(text_[pos_]) || text_[pos_] == '.')) return number();
    if (pos_ < text_.size() && is_letter(text_[pos_])) return name_or_call();
    fail("a number, a name, a function call or '('");
  }

  Expression number() {
    const std::size_t start = pos_;
    while (pos_ < text_.size() && is_digit(text_[pos_])) ++pos_;
    if (at('.')) {
      ++pos_;
      while (pos_ < text_.size() && is_digit(text_[pos_])) ++pos_;
    }
    if (pos_ == start + 1 && text_[start] == '.') {
      pos_ = start;
      fail("a number (digits before or after '.')");
    }
    if (at('e') || at('E')) {
      ++pos_;
      if (at('+') || at('-')) ++pos_;
      if (pos_ >= text_.size() || !is_digit(text_[pos_])) fail("the digits of an exponent");
      while (pos_ < text_.size() && is_digit(text_[pos_])) ++pos_;
    }
    if (pos_ < text_.size() && (is_letter(text_[pos_]) || text_[pos_] == '.'))
      fail("an operator after the number " + std::string(text_.substr(start, pos_ - start)));
    Expression e;
    e.kind = Expression::Kind::Number;
    e.offset = start;
    const auto result = std::from_chars(text_.data() + start, text_.data() + pos_, e.number);
    if (result.ec != std::errc() || !std::isfinite(e.number)) {
      // The number as typed (the token describer would show its first digit alone: "got '1'"
      // for 1e999).
      const std::string typed(text_.substr(start, pos_ - start));
      pos_ = start;
      throw ExpressionError{pos_, "a finite number", "'" + typed + "'"};
    }
    return e;
  }

  Expression name_or_call() {
    const std::size_t start = pos_;
    while (pos_ < text_.size() && (is_letter(text_[pos_]) || is_digit(text_[pos_]))) ++pos_;
    if (pos_ - start > kMaxNameLength) {
      pos_ = start;
      fail("a name of at most " + std::to_string(kMaxNameLength) + " characters");
    }
    const std::string_view word = text_.substr(start, pos_ - start);
    skip_space();
    Expression e;
    e.offset = start;
    const FunctionInfo* info = nullptr;
    for (const auto& f : kFunctions)
      if (f.name == word) info = &f;
    if (!at('(')) {
      if (info) fail("'(' after the function " + std::string(word));
      e.kind = Expression::Kind::Name;
      e.name = std::string(word);
      return e;
    }
    if (!info) {
      pos_ = start;
      std::string known;
      for (const auto& f : kFunctions) known += (known.empty() ? "" : ", ") + std::string(f.name);
      fail("a function (" + known + ")");
    }
    e.kind = Expression::Kind::Call;
    e.function = info->function;
    ++pos_;  // '('
    skip_space();
    for (;;) {
      e.operands.push_back(expression());
      skip_space();
      if (at(',')) {
        ++pos_;
        skip_space();
        continue;
      }
      if (at(')')) break;
      fail("',' or ')' in the arguments of " + std::string(word));
    }
    if (static_cast<int>(e.operands.size()) != info->arity)
      fail(std::string(word) + " with " + std::to_string(info->arity) + " argument" +
           (info->arity > 1 ? "s" : "") + ", not " + std::to_string(e.operands.size()));
    ++pos_;  // ')'
    return e;
  }

  std::string_view text_;
  std::size_t pos_ = 0;
  int depth_ = 0;
};

double call(Function f, const std::vector<double>& a) {
  switch (f) {
    case Function::Sin:
      return std::sin(a[0]);
    case Function::Cos:
      return std::cos(a[0]);
    case Function::Tan:
      return std::tan(a[0]);
    case Function::Exp:
      return std::exp(a[0]);
    case Function::Log:
      return std::log(a[0]);
    case Function::Sqrt:
      return std::sqrt(a[0]);
    case Function::Abs:
      return std::abs(a[0]);
    case Function::Tanh:
      return std::tanh(a[0]);
    case Function::Atan:
      return std::atan(a[0]);
    case Function::Asin:
      return std::asin(a[0]);
    case Function::Acos:
      return std::acos(a[0]);
    case Function::Sinh:
      return std::sinh(a[0]);
    case Function::Cosh:
      return std::cosh(a[0]);
    case Function::Pow:
      return std::pow(a[0], a[1]);
    case Function::Atan2:
      return std::atan2(a[0], a[1]);
    case Function::Min:
      return std::min(a[0], a[1]);
    case Function::Max:
      return std::max(a[0], a[1]);
    case Function::SignSmooth:
      return std::tanh(a[0] / a[1]);
    case Function::Sign:
      return a[0] >= 0.0 ? 1.0 : -1.0;
  }
  throw std::logic_error("unknown function");
}

}  // namespace

std::span<const FunctionInfo> functions() {
  return kFunctions;
}

const FunctionInfo& function_info(Function f) {
  return kFunctions[static_cast<std::size_t>(f)];
}

std::string ExpressionError::message() const {
  return "expected " + expected + ", got " + found;
}

Expression parse_expression(std::string_view text) {
  return Parser(text).parse();
}

void collect_names(const Expression& e, std::vector<const Expression*>& names) {
  if (e.kind == Expression::Kind::Name) names.push_back(&e);
  for (const auto& o : e.operands) collect_names(o, names);
}

double evaluate_expression(const Expression& e,
                           const std::function<double(const std::string&)>& value_of_name) {
  auto operand = [&](int i) { return evaluate_expression(e.operands[i], value_of_name); };
  switch (e.kind) {
    case Expression::Kind::Number:
      return e.number;
    case Expression::Kind::Name:
      return value_of_name(e.name);
    case Expression::Kind::Negate:
      return -operand(0);
    case Expression::Kind::Add:
      return operand(0) + operand(1);
    case Expression::Kind::Subtract:
      return operand(0) - operand(1);
    case Expression::Kind::Multiply:
      return operand(0) * operand(1);
    case Expression::Kind::Divide:
      return operand(0) / operand(1);
    case Expression::Kind::Power:
      return std::pow(operand(0), operand(1));
    case Expression::Kind::Call: {
      std::vector<double> args;
      for (std::size_t i = 0; i < e.operands.size(); ++i) args.push_back(operand(i));
      return call(e.function, args);
    }
  }
  throw std::logic_error("unknown expression kind");
}

}  // namespace sympathy
