#include "barimpact/model/expression.hpp"

#include <fmt/format.h>

#include <muParser.h>

#include <cctype>
#include <charconv>
#include <cmath>
#include <optional>
#include <string_view>

#include "barimpact/model/input_error.hpp"

namespace barimpact {

struct Expression::Impl {
  mu::Parser parser;
  double x = 0.0;
  double t = 0.0;
};

namespace {

// `text` as a number when it is one written plainly, [-]digits[.digits][e[+-]digits]
// (muparser reads it to the same double), else nothing.
std::optional<double> plain_number(std::string_view text) {
  std::size_t i = text.starts_with('-') ? 1 : 0;
  const auto digits = [&] {
    const std::size_t from = i;
    while (i < text.size() && std::isdigit(static_cast<unsigned char>(text[i])) != 0) ++i;
    return i - from;
  };
  std::size_t mantissa = digits();
  if (i < text.size() && text[i] == '.') {
    ++i;
    mantissa += digits();
  }
  if (mantissa == 0) return std::nullopt;
  if (i < text.size() && (text[i] == 'e' || text[i] == 'E')) {
    ++i;
    if (i < text.size() && (text[i] == '+' || text[i] == '-')) ++i;
    if (digits() == 0) return std::nullopt;
  }
  double v = 0.0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  if (i != text.size() || ec != std::errc() || end != text.data() + text.size() || !std::isfinite(v))
    return std::nullopt;
  return v;
}

// True when `text` holds an assignment (x = 5, t += 1), which muparser
// accepts, and which would set the variable rather than compare it: an "="
// that is not part of ==, !=, <= or >=.
bool assigns(std::string_view text) {
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (text[i] != '=') continue;
    if (i + 1 < text.size() && text[i + 1] == '=') {
      ++i;  // ==
      continue;
    }
    if (i > 0 && (text[i - 1] == '!' || text[i - 1] == '<' || text[i - 1] == '>')) continue;
    return true;
  }
  return false;
}

}  // namespace

Expression::Expression(const std::string& text) {
  // A plain number (a mass's velocity, most initial conditions) needs no
  // parser: setting one up costs some 10 us, and a line of 10^5 masses has
  // two such numbers a body.
  if (const auto v = plain_number(text)) {
    constant_ = *v;
    return;
  }
  if (text.find_first_not_of(" \t\r\n") == std::string::npos) throw InputError("the expression is empty");
  // muparser stops reading at a NUL: the rest would be silently ignored.
  if (text.find('\0') != std::string::npos) throw InputError("the expression holds a NUL character");
  if (assigns(text)) throw InputError("\"=\" assigns a variable: give a formula in x and t (to compare, write ==)");
  impl_ = std::make_unique<Impl>();
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
  if (!impl_) return constant_;
  impl_->x = x;
  impl_->t = t;
  return impl_->parser.Eval();
}

bool Expression::is_zero() const {
  return !uses_x_ && !uses_t_ && (*this)(0.0, 0.0) == 0.0;
}

}  // namespace barimpact
