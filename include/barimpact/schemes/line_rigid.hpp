// What the event-capturing rigid-contact schemes on a line share
// (line_moreau_jean.hpp, line_paoli_schatzman.hpp,
// line_mass_redistribution.hpp): each steps one tridiagonal matrix A of the
// line, factored once, and settles its rigid links afterwards through the
// precomputed responses A^{-1} h_i.
//
// Held ends. A clamped or velocity-driven end node's row of A becomes the
// identity (its couplings are zeroed), its unknown is known; the coupling
// A_{k,j} to its neighbour k moves to k's right-hand side. The row's own
// right-hand side, kept, gives the support's force afterwards:
// S = A_jj x_j + A_jk x_k - r_j, the residual of the original row.
//
// Sweeps. A = U L eliminated from the far end (FactoredTridiagonal). The
// sweep towards x = 0 forms each right-hand side r_j as it goes: inside a
// uniform stretch of a bar (both bonds the same element, no point mass,
// nothing special) from a stencil with constant coefficients, the single
// bar's; elsewhere (body ends, joints, masses, held ends and their
// neighbours, link faces) from the scheme's general row. So a step of a line
// costs about a step of one uniform bar of as many elements.
//
// Rigid links. Link i pushes its faces apart along h_i = e_b - e_a (a ground
// face dropped, a held face too: the support takes that share). Links are not
// assembled, so A is block diagonal over the clusters of nodes that bonds
// join, and w_i = A^{-1}(s h_i) is exactly zero outside the one or two
// clusters that link i touches: it is stored on that span only. A cluster is
// touched by at most the link on either side of it, so the Delassus operator
// D_kl = h_k^T w_l is tridiagonal in link order. The contact problem of a
// step, 0 <= p _|_ q + D p >= 0 on a set of links, is solved by projected
// Gauss-Seidel: exact in one sweep when no two of the links share a cluster,
// else to a change of |dp_k| D_kk <= 1e-13 max|q| per sweep (10^4 sweeps at
// most, never reached in the tests).
#pragma once

#include <cstddef>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "barimpact/model/line.hpp"
#include "barimpact/model/tridiagonal.hpp"
#include "barimpact/schemes/line_scheme.hpp"

namespace barimpact {

/// A held end's row of the scheme's matrix.
struct HeldRow {
  static constexpr std::size_t none = Link::ground;
  std::size_t node = 0;
  std::size_t neighbour = none;  ///< the node beside it (none on a one-node line)
  double diagonal = 0.0;         ///< A_jj before the row became the identity
  double coupling = 0.0;         ///< A_jk, moved to the neighbour's right-hand side
  bool near = true;              ///< the near end (else the far end)
  bool driven = false;           ///< driven at a velocity (else clamped)
  double value = 0.0;            ///< this step's known unknown x_j
  double before = 0.0;           ///< the node's state the step starts from (the scheme's)
  double rhs = 0.0;              ///< this step's original right-hand side r_j
  double support = 0.0;          ///< the support's share of the step (the scheme's units)
  /// The original row's residual A_jj x_j + A_jk x_k - r_j: the support's share.
  [[nodiscard]] double residual(const double* x) const {
    return diagonal * x[node] + (neighbour == none ? 0.0 : coupling * x[neighbour]) - rhs;
  }
};

/// Row j's right-hand side `r` as a step with held rows solves it: a held
/// row keeps r (the support's share is read from it) and gives its known
/// value; its neighbour's row moves the held node's coupling A_kj x_j to the
/// right-hand side.
inline double held_row(std::vector<HeldRow>& held, std::size_t j, double r) {
  for (auto& h : held)
    if (j == h.node) {
      h.rhs = r;
      return h.value;
    }
  for (const auto& h : held)
    if (j == h.neighbour) r -= h.coupling * h.value;
  return r;
}

/// The held ends of `line`, their rows of `a` made the identity.
[[nodiscard]] std::vector<HeldRow> hold_rows(const Line& line, Tridiagonal& a);
/// Their nodes.
[[nodiscard]] inline std::vector<std::size_t> held_nodes(const std::vector<HeldRow>& rows) {
  std::vector<std::size_t> nodes;
  for (const HeldRow& h : rows) nodes.push_back(h.node);
  return nodes;
}

/// The near and far forces history reports (compressions > 0, line_scheme.hpp):
/// an end's link force, else its force end's value, else its support's
/// force (HeldRow::support times `support_scale`).
struct EndReport {
  double near = 0.0, far = 0.0;
};
[[nodiscard]] EndReport end_report(const Line& line, const std::vector<double>& link_force, double near_value,
                                   double far_value, const std::vector<HeldRow>& held, double support_scale);

/// Interior nodes [first, last) of one uniform run of bar elements: bonds
/// first - 1 .. last - 1 identical, no point mass, none of the nodes special.
struct Stretch {
  std::size_t first, last;
};

/// The stretches of `line` avoiding the nodes flagged in `special` (held ends
/// and their neighbours are always special; so are nodes 0 and n - 1).
[[nodiscard]] std::vector<Stretch> uniform_stretches(const Line& line, std::vector<unsigned char> special,
                                                     const std::vector<HeldRow>& held);

/// The sweep of `f` towards x = 0, y_j = r_j - coupling_{j+1} y_{j+1}, with r_j
/// = stencil(s)(j) inside stretch s (the stencil built once per stretch,
/// its coefficients constants of the loop) and special(j) elsewhere.
template <class MakeStencil, class Special>
inline void sweep_towards_near(const FactoredTridiagonal& f, const std::vector<Stretch>& stretches, MakeStencil stencil,
                               Special special, double* __restrict y) {
  const double* __restrict cp = f.coupling();
  const std::size_t n = f.size();
  double carry = 0.0;
  std::size_t j = n;  // rows j.. are done
  auto one = [&](std::size_t i) {
    const double r = special(i);
    carry = i + 1 < n ? r - cp[i + 1] * carry : r;
    y[i] = carry;
  };
  for (auto s = stretches.rbegin(); s != stretches.rend(); ++s) {
    for (; j > s->last; --j) one(j - 1);
    const auto row = stencil(*s);
    for (; j > s->first; --j) {
      carry = row(j - 1) - cp[j] * carry;
      y[j - 1] = carry;
    }
  }
  for (; j > 0; --j) one(j - 1);
}

/// The sweep back, x_0 = y_0 inv_0, x_j = y_j inv_j - coupling_j x_{j-1},
/// each x_j handed to update(j, x_j) as it is found (which may overwrite y_j).
template <class Update>
inline void sweep_away(const FactoredTridiagonal& f, const double* y, Update update) {
  const double* __restrict inv = f.inverse_pivots();
  const double* __restrict cp = f.coupling();
  double x = y[0] * inv[0];
  update(std::size_t{0}, x);
  for (std::size_t j = 1; j < f.size(); ++j) {
    x = y[j] * inv[j] - cp[j] * x;
    update(j, x);
  }
}

/// The rigid links of a line, their responses and their Delassus operator.
class RigidLinks {
 public:
  RigidLinks() = default;
  /// Responses w_k = A^{-1}(scale h_k) through `factor` (A's held rows the
  /// identity). Links whose faces cannot move (D_kk = 0) are left out.
  RigidLinks(const Line& line, const FactoredTridiagonal& factor, double scale);

  [[nodiscard]] std::size_t size() const { return link_.size(); }
  /// Link k's index in line.links.
  [[nodiscard]] std::size_t link(std::size_t k) const { return link_[k]; }
  [[nodiscard]] double restitution(std::size_t k) const { return restitution_[k]; }
  /// h_k^T x: the opening's change (or rate) that x gives link k.
  [[nodiscard]] double along(std::size_t k, const double* x) const {
    return (b_[k] == Link::ground ? 0.0 : x[b_[k]]) - (a_[k] == Link::ground ? 0.0 : x[a_[k]]);
  }
  /// Solves 0 <= p _|_ q + D p >= 0 over the links with active[k] (p_k = 0
  /// for the others). Returns the sweeps taken.
  int solve(const double* q, const unsigned char* active, double* p) const;
  /// x += s sum_k p_k w_k, each response on its span only.
  void add_responses(const double* p, double s, double* x) const;
  /// The force sum_k p_k h_k puts on node j (a held face's share).
  [[nodiscard]] double on_node(std::size_t j, const double* p) const;

  static constexpr double tolerance = 1e-13;
  static constexpr int max_sweeps = 10000;

 private:
  [[nodiscard]] double response_at(std::size_t k, std::size_t j) const {
    return j == Link::ground || j < first_[k] || j >= first_[k] + response_[k].size() ? 0.0
                                                                                      : response_[k][j - first_[k]];
  }

  std::vector<std::size_t> link_, a_, b_, first_;
  std::vector<std::vector<double>> response_;
  std::vector<double> restitution_, diag_, lower_;  // D_kk, D_{k,k-1}
  bool coupled_ = false;                            // some D_{k,k-1} != 0
};

/// What mass redistribution cannot run beyond its laws (registry.hpp): a
/// dashpot, a rigid link's face on a point mass or on a bar of one element.
[[nodiscard]] std::optional<SchemeMisfit> redistribution_misfit(const Case& c, const Line& line);

}  // namespace barimpact
