// Expressions of equation case files: sympathy's own grammar, parsed into a tree.
//
// A case file is data, not code: its expressions are read by this recursive-descent parser into
// an Expression tree, and C++ is generated from the tree alone (equation_codegen.hpp), so no text
// of a file reaches the compiler. The grammar, from loosest to tightest binding:
//
//   expression := term (('+' | '-') term)*
//   term       := unary (('*' | '/') unary)*
//   unary      := ('-' | '+') unary | power
//   power      := primary (('^' | '**') unary)?      right-associative: 2^3^2 = 2^9
//   primary    := NUMBER | NAME | NAME '(' expression (',' expression)* ')' | '(' expression ')'
//
// so -x^2 = -(x^2) and 2^-1 = 0.5, as in mathematics (and Python, Fortran). NUMBER is decimal,
// 12, 1.5, .5, 1e-3, 2.5E+4; NAME is an ASCII letter or '_' then letters, digits and '_', at most
// kMaxNameLength characters. Spaces, tabs and line breaks separate tokens; any other character
// (quotes, ';', braces, '#', '\\', non-ASCII bytes) is refused where it stands.
//
// Functions (a fixed table, `functions()`): one argument: sin cos tan exp log sqrt abs tanh atan
// asin acos sinh cosh sign; two: pow atan2 min max sign_smooth. sign_smooth(x, eps) = tanh(x /
// eps), a sign function smoothed over a width eps (as the metronome model's escapement smooths
// its switch); |sign_smooth(x, eps) - sign(x)| < 1e-8 for |x| > 10 eps. sign(x) is the sign
// itself, +1 where x >= 0 and -1 where x < 0: in an equation case file each sign(...) makes the
// system piecewise smooth, x = 0 a switching surface (cases/equation_codegen.cpp).
#pragma once

#include <cstddef>
#include <functional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace sympathy {

enum class Function {
  Sin,
  Cos,
  Tan,
  Exp,
  Log,
  Sqrt,
  Abs,
  Tanh,
  Atan,
  Asin,
  Acos,
  Sinh,
  Cosh,
  Pow,
  Atan2,
  Min,
  Max,
  SignSmooth,
  Sign,
};

struct FunctionInfo {
  Function function;
  std::string_view name;  // as written in a case file
  int arity;
};
// Every function of the grammar, in the order of the enumeration.
std::span<const FunctionInfo> functions();
const FunctionInfo& function_info(Function f);

constexpr std::size_t kMaxNameLength = 64;
constexpr std::size_t kMaxExpressionLength = 4000;  // characters of one expression
constexpr int kMaxExpressionDepth = 100;            // nesting of parentheses and operators

struct Expression {
  enum class Kind { Number, Name, Negate, Add, Subtract, Multiply, Divide, Power, Call };
  Kind kind = Kind::Number;
  double number = 0.0;                // Number
  std::string name;                   // Name
  Function function = Function::Sin;  // Call
  std::vector<Expression> operands;   // Negate: 1, binary operators: 2, Call: its arguments
  std::size_t offset = 0;             // where it starts in the text (for messages)
};

// A parse failure at `offset` of the text: `expected` says what the grammar wanted there
// ("a number, a name or '('"), `found` what stood there ("';'", "the end").
struct ExpressionError {
  std::size_t offset = 0;
  std::string expected;
  std::string found;
  std::string message() const;  // "expected EXPECTED, got FOUND"
};

// Parses `text` whole; throws ExpressionError. Names are not resolved here (the caller knows
// which names exist); function names are, and a call's argument count is checked.
Expression parse_expression(std::string_view text);

// Every Name node of `e` (with its offset), left to right.
void collect_names(const Expression& e, std::vector<const Expression*>& names);

// The value of `e` with names looked up by `value_of_name` (for tests and checks; generated code
// is what runs).
double evaluate_expression(const Expression& e,
                           const std::function<double(const std::string&)>& value_of_name);

}  // namespace sympathy
