// A user's formula in x and t (expression.hpp): its values, which
// variables it uses, whether it is the constant zero, and the refusals of
// what does not parse or names another variable.
#include "barimpact/model/expression.hpp"

#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <string>
#include <utility>

#include "barimpact/model/input_error.hpp"

namespace barimpact {
namespace {

// The message of a refused formula; a failure (and "") when it compiles.
std::string refusal(const std::string& text) {
  try {
    (void)Expression(text);
  } catch (const InputError& e) {
    return e.what();
  }
  ADD_FAILURE() << "accepted: " << text;
  return "";
}

// Values against the formulas evaluated by hand; exact in binary here.
TEST(Expression, EvaluatesInXAndT) {
  const Expression f("2 * x + t^2");
  EXPECT_EQ(f(3.0, 4.0), 22.0);
  EXPECT_EQ(f(-0.5, 0.0), -1.0);
  EXPECT_TRUE(f.depends_on_x());
  EXPECT_TRUE(f.depends_on_t());
  const Expression g("sin(0) + 0.25 * (1 - x)");
  EXPECT_EQ(g(0.5, 123.0), 0.125);
  EXPECT_TRUE(g.depends_on_x());
  EXPECT_FALSE(g.depends_on_t());
  const Expression h("t < 2 ? 1 : 0");
  EXPECT_EQ(h(0.0, 1.0), 1.0);
  EXPECT_EQ(h(0.0, 3.0), 0.0);
  EXPECT_FALSE(h.depends_on_x());
  // Evaluated many times, each call its own (x, t).
  const Expression product("x * t");
  EXPECT_EQ(product(2.0, 3.0), 6.0);
  EXPECT_EQ(product(5.0, 0.5), 2.5);
}

// The constant zero, however written; a formula that may be zero is not.
TEST(Expression, APlainNumberIsTheDoubleMuparserReads) {
  // A plain number skips the parser (a line of 10^5 masses has two a body):
  // the same bits as muparser gives it in parentheses, which it parses.
  for (const char* v : {"0", "-0", "3", "-1.5", "0.1", ".5", "5.", "1e-3", "-2.5E+2", "12345678901234567890",
                        "1.7976931348623157e308", "4.9e-324", "2.5e-1", "-.5e1", "0.30000000000000004"}) {
    const Expression plain(v);
    const Expression parsed(std::string("(") + v + ")");
    EXPECT_EQ(std::bit_cast<std::uint64_t>(plain(0.3, 0.7)), std::bit_cast<std::uint64_t>(parsed(0.3, 0.7))) << v;
    EXPECT_FALSE(plain.depends_on_x() || plain.depends_on_t()) << v;
  }
  EXPECT_TRUE(Expression("0").is_zero());
  EXPECT_TRUE(Expression("-0").is_zero());
  // Not plain: parsed, refused as before.
  for (const char* v : {"1e", "1e5x", "inf", "nan", "0x10", "+", "-"}) EXPECT_FALSE(refusal(v).empty()) << v;
}

// Issue 36: muparser accepts assignments (x=5 evaluates to 5 and sets x);
// they are refused, comparisons kept.
TEST(Expression, RefusesAnAssignment) {
  for (const char* text : {"x=5", "x = 5", "t+=1", "x-=1", "x*=2", "x/=2", "(x=2)*x", "1+(t=3)"})
    EXPECT_NE(refusal(text).find("assigns"), std::string::npos) << text << ": " << refusal(text);
  for (const char* text : {"x==5", "x<=1", "x>=0?1:0", "x!=1", "(x==0)*t"}) EXPECT_NO_THROW(Expression{text}) << text;
  EXPECT_EQ(Expression("x<=1")(0.5, 0.0), 1.0);
}

TEST(Expression, IsZeroOnlyForAConstantZero) {
  EXPECT_TRUE(Expression("0").is_zero());
  EXPECT_TRUE(Expression("1 - 1").is_zero());
  EXPECT_TRUE(Expression(" 0.0 * 5 ").is_zero());
  EXPECT_FALSE(Expression("1").is_zero());
  EXPECT_FALSE(Expression("0 * x").is_zero());  // uses x: not a constant
  EXPECT_FALSE(Expression("t").is_zero());
}

TEST(Expression, RefusesWhatDoesNotParseOrUsesAnotherVariable) {
  EXPECT_EQ(refusal("x + y"), "unknown name \"y\" (the variables are x and t)");
  EXPECT_EQ(refusal(""), "the expression is empty");
  EXPECT_EQ(refusal("  \t"), "the expression is empty");
  EXPECT_EQ(refusal(std::string("1\0+ x", 5)), "the expression holds a NUL character");
  EXPECT_NE(refusal("2 * ("), "");
  EXPECT_NE(refusal("x +"), "");
}

}  // namespace
}  // namespace barimpact
