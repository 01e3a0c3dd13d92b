// `newmark` on a line of bodies: Newmark (beta, gamma) with consistent mass,
// as the single bar's (newmark_scheme.hpp), every penalty link solved at
// t_{n+1}:
//
//   M a^{n+1} + C v^{n+1} + K u^{n+1} = F^{n+1} + sum_i p_i^{n+1} h_i,
//   u^{n+1} = u^* + beta dt^2 a^{n+1},  v^{n+1} = v^* + gamma dt a^{n+1},
//
// h_i = e_b - e_a the link's direction, p_i its law at (u^{n+1}, v^{n+1}).
// A = M + gamma dt C + beta dt^2 K is factored once, with the rows of held
// nodes replaced by their prescribed accelerations; the links' responses
// w_i = A^{-1} h_i and the small Delassus matrix W_ij = h_i . w_j are
// computed once, so that a step is one solve, the links' piecewise-linear
// laws at t_{n+1} solved exactly together (penalty_links.hpp: an active-set
// iteration over the laws' branches, one small dense solve per pass, until
// a pass moves no link) and one update per active link.
// Budget of the trapezoidal rule: E_kin = v^T M v / 2, E_strain = u^T K u / 2
// (bar elements; springs in E_obstacle with the links' stored energy),
// dW = (u^{n+1} - u^n) . (F^n + F^{n+1}) / 2 with the end forces and the
// supports', dD = dt vbar^T C vbar plus the viscoelastic links' force beyond
// their spring's, trapezoidal; a cushion's hysteresis is D_contact.
#pragma once

#include <vector>

#include "barimpact/schemes/line_scheme.hpp"
#include "barimpact/schemes/penalty_links.hpp"

namespace barimpact {

class LineNewmark final : public LineScheme {
 public:
  LineNewmark(const Case& c, Line line);

  void start() override;
  void advance() override;
  [[nodiscard]] double displacement_at(std::size_t j) const override { return u_[j]; }
  [[nodiscard]] double velocity_at(std::size_t j) const override { return v_[j]; }
  [[nodiscard]] Energies energies() const override;
  [[nodiscard]] bool finite() const override;

 private:
  /// r = F(t) + end forces - C v - K u at every free row; held rows get `held`.
  void residual(const std::vector<double>& u, const std::vector<double>& v, double t, std::vector<double>& r);
  /// The links' forces at t_{n+1} (force_) given the free acceleration in rhs_.
  void solve_links();
  /// The held ends' prescribed accelerations at t_{n+1} into rhs_.
  void hold_ends(double t);
  void forward(double t);
  [[nodiscard]] double end_row(std::size_t j, double r, double t) const;
  void update(double t);
  void book_links(double t);
  [[nodiscard]] double support(std::size_t node, double t) const;

  double beta_, gamma_;
  Tridiagonal mass_, stiff_, visc_;
  std::vector<double> lower_, inv_pivot_, upper_;  // LU of A, the held rows made identity
  std::vector<std::size_t> held_;                  // nodes held by their ends
  std::vector<std::vector<double>> response_;      // w_i = A^{-1} h_i, per penalty link
  PenaltyLinks penalty_;                           // the links' laws and Delassus matrix W_ij = h_i . w_j
  std::vector<double> u_, v_, acc_, rhs_, work_;
  std::vector<double> load_old_, p_old_, c_old_, c_free_, rate_free_;
  std::vector<double> stiff_bond_, visc_bond_;  // k_j, c_j per bond
  std::vector<std::size_t> active_;             // links pushing this step
  double du_end_[2] = {0, 0};                   // the ends' u^{n+1} - u^n
  double step_work_ = 0.0, step_dissipation_ = 0.0;
  bool viscous_ = false;
  double support_old_[2] = {0, 0};
  double ext_work_ = 0.0, dissipation_ = 0.0;
};

}  // namespace barimpact
