// `moreau-jean`: the velocity-level theta-scheme of Moreau (1988) and Jean
// (1999) with per-bond coefficients, every
// rigid link under Newton's impact law:
//
//   M (v^{n+1} - v^n) = dt (theta f^{n+1} + (1 - theta) f^n) + sum_i p_i h_i,
//   u^{n+1} = u^n + dt (theta v^{n+1} + (1 - theta) v^n),   f = F - K u - C v,
//   link i active when y_i^n + (dt/2) ydot_i^n <= 0, and then
//   0 <= p_i _|_ ydot_i^{n+1} + e_i ydot_i^n >= 0,
//
// M consistent (point masses on its diagonal), F the body force, gravity and
// the force ends' values. W = M + theta dt C + theta^2 dt^2 K is factored
// once; a step forms P v + Q u + loads inside the sweep towards x = 0
// (P = M - dt^2 theta (1 - theta) K - dt (1 - theta) C, Q = -dt K: per bond
// the tension alpha_j dv_j + beta_j du_j), updates v and u in the sweep back,
// and only then settles the active links: ydot^{n+1} = q + D p with q the free
// rates plus e ydot^n, D = H W^{-1} H^T (line_rigid.hpp), v += p w,
// u += dt theta p w. A held node's v^{n+1} is its end's v(t_{n+1}) (0 when
// clamped, and v^0 = v(0)); its support's impulse is its row's residual.
// History reports p / dt.
//
// Budget (theta = 1/2): tested with (v^n + v^{n+1}) / 2 the step gives
// dE_kin + dE_strain + dE_springs = dt vbar . F^{n+1/2} - dt vbar^T C vbar
// + sum_i p_i (ydot_i^n + ydot_i^{n+1}) / 2 exactly: W_ext books the loads'
// (du . (F^n + F^{n+1}) / 2) and the supports' (S vbar) work, D_visc the
// viscous term, D_contact -p_i (ydot_i^n + ydot_i^{n+1}) / 2 =
// (1 - e_i) p_i |ydot_i^n| / 2 >= 0 at an impact. theta > 1/2 damps on top.
// Elastic-plastic bodies: the plastic strains' load G p at t_{n+1}, found
// by the Newton iteration of plastic_iteration.hpp around this step.
#pragma once

#include <vector>

#include "barimpact/schemes/line_rigid.hpp"
#include "barimpact/schemes/line_scheme.hpp"

namespace barimpact {

class LineMoreauJean final : public LineScheme {
 public:
  LineMoreauJean(const Case& c, Line line);

  void start() override;
  void advance() override;
  [[nodiscard]] double displacement_at(std::size_t j) const override { return u_[j]; }
  [[nodiscard]] double velocity_at(std::size_t j) const override { return v_[j]; }
  [[nodiscard]] Energies energies() const override;
  [[nodiscard]] bool finite() const override;

 private:
  void advance_elastic();
  /// The step without the rigid links: v^{n+1}, u^{n+1} in u_, v_.
  template <bool loaded>
  void free_step();
  /// r_j = (P v + Q u)_j + dt (theta F^{n+1} + (1 - theta) F^n)_j at any node.
  template <bool loaded>
  [[nodiscard]] double row(std::size_t j) const;
  /// row(j) with the ends: force values, held rows and their neighbours.
  template <bool loaded>
  [[nodiscard]] double special_row(std::size_t j);
  /// Which links are active at t_n, their rates ydot^n.
  void predict_contacts();
  /// Newton's law on the active links: p, then v and u corrected.
  void settle_contacts();
  void end_forces(double t1);
  void book_budget(double t0, double t1);

  double theta_;
  Tridiagonal mass_;                              // M, for E_kin
  FactoredTridiagonal factor_;                    // W, held rows the identity
  std::vector<double> alpha_, beta_, viscosity_;  // per bond: P's and Q's tension coefficients, c_j
  std::vector<Stretch> stretches_;
  std::vector<HeldRow> held_;
  RigidLinks rigid_;
  std::vector<double> u_, v_, u_old_, v_old_, y_, load_old_;
  std::vector<double> rate_old_, q_, p_;  // per rigid link
  std::vector<unsigned char> active_;
  bool any_active_ = false, viscous_ = false;
  double near_impulse_ = 0.0, far_impulse_ = 0.0;  // force ends: dt (theta f(t_{n+1}) + (1 - theta) f(t_n))
  double near_u_old_ = 0.0, far_u_old_ = 0.0;
  double work_ = 0.0, dissipation_ = 0.0, contact_ = 0.0;
  // The state a step changes, as one value (state.hpp): u first.
  auto state() {
    return std::tie(u_, load_, force_, c_max_, near_force_, far_force_, v_, load_old_, work_, dissipation_, contact_);
  }
  void keep_state() override { kept_.keep(state()); }
  void restore_state() override { kept_.restore(state()); }
  [[nodiscard]] const double* kept_displacement() const override { return kept_.get<0>().data(); }
  KeptState<std::vector<double>, std::vector<double>, std::vector<double>, std::vector<double>, double, double,
            std::vector<double>, std::vector<double>, double, double, double>
      kept_;
};

}  // namespace barimpact
