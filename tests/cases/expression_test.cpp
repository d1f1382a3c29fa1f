// The expression grammar of equation case files (cases/expression.hpp): precedence, every
// function, and errors located at the character where the grammar stopped.
#include "sympathy/cases/expression.hpp"

#include <cmath>
#include <map>
#include <numbers>

#include <gtest/gtest.h>

namespace sympathy {
namespace {

double value(const std::string& text, std::map<std::string, double> names = {}) {
  names.emplace("pi", std::numbers::pi);
  return evaluate_expression(parse_expression(text),
                             [&](const std::string& name) { return names.at(name); });
}

ExpressionError error_of(const std::string& text) {
  try {
    parse_expression(text);
  } catch (const ExpressionError& e) {
    return e;
  }
  ADD_FAILURE() << "no error for: " << text;
  return {};
}

// Expected values by hand (exact in binary floating point, hence EXPECT_EQ).
TEST(Expression, PrecedenceAndAssociativity) {
  EXPECT_EQ(value("1 + 2 * 3"), 7.0);
  EXPECT_EQ(value("(1 + 2) * 3"), 9.0);
  EXPECT_EQ(value("8 / 4 / 2"), 1.0);    // left-associative
  EXPECT_EQ(value("10 - 4 - 3"), 3.0);   // left-associative
  EXPECT_EQ(value("2 ^ 3 ^ 2"), 512.0);  // right-associative: 2^9
  EXPECT_EQ(value("2 ** 3"), 8.0);       // Fortran's power too
  EXPECT_EQ(value("-2 ^ 2"), -4.0);      // -(2^2)
  EXPECT_EQ(value("2 ^ -1"), 0.5);       // a signed exponent
  EXPECT_EQ(value("-x * -y", {{"x", 3}, {"y", 2}}), 6.0);
  EXPECT_EQ(value("2 * x ^ 2", {{"x", 3}}), 18.0);
  EXPECT_EQ(value("+x - -x", {{"x", 1.5}}), 3.0);
  EXPECT_EQ(value("1.5e2 + .5 + 2.E-1 * 10"), 152.5);
  EXPECT_EQ(value(" \t 1\t+2 "), 3.0);
  EXPECT_EQ(value("1 +\n  2\r\n"), 3.0);  // line breaks separate tokens too
}

// Every function against the C library at an argument inside its domain.
TEST(Expression, EveryFunction) {
  const double x = 0.3, y = 1.7;
  const std::map<std::string, double> n{{"x", x}, {"y", y}};
  EXPECT_EQ(value("sin(x)", n), std::sin(x));
  EXPECT_EQ(value("cos(x)", n), std::cos(x));
  EXPECT_EQ(value("tan(x)", n), std::tan(x));
  EXPECT_EQ(value("exp(x)", n), std::exp(x));
  EXPECT_EQ(value("log(y)", n), std::log(y));
  EXPECT_EQ(value("sqrt(y)", n), std::sqrt(y));
  EXPECT_EQ(value("abs(-y)", n), y);
  EXPECT_EQ(value("tanh(x)", n), std::tanh(x));
  EXPECT_EQ(value("atan(y)", n), std::atan(y));
  EXPECT_EQ(value("asin(x)", n), std::asin(x));
  EXPECT_EQ(value("acos(x)", n), std::acos(x));
  EXPECT_EQ(value("sinh(x)", n), std::sinh(x));
  EXPECT_EQ(value("cosh(x)", n), std::cosh(x));
  EXPECT_EQ(value("pow(y, x)", n), std::pow(y, x));
  EXPECT_EQ(value("atan2(x, -y)", n), std::atan2(x, -y));
  EXPECT_EQ(value("min(x, y)", n), x);
  EXPECT_EQ(value("max(x, y)", n), y);
  EXPECT_EQ(value("sign_smooth(x, 0.1)", n), std::tanh(x / 0.1));
  // The header's claim: within 1e-8 of sign(x) beyond 10 eps (1 - tanh(10) = 2 e^-20 = 4.1e-9).
  EXPECT_LT(1.0 - value("sign_smooth(10, 1)"), 1e-8);
  // sign: +1 at and above zero, -1 below (the side a switching surface's region counts zero on).
  EXPECT_EQ(value("sign(x)", n), 1.0);
  EXPECT_EQ(value("sign(-x)", n), -1.0);
  EXPECT_EQ(value("sign(0)"), 1.0);
  EXPECT_EQ(functions().size(), 19u);
  for (const auto& f : functions()) EXPECT_EQ(&function_info(f.function), &f);
}

TEST(Expression, TreeKeepsOffsetsOfNames) {
  const Expression e = parse_expression("a*sin(bb) + c");
  std::vector<const Expression*> names;
  collect_names(e, names);
  ASSERT_EQ(names.size(), 3u);
  EXPECT_EQ(names[0]->name, "a");
  EXPECT_EQ(names[1]->name, "bb");
  EXPECT_EQ(names[1]->offset, 6u);
  EXPECT_EQ(names[2]->offset, 12u);
}

TEST(Expression, ErrorsSayWhereAndWhatWasExpected) {
  auto e = error_of("x + ");
  EXPECT_EQ(e.offset, 4u);
  EXPECT_EQ(e.message(),
            "expected a number, a name, a function call or '(', got the end of the "
            "expression");
  e = error_of("(x + 1");
  EXPECT_EQ(e.offset, 6u);
  EXPECT_NE(e.message().find("expected ')' closing the '('"), std::string::npos);
  e = error_of("x y");
  EXPECT_EQ(e.offset, 2u);
  EXPECT_EQ(e.message(), "expected an operator (+ - * / ^) or the end of the expression, got 'y'");
  e = error_of("foo(x)");
  EXPECT_EQ(e.offset, 0u);
  EXPECT_NE(e.message().find("expected a function (sin, cos,"), std::string::npos);
  e = error_of("pow(x)");
  EXPECT_NE(e.message().find("expected pow with 2 arguments, not 1"), std::string::npos);
  e = error_of("sin x");
  EXPECT_NE(e.message().find("expected '(' after the function sin"), std::string::npos);
  e = error_of("1e");
  EXPECT_NE(e.message().find("the digits of an exponent"), std::string::npos);
  e = error_of("2x");
  EXPECT_EQ(e.offset, 1u);
  e = error_of("1.2.3");
  EXPECT_EQ(e.offset, 3u);
  e = error_of("2*1e999");
  EXPECT_EQ(e.message(), "expected a finite number, got '1e999'");  // as typed (issue 32: '1')
  EXPECT_EQ(e.offset, 2u);
  e = error_of("x ** ");
  EXPECT_EQ(e.offset, 5u);
}

// Nothing but the grammar passes: every character a C++ (or shell) snippet needs is refused
// where it stands, with what stood there named (a byte outside ASCII by its code).
TEST(Expression, RefusesEverythingOutsideTheGrammar) {
  const std::map<std::string, std::size_t> smuggled{
      {"x; system(\"rm -rf /\")", 1},
      {"x } int main() {", 2},
      {"\"x\"", 0},
      {"'x'", 0},
      {"x // comment", 3},
      {"x /* c */", 3},
      {"#include <cstdlib>", 0},
      {"x\n#define y", 2},
      {"x\\", 1},
      {"std::system(0)", 3},
      {"x[0]", 1},
      {"x.y", 1},
      {"x = 1", 2},
      {"x, y", 1},
      {"a ? b : c", 2},
      {"x & y", 2},
      {"`ls`", 0},
      {"$(ls)", 0},
      {"x\xc2\xa0+ y", 1},  // a non-breaking space
      {"\xce\xb1", 0},      // a Greek alpha
  };
  for (const auto& [text, offset] : smuggled) {
    const auto e = error_of(text);
    EXPECT_EQ(e.offset, offset) << text;
  }
  EXPECT_EQ(error_of("x\xce\xb1").found, "byte 0xce (not ASCII)");
  EXPECT_EQ(error_of("x\x01").found, "byte 0x01");
}

TEST(Expression, RefusesOverlongInput) {
  EXPECT_NE(error_of(std::string(kMaxExpressionLength + 1, '1')).message().find("at most 4000"),
            std::string::npos);
  EXPECT_NE(error_of(std::string(kMaxNameLength + 1, 'a')).message().find("at most 64"),
            std::string::npos);
  const std::string deep = std::string(200, '(') + "x" + std::string(200, ')');
  EXPECT_NE(error_of(deep).message().find("levels of nesting"), std::string::npos);
  const std::string minus(300, '-');
  EXPECT_NE(error_of(minus + "x").message().find("levels of nesting"), std::string::npos);
  EXPECT_EQ(value(std::string(kMaxNameLength, 'a'), {{std::string(kMaxNameLength, 'a'), 2.0}}),
            2.0);
}

}  // namespace
}  // namespace sympathy
