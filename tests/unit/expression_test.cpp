// A user's formula in x and t (expression.hpp): its values, which
// variables it uses, whether it is the constant zero, and the refusals of
// what does not parse or names another variable.
#include "barimpact/model/expression.hpp"

#include <gtest/gtest.h>

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
