// A user's formula in x and t (body force, initial displacement, velocity),
// compiled once by muparser and evaluated many times.
//
// Owns the parsing and the check that only x and t are used. Does not know
// which key it came from: callers wrap its errors with the key's name.
#pragma once

#include <memory>
#include <string>

namespace barimpact {

class Expression {
 public:
  /// Compiles `text` in the variables x and t. Throws InputError (without a
  /// key name) when it does not parse or uses another variable.
  explicit Expression(const std::string& text);
  ~Expression();
  Expression(Expression&&) noexcept;
  Expression& operator=(Expression&&) noexcept;
  Expression(const Expression&) = delete;
  Expression& operator=(const Expression&) = delete;

  /// f(x, t). Not thread-safe: one Expression per thread.
  [[nodiscard]] double operator()(double x, double t) const;
  [[nodiscard]] bool depends_on_t() const { return uses_t_; }
  [[nodiscard]] bool depends_on_x() const { return uses_x_; }
  /// True when the text is a constant that evaluates to 0.
  [[nodiscard]] bool is_zero() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;  // none for a plain number, which is constant_
  double constant_ = 0.0;
  bool uses_x_ = false;
  bool uses_t_ = false;
};

}  // namespace barimpact
