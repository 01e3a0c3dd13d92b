// Smith's soil (contact_law.hpp's smith toe, line.hpp's Shaft) for a
// one-step implicit scheme (newmark): its forces at t_{n+1} found by
// Newton's iteration around the scheme's step, as the plastic strains'
// (plastic_iteration.hpp).
//
// Each soil point (a shaft node, or the toe's node) resists along +x with
// g(u^{n+1}, v^{n+1}): the static spring with its slip from level n, and its
// damping at the new velocity. The step answers a load g at t_{n+1} by
// u^{n+1} += c A^{-1} g and v^{n+1} += r c A^{-1} g (newmark: c = beta dt^2,
// r = gamma / (beta dt)), so the residual g - G(U(g)) has the tangent
// I + K c A^{-1}, K the soil's diagonal stiffness at the step's u^{n+1}
// (its spring while elastic, and its damping's dependence on u and v):
//
//   (A + c K) du = c (G^ - g^k),   g^{k+1} = G(u^{n+1} + du, v^{n+1} + r du),
//
// and the step is taken again with g^{k+1}, until max |G^ - g^k| <= 1e-10
// of the soil's total capacity (far below any force a user reads, above the
// step's round-off). The law is piecewise smooth, so the iteration ends in a
// few steps; the first iterate is level n's force.
//
// Budget: the toe's spring energy and slip are its link's (E_obstacle,
// link_hysteresis); the shaft's springs k (w - s)^2 / 2 are E_obstacle, its
// slip R_u |s^{n+1} - s^n| and every point's damping, trapezoidal
// (d^n + d^{n+1}) (w^{n+1} - w^n) / 2, are D_contact; the scheme keeps the
// soil's forces out of W_ext. The static forces' trapezoidal work differs
// from stored energy plus slip only at the springs' kinks: the budget
// closes to O(dt^2) there, as the penalty links' does.
//
// A three-level scheme (line_paper.hpp, use_levels) steps the soil as the
// paper steps its loads: the force it applies at level m is
//
//   Phi^m = w_new R(u^{m+1}) + w_cur R^m + w_old R^{m-1} + eta^m (w^{m+1} - w^{m-1}) / (2 dt),
//
// the static springs R alpha-averaged over the three levels (the weights
// carry the exponential shift), the damping centred at t_m with level m's
// dashpot eta^m (J |R^m|, or J R_u while the point is in the soil), so that
// it dissipates exactly eta^m dt v^2; the toe's Phi is clipped at 0. Phi^m
// is continuous in u^{m+1}: the viscous toe has no face there. The unknown
// of the iteration is Phi^m, with c = u^{m+1}'s answer to it and r = 1/(2 dt).
// The reported level m then keeps its own slips (the springs' energy at u^m,
// the slip up to m) and books level m's damping as the scheme tests it,
// Phi^m's damping times (w^{m+1} - w^{m-1}) / 2, half of it up to t_m.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "barimpact/model/line.hpp"
#include "barimpact/model/tridiagonal.hpp"

namespace barimpact {

class SoilIteration {
 public:
  /// The largest number of steps taken for one level before the run fails.
  static constexpr int most_iterations = 30;

  SoilIteration() = default;
  /// The soil of `line`; `a` the scheme's matrix (the Newton solve makes
  /// the rows of `held` the identity), `c` and `r` as above (r finite: beta > 0).
  SoilIteration(const Line& line, const Tridiagonal& a, const std::vector<std::size_t>& held, double c, double r);

  /// The three-level form above: R(u^{m+1}), R^m and R^{m-1}'s weights.
  struct Levels {
    double new_level, current, old;
  };
  void use_levels(Levels w);

  [[nodiscard]] bool active() const { return !points_.empty(); }
  /// The toe's link, or Link::ground when the toe is not Smith's.
  [[nodiscard]] std::size_t toe_link() const { return toe_link_; }

  /// Level 0 at (u0, v0): the shaft's slip from a virgin soil, the forces.
  void start(const double* u0, const double* v0);
  /// The three-level form's level 1 at u1 (after start): its slips and
  /// static forces; level 0's damping over the first half step, dt/2 v0.
  void start_levels(const double* u1, const double* v0, double dt);
  /// f += the shaft's forces at level 0 (the toe's is its link's).
  void add_start_forces(double* f) const;
  /// The first iterate: level n's forces.
  void begin_step();
  /// f += g^k.
  void add_load(double* f) const;
  /// After the step with g^k reached (u, v) at t_{n+1}: true when g^k holds;
  /// otherwise g^{k+1} by Newton's update, and false.
  [[nodiscard]] bool settled(const double* u, const double* v);
  /// Level n + 1: the slips at (u, v), the damping's work since u_old
  /// (the three-level form: u_old = u^{m-1}, the centred increment).
  void accept(const double* u_old, const double* u);
  /// The force g^k on `node` (a held node's support carries it).
  [[nodiscard]] double load_on(std::size_t node) const;
  /// The toe's force at t_n (0 without Smith's toe).
  [[nodiscard]] double toe_force() const { return toe_force_; }
  /// The largest |G^ - g^k| / tolerance of the last check.
  [[nodiscard]] double misfit() const { return misfit_; }
  /// Why a run stops after most_iterations steps of one level.
  [[nodiscard]] std::string failure() const;

  /// The shaft springs' energy at u = scale u_kept, u^n.
  [[nodiscard]] double shaft_energy(const double* u_kept, double scale = 1.0) const;
  /// What the shaft's slip has dissipated up to t_n.
  [[nodiscard]] double shaft_slip_work() const { return slip_work_ - slip_last_; }
  /// What the soil's damping (toe and shaft) has dissipated up to t_n.
  [[nodiscard]] double damping_work() const { return damping_work_ - 0.5 * damping_last_; }

 private:
  struct Point {
    std::size_t node;
    bool toe;  // one way (compression), its state c_max; else a side spring, its state the slip
    double ultimate, quake, stiffness, smith, viscous;  // R_u, q, k, J (Smith's damping) or J R_u (viscous)
    double gap;                                         // the toe's: c = -(u + gap)
  };
  struct Resistance {
    double force = 0.0, damping = 0.0, tangent = 0.0;     // along +x; d force / d u is -tangent
    double state = 0.0;                                   // the slip, or c_max, this force implies
    double spring = 0.0, dashpot = 0.0, stiffness = 0.0;  // R_s, the law's eta and dR_s/dw at this u
  };
  /// Point i's resistance at (u, v) of its node, from level n's state: the
  /// law's (law_at) or the three-level form's Phi (level_at).
  [[nodiscard]] Resistance at(std::size_t i, double u, double v) const {
    return levels_ ? level_at(i, u, v) : law_at(i, u, v);
  }
  [[nodiscard]] Resistance law_at(std::size_t i, double u, double v) const;
  [[nodiscard]] Resistance level_at(std::size_t i, double u, double v) const;
  void newton(const double* u, const double* v);
  /// g^{k+1} of the toe (point i) on the step's line through it; du updated.
  void solve_toe(std::size_t i, const double* u, const double* v);
  void accept_level(const double* u_old, const double* u);
  /// Whether the toe (point i) holds on its face at (u, v) with force g^k.
  [[nodiscard]] bool on_face(std::size_t i, double u, double v) const;

  std::vector<Point> points_;
  std::size_t toe_link_ = Link::ground;
  Tridiagonal a_;
  std::vector<std::size_t> held_;
  double c_ = 0.0, r_ = 0.0, tolerance_ = 0.0;
  // Per point: level n's state (slip or c_max), force and damping; g^k;
  // G^ with its damping, state and tangent.
  std::vector<double> state_, force_, damping_, iterate_, trial_, trial_damping_, trial_state_, tangent_;
  std::vector<double> diag_, off_, du_;  // the tangent's solve
  std::vector<double> toe_du_;           // its answer to the toe's force
  double toe_force_ = 0.0, slip_work_ = 0.0, damping_work_ = 0.0, misfit_ = 0.0;
  // The three-level form: its weights; per point R^m, R^{m-1}, eta^m, level
  // m's state (state_ is then m + 1's once a step is accepted), the trial's R
  // and eta; the last level's slip and damping increments.
  bool levels_ = false;
  Levels weights_{1.0, 0.0, 0.0};
  std::vector<double> spring_, spring_old_, dashpot_, state_reported_, trial_spring_, trial_dashpot_;
  double slip_last_ = 0.0, damping_last_ = 0.0;
};

}  // namespace barimpact
