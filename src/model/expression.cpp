#include "barimpact/model/expression.hpp"

#include <fmt/format.h>

#include <muParser.h>

#include "barimpact/model/input_error.hpp"

namespace barimpact {

struct Expression::Impl {
  mu::Parser parser;
  double x = 0.0;
  double t = 0.0;
};

Expression::Expression(const std::string& text) : impl_(std::make_unique<Impl>()) {
  if (text.find_first_not_of(" \t\r\n") == std::string::npos) throw InputError("the expression is empty");
  // muparser stops reading at a NUL: the rest would be silently ignored.
  if (text.find('\0') != std::string::npos) throw InputError("the expression holds a NUL character");
  try {
    impl_->parser.DefineVar("x", &impl_->x);
    impl_->parser.DefineVar("t", &impl_->t);
    impl_->parser.SetExpr(text);
    for (const auto& [name, ptr] : impl_->parser.GetUsedVar()) {
      if (name == "x") uses_x_ = true;
      if (name == "t") uses_t_ = true;
    }
    (void)impl_->parser.Eval();  // muparser parses lazily: make it parse now
  } catch (const mu::Parser::exception_type& e) {
    if (e.GetCode() == mu::ecUNASSIGNABLE_TOKEN)
      throw InputError(fmt::format("unknown name \"{}\" (the variables are x and t)", e.GetToken()));
    throw InputError(e.GetMsg());
  }
}

Expression::~Expression() = default;
Expression::Expression(Expression&&) noexcept = default;
Expression& Expression::operator=(Expression&&) noexcept = default;

double Expression::operator()(double x, double t) const {
  impl_->x = x;
  impl_->t = t;
  return impl_->parser.Eval();
}

bool Expression::is_zero() const {
  return !uses_x_ && !uses_t_ && (*this)(0.0, 0.0) == 0.0;
}

}  // namespace barimpact
