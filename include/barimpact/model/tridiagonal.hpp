// Symmetric tridiagonal matrices and their solvers: every matrix of a line of
// bodies is one (line.hpp). The factored forms are computed once per run; the
// kernels that fuse their right-hand side into the sweeps read the factors.
#pragma once

#include <cstddef>
#include <span>
#include <vector>

namespace barimpact {

/// A symmetric tridiagonal matrix: `diag` has n entries, `off` n - 1.
struct Tridiagonal {
  std::vector<double> diag;
  std::vector<double> off;

  [[nodiscard]] std::size_t size() const { return diag.size(); }
  /// y = A x.
  void multiply(std::span<const double> x, std::span<double> y) const;
  /// x^T A x.
  [[nodiscard]] double quadratic_form(std::span<const double> x) const;
  /// c1 A + c2 B (same size).
  [[nodiscard]] static Tridiagonal combine(double c1, const Tridiagonal& a, double c2, const Tridiagonal& b);
  /// The same in A's storage: a line's matrices at 10^6 nodes are megabytes
  /// each, and a chain of combinations need not fault in one per link.
  [[nodiscard]] static Tridiagonal combine(double c1, Tridiagonal&& a, double c2, const Tridiagonal& b);
};

/// Solves A x = b in place by the Thomas algorithm, A symmetric tridiagonal
/// given by `diag` and `off` (both overwritten), its rows `held` made the
/// identity first (their b 0); `b2`, if given, a second right-hand side. The
/// Newton tangents of the plastic and soil iterations.
void solve_tangent(std::vector<double>& diag, std::vector<double>& off, const std::vector<std::size_t>& held,
                   std::span<double> b, std::span<double> b2 = {});

/// The factors of a symmetric positive definite tridiagonal matrix, computed
/// once, eliminated from the far end towards x = 0 (A = U L): the first sweep
/// runs from node n-1 to node 0, so that x_0, where the obstacle acts, is
/// known before the second sweep, and a force at node 0 found then (contact,
/// the obstacle's status) enters the solve at no extra pass. With `fix_last`
/// the last row is replaced by u_M = 0 (a clamped end).
class FactoredTridiagonal {
 public:
  FactoredTridiagonal() = default;
  FactoredTridiagonal(const Tridiagonal& a, bool fix_last);
  /// x <- A^{-1} x, in place.
  void solve(std::span<double> x) const;
  /// A^{-1} e_0: how the whole bar answers a unit force at x = 0; its first
  /// entry is inverse_pivots()[0].
  [[nodiscard]] std::vector<double> response_to_end_force() const;
  [[nodiscard]] std::size_t size() const { return inv_.size(); }
  /// The factors, for kernels that fuse their right-hand side and update into
  /// the sweeps:
  ///   towards x = 0:  y_{n-1} = r_{n-1},  y_j = r_j - coupling_{j+1} y_{j+1};
  ///   away from it:   x_0 = y_0 inv_0,    x_j = y_j inv_j - coupling_j x_{j-1},
  /// coupling_j = off_{j-1} inv_j (one multiply-subtract on each sweep's
  /// chain). A clamped last row has inv = coupling = 0, so r_{n-1} is ignored.
  [[nodiscard]] const double* inverse_pivots() const { return inv_.data(); }
  [[nodiscard]] const double* coupling() const { return coupling_.data(); }

 private:
  std::vector<double> inv_;       // 1 / pivot (0 on a fixed row)
  std::vector<double> coupling_;  // off_{j-1} / pivot_j (coupling_0 = 0)
};

/// The two-ended ("twisted") factors of a symmetric positive definite
/// tridiagonal matrix: rows 0..k-1 eliminated from row 0 down, rows
/// k+1..n-1 from row n-1 up, row k = (n-1)/2 last. A solve is then one sweep
/// inwards from both ends and one sweep outwards from row k, each carrying
/// two independent chains of multiply-subtracts (one per half), which a
/// latency-bound processor runs in the time of one: the paper scheme's solve
/// (paper_scheme.hpp) with per-row coefficients.
class TwistedTridiagonal {
 public:
  TwistedTridiagonal() = default;
  explicit TwistedTridiagonal(const Tridiagonal& a);
  [[nodiscard]] std::size_t size() const { return inv_.size(); }
  /// The twist row k = (n - 1) / 2.
  [[nodiscard]] std::size_t twist() const { return (inv_.size() - 1) / 2; }
  /// x = A^{-1} r into `x`, r_j = row(j) asked once per row, in the order of
  /// the sweeps inwards (r may be formed on the fly, and `x` may hold the
  /// inputs row(j) reads only at rows not yet reached).
  template <class Row>
  void solve(Row row, double* x) const {
    const std::size_t last = inv_.size() - 1, k = last / 2;
    double yt = 0.0, yb = 0.0;
    std::size_t jb = last;
    if (last > 2 * k) {  // the lower half's extra row
      inward(row(jb), jb, yb, x);
      --jb;
    }
    for (std::size_t j = 0; j < k; ++j, --jb) {
      inward(row(j), j, yt, x);
      inward(row(jb), jb, yb, x);
    }
    outward(row(k), yt, yb, x);
  }
  /// x <- A^{-1} x.
  void solve(double* x) const {
    solve([x](std::size_t j) { return x[j]; }, x);
  }
  /// The steps of a solve, for kernels that run the sweeps inwards
  /// themselves: row j with right-hand side r, j < k in the upper half's
  /// order (from row 0 down) or j > k in the lower half's (from row n - 1
  /// up), each half carrying its chain y; then row k and the sweep outwards.
  void inward(double r, std::size_t j, double& y, double* x) const {
    y = r * inv_[j] - inward_[j] * y;
    x[j] = y;
  }
  void outward(double r_twist, double y_top, double y_bottom, double* x) const {
    const std::size_t last = inv_.size() - 1, k = last / 2;
    const double* __restrict out = outward_.data();
    const double xk = (r_twist - lower_ * y_top - upper_ * y_bottom) * inv_[k];  // row k meets both halves
    x[k] = xk;
    double xt = xk, xb = xk;
    for (std::size_t i = 1; i <= k; ++i) {
      xt = x[k - i] - out[k - i] * xt;
      x[k - i] = xt;
      xb = x[k + i] - out[k + i] * xb;
      x[k + i] = xb;
    }
    for (std::size_t j = 2 * k + 1; j <= last; ++j) {  // the lower half's extra row
      xb = x[j] - out[j] * xb;
      x[j] = xb;
    }
  }

 private:
  std::vector<double> inv_;           // 1 / pivot
  std::vector<double> inward_;        // a row's coupling to the row eliminated before it, over its pivot
  std::vector<double> outward_;       // its coupling to the row solved before it on the way out, over its pivot
  double lower_ = 0.0, upper_ = 0.0;  // A_{k,k-1}, A_{k,k+1}
};

}  // namespace barimpact
