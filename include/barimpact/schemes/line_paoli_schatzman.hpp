// `paoli-schatzman`: central differences with the consistent mass
// (Paoli & Schatzman 2002) and per-bond coefficients,
//
//   M (u^{n+1} - 2 u^n + u^{n-1}) / dt^2 = F^n + N_j^n - N_{j-1}^n + P^n + sum_i mu_i h_i / dt^2,
//   N_j = k_j (u_{j+1} - u_j)^n + c_j ((u_{j+1} - u_j)^n - (u_{j+1} - u_j)^{n-1}) / dt,
//
// P the penalty links' forces at t_n (as central-difference's: explicit,
// their rates by a backward difference) and the force ends' values. Every
// rigid link i holds its restitution-weighted opening,
//   (y_i^{n+1} + e_i y_i^{n-1}) / (1 + e_i) >= 0,
// by the projection of the free u^{n+1} in the kinetic metric along
// w_i = M^{-1} h_i: 0 <= mu _|_ q + D mu >= 0, q_i = y_i^{free} + e_i y_i^{n-1},
// D = H M^{-1} H^T (line_rigid.hpp), u^{n+1} += sum_i mu_i w_i; the force
// reported is mu_i / dt^2. Links that share no body are projected
// independently (exact in one sweep). A clamped node stays at 0, a node
// driven at v(t) moves by dt v(t_{n+1/2}). M is factored once; a step forms
// the forces inside its first sweep and u^{n+1} inside the second. Explicit
// in K: a step above line_stable_step(line, true) is refused.
//
// Budget: as central-difference's (line_central_difference.hpp) with
// H^{n+1/2} = |w|_M^2 / 2 + (u^n)^T K u^{n+1} / 2: the rigid links' work is
// D_contact, exact by the scheme's identity; a penalty link's energy is its
// law's at u^n (O(dt^2)), a cushion's hysteresis is D_contact.
// Elastic-plastic bodies as central-difference's (plastic_bonds.hpp): the
// axial forces at t_n from the return map at u^n, D_plastic by the same
// identity (the consistent mass changes only the kinetic energy).
#pragma once

#include <array>
#include <vector>

#include "barimpact/schemes/line_rigid.hpp"
#include "barimpact/schemes/line_scheme.hpp"
#include "barimpact/schemes/plastic_bonds.hpp"

namespace barimpact {

class LinePaoliSchatzman final : public LineScheme {
 public:
  LinePaoliSchatzman(const Case& c, Line line);

  void start() override;
  void advance() override;
  [[nodiscard]] double displacement_at(std::size_t j) const override { return cur_[j]; }
  [[nodiscard]] double velocity_at(std::size_t j) const override {
    return n_ == 0 ? v0_[j] : (next_[j] - prev_[j]) / (2.0 * dt_);
  }
  [[nodiscard]] Energies energies() const override;
  [[nodiscard]] bool finite() const override;
  [[nodiscard]] double plastic_strain(std::size_t bond) const override {
    return plastic_.active() ? plastic_.current()[bond] : 0.0;
  }
  [[nodiscard]] double plastic_work(std::size_t body) const override { return plastic_.body_work(body); }

 private:
  /// up = 2 u - um + scale M^{-1} r, r the forces at level u (rates from um),
  /// at time t; scale = dt^2, or dt^2 / 2 for the start's Taylor step.
  void predict(const double* um, const double* u, double* up, double t, double scale);
  template <bool viscous, bool loaded>
  void sweeps(const double* um, const double* u, double* up, double scale);
  /// F_j + N_j - N_{j-1} + P_j at any node, then the held rows.
  [[nodiscard]] double special_row(const double* um, const double* u, std::size_t j);
  /// The rigid links' projection; `before` is u^{n-1}.
  void project(const double* before, double* up, double force_scale);
  void end_forces(const double* um, const double* u, const double* up, double t, double scale);
  void book_budget(const double* um, const double* u, const double* up, double& dw, double& dd, double& dc) const;
  [[nodiscard]] double half_step_kinetic(const double* a, const double* b) const;

  Tridiagonal mass_;            // M, for E_kin and the supports
  FactoredTridiagonal factor_;  // M, held rows the identity
  std::vector<double> k_, c_;   // per bond
  std::vector<double> extra_;   // forces at t_n on the link faces and force ends
  std::vector<std::size_t> extra_nodes_;
  std::vector<double> target_;  // held rows' u^{n+1}
  std::vector<Stretch> stretches_;
  std::vector<HeldRow> held_;
  RigidLinks rigid_;
  PlasticBonds plastic_;  // the elastic-plastic elements' state (none: every body elastic)
  std::vector<double> q_, mu_;
  std::vector<unsigned char> all_;
  std::array<std::vector<double>, 3> levels_;
  double* prev_ = nullptr;
  double* cur_ = nullptr;
  double* next_ = nullptr;
  bool viscous_ = false;
  CentredBudget budget_;
};

}  // namespace barimpact
