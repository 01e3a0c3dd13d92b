// The penalty links of a line at the new level of an implicit one-step
// scheme (line_newmark.hpp), solved exactly. It owns the links' laws, their
// Delassus matrix W_ij = h_i . A^{-1} h_j and the branch each link was on at
// the last solve; it knows no line, no mesh and no time step. Given the
// free compressions and rates (every force 0),
//
//   c_i = cbar_i - alpha (W p)_i,   dc_i/dt = rbar_i - gamma (W p)_i,
//   p_i = law_i(c_i, dc_i/dt, c_max_i)   for every link i,
//
// (alpha = beta dt^2, gamma = gamma dt for Newmark) is a piecewise-linear
// system: each law is linear on each of its branches,
//
//   off        p = 0
//   on         p = k c (elastic, a cushion loading: c >= c_max),
//              p = k c + l dc/dt (viscoelastic, c > 0)
//   unloading  p = (k / e^2)(c - (1 - e^2) c_max)   (a cushion, (1 - e^2) c_max < c < c_max)
//   face       c = 0 with 0 <= p <= l dc/dt         (viscoelastic: the dashpot stops the
//              faces exactly where the law jumps; p = 0 for c < 0, k c + l dc/dt for c > 0)
//
// Active-set iteration: start from the branches of the last solve, solve the
// linear system of the current branches (one dense equation per link not
// off, Gaussian elimination with partial pivoting), then move every link
// whose compression, rate and force lie outside its branch's interval to the
// branch they lie on. Stopping rule: a pass that moves no link, within
// 1e-12 of the links' compression and force scales (so that round-off at a
// kink, where two branches give the same force, does not flip a link back
// and forth); the forces of that pass solve the system exactly, to the
// round-off of one small dense solve. A step that changes nothing settles in
// one pass, a link that closes or opens in two. Where links push each other
// hard (k alpha W of order 1 or more, links sharing a light body) the
// iteration can cycle among a few branch sets: after 8 passes without
// settling, Gauss-Seidel (each link's closed form in turn, i.e. exact
// minimisation along each link of the strictly convex energy whose
// stationary point this system is, so it converges) approaches the solution
// to 1e-6, the branches are read off it and the active set starts again
// from them; up to 4 such rounds, each sweeping 1000 times closer. Only
// then (never met in the tests) Gauss-Seidel alone finishes, to 1e-14 of the
// largest force.
#pragma once

#include <cstddef>
#include <vector>

#include "barimpact/model/contact_law.hpp"

namespace barimpact {

/// Solves the m x m system a x = b in place (a row-major, overwritten; x
/// into b) by Gaussian elimination with partial pivoting. False if a pivot
/// vanishes or is not finite.
bool solve_dense(std::size_t m, double* a, double* b);

class PenaltyLinks {
 public:
  enum class Branch : unsigned char { off, on, unloading, face };

  PenaltyLinks() = default;
  /// `delassus`: W, links x links, row-major, symmetric positive definite on
  /// the links that can push. Rigid laws are not allowed (their force is no law's).
  PenaltyLinks(std::vector<ContactLaw> laws, std::vector<double> delassus, double alpha, double gamma);

  /// The forces p (size links) for free compressions `cbar`, rates `rbar` and
  /// largest compressions so far `c_max`. Returns the active-set passes it
  /// took (0: Gauss-Seidel alone finished). Allocates nothing.
  int solve(const double* cbar, const double* rbar, const double* c_max, double* p);
  [[nodiscard]] std::size_t size() const { return laws_.size(); }
  [[nodiscard]] Branch branch(std::size_t i) const { return branch_[i]; }
  /// Every link's branch, where the next solve starts from (a scheme that
  /// takes a step again keeps them).
  [[nodiscard]] std::vector<Branch>& branches() { return branch_; }

 private:
  /// The branch that (c, rate, p) lie on, or `now` while they lie on it within the tolerances.
  [[nodiscard]] Branch indicated(std::size_t i, double c, double rate, double p, double c_max) const;
  /// The branch that (c, rate, p) lie on, whatever the link's branch was.
  [[nodiscard]] Branch branch_of(std::size_t i, double c, double rate, double p, double c_max) const;
  /// The linear system of the current branches, solved; false if singular.
  bool solve_branches(const double* cbar, const double* rbar, const double* c_max, double* p);
  bool move_branches(const double* cbar, const double* rbar, const double* c_max, const double* p, bool afresh);
  void gauss_seidel(const double* cbar, const double* rbar, const double* c_max, double* p, double to) const;

  std::vector<ContactLaw> laws_;
  std::vector<double> w_;  // W, row-major
  double alpha_ = 0.0, gamma_ = 0.0;
  std::vector<Branch> branch_;
  std::vector<std::size_t> active_;  // the links not off
  std::vector<double> matrix_, rhs_;
  double tol_c_ = 0.0, tol_p_ = 0.0;
};

}  // namespace barimpact
