#include "barimpact/model/tridiagonal.hpp"

#include "barimpact/model/setup_polling.hpp"

#include <array>
#include <cassert>
#include <cmath>
#include <utility>

namespace barimpact {

void Tridiagonal::multiply(std::span<const double> x, std::span<double> y) const {
  const std::size_t n = size();
  assert(x.size() == n && y.size() == n);
  for (std::size_t i = 0; i < n; ++i) {
    double s = diag[i] * x[i];
    if (i > 0) s += off[i - 1] * x[i - 1];
    if (i + 1 < n) s += off[i] * x[i + 1];
    y[i] = s;
  }
}

double Tridiagonal::quadratic_form(std::span<const double> x) const {
  double s = 0.0;
  for (std::size_t i = 0; i < size(); ++i) s += diag[i] * x[i] * x[i];
  for (std::size_t i = 0; i + 1 < size(); ++i) s += 2.0 * off[i] * x[i] * x[i + 1];
  return s;
}

Tridiagonal Tridiagonal::combine(double c1, const Tridiagonal& a, double c2, const Tridiagonal& b) {
  return combine(c1, Tridiagonal{a.diag, a.off}, c2, b);
}

Tridiagonal Tridiagonal::combine(double c1, Tridiagonal&& a, double c2, const Tridiagonal& b) {
  poll_setup();  // line-sized: a study's case polls its interrupt between such phases
  assert(a.size() == b.size());
  Tridiagonal r = std::move(a);
  for (std::size_t i = 0; i < r.diag.size(); ++i) r.diag[i] = c1 * r.diag[i] + c2 * b.diag[i];
  for (std::size_t i = 0; i < r.off.size(); ++i) r.off[i] = c1 * r.off[i] + c2 * b.off[i];
  return r;
}

FactoredTridiagonal::FactoredTridiagonal(const Tridiagonal& a, bool fix_last) {
  poll_setup();
  const std::size_t n = a.size();
  inv_.assign(n, 0.0);
  coupling_.assign(n, 0.0);
  // Pivots from the far end: p_{n-1} = d_{n-1}, p_j = d_j - off_j^2 / p_{j+1}.
  // A fixed last row drops out: inv = 0 there, and p_{n-2} = d_{n-2}.
  inv_[n - 1] = fix_last ? 0.0 : 1.0 / a.diag[n - 1];
  for (std::size_t j = n - 1; j-- > 0;) {
    coupling_[j + 1] = a.off[j] * inv_[j + 1];
    inv_[j] = 1.0 / (a.diag[j] - a.off[j] * coupling_[j + 1]);
  }
}

void FactoredTridiagonal::solve(std::span<double> x) const {
  const std::size_t n = inv_.size();
  if (inv_[n - 1] == 0.0) x[n - 1] = 0.0;  // the fixed row
  for (std::size_t j = n - 1; j-- > 0;) x[j] -= coupling_[j + 1] * x[j + 1];
  x[0] *= inv_[0];
  for (std::size_t j = 1; j < n; ++j) x[j] = x[j] * inv_[j] - coupling_[j] * x[j - 1];
}

std::vector<double> FactoredTridiagonal::response_to_end_force() const {
  std::vector<double> w(inv_.size(), 0.0);
  w[0] = 1.0;
  solve(w);
  return w;
}

TwistedTridiagonal::TwistedTridiagonal(const Tridiagonal& a) {
  const std::size_t n = a.size(), last = n - 1, k = last / 2;
  const std::vector<double>&d = a.diag, &o = a.off;
  inv_.assign(n, 0.0);
  inward_.assign(n, 0.0);
  outward_.assign(n, 0.0);
  for (std::size_t j = 0; j < k; ++j) {  // p_j = d_j - o_{j-1}^2 / p_{j-1}
    inv_[j] = 1.0 / (d[j] - (j > 0 ? o[j - 1] * o[j - 1] * inv_[j - 1] : 0.0));
    inward_[j] = j > 0 ? o[j - 1] * inv_[j] : 0.0;
    outward_[j] = o[j] * inv_[j];
  }
  for (std::size_t j = last; j > k; --j) {  // p_j = d_j - o_j^2 / p_{j+1}
    inv_[j] = 1.0 / (d[j] - (j < last ? o[j] * o[j] * inv_[j + 1] : 0.0));
    inward_[j] = j < last ? o[j] * inv_[j] : 0.0;
    outward_[j] = o[j - 1] * inv_[j];
  }
  lower_ = k > 0 ? o[k - 1] : 0.0;
  upper_ = k < last ? o[k] : 0.0;
  inv_[k] =
      1.0 / (d[k] - (k > 0 ? lower_ * lower_ * inv_[k - 1] : 0.0) - (k < last ? upper_ * upper_ * inv_[k + 1] : 0.0));
}

void solve_tangent(std::vector<double>& diag, std::vector<double>& off, const std::vector<std::size_t>& held,
                   std::span<double> b, std::span<double> b2) {
  const std::size_t n = diag.size();
  const bool two = !b2.empty();
  for (std::size_t j : held) {
    diag[j] = 1.0;
    b[j] = 0.0;
    if (two) b2[j] = 0.0;
    if (j > 0) off[j - 1] = 0.0;
    if (j + 1 < n) off[j] = 0.0;
  }
  // Forward elimination, diag becoming the inverse pivots (one division a
  // row), then back substitution.
  diag[0] = 1.0 / diag[0];
  for (std::size_t j = 1; j < n; ++j) {
    const double m = off[j - 1] * diag[j - 1];
    diag[j] = 1.0 / (diag[j] - m * off[j - 1]);
    b[j] -= m * b[j - 1];
    if (two) b2[j] -= m * b2[j - 1];
  }
  b[n - 1] *= diag[n - 1];
  for (std::size_t j = n - 1; j-- > 0;) b[j] = (b[j] - off[j] * b[j + 1]) * diag[j];
  if (!two) return;
  b2[n - 1] *= diag[n - 1];
  for (std::size_t j = n - 1; j-- > 0;) b2[j] = (b2[j] - off[j] * b2[j + 1]) * diag[j];
}

}  // namespace barimpact
