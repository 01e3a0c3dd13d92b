// `mass-redistribution`: the idea of Khenous, Laborde & Renard (2008) at
// every rigid link. Each face of a rigid
// link gives its share of its element's mass to its inner neighbour (the
// element's m/6 [[2, 1], [1, 2]] becomes m on the inner node: the body's mass
// is kept), so the face carries no inertia and is in static equilibrium at
// every t_{n+1}:
//
//   (K u^{n+1})_f = F_f^{n+1} + (H lambda^{n+1})_f,  0 <= lambda _|_ y^{n+1} >= 0,
//
// while every other node follows Crank-Nicolson with the redistributed mass M~:
//   M~ (v^{n+1} - v^n) = dt (Fbar - K (u^n + u^{n+1}) / 2),  u^{n+1} - u^n = dt (v^n + v^{n+1}) / 2.
//
// Both kinds of row are rows of one symmetric tridiagonal matrix,
// A = 2 M~ / dt^2 + K / 2 (the faces' rows are their equilibrium halved), so
// that one factorisation serves every status pattern: a step solves the free
// problem (every face in equilibrium with lambda = 0), then decides each
// link's status by the small problem 0 <= lambda _|_ q + D lambda >= 0, q the
// free openings, D = H A^{-1} H^T / 2 (line_rigid.hpp), and adds
// lambda_i A^{-1} h_i / 2 (the capacitance form of Sherman-Morrison: no
// factorisation per status). On one bar this is the single bar's two
// factorisations that differ in node 1's pivot, and the same numbers. A
// face's velocity is the backward difference (u^{n+1} - u^n) / dt. A held node's
// u^{n+1} is u^n + dt (v(t_n) + v(t_{n+1})) / 2 (0 when clamped, v^0 = v(0)).
// History reports lambda.
//
// Refused (line_scheme_misfit): penalty links, viscosity, and rigid links
// touching a mass body (a point mass cannot give its mass away) or a bar of
// one element between two rigid links.
//
// Budget: testing the Crank-Nicolson rows with u^{n+1} - u^n gives
// dE_kin + dE_strain + dE_springs = du . Fbar + sum_f du_f (rho_f^n + rho_f^{n+1}) / 2,
// rho_f = (K u)_f - F_f the face's imbalance, (H lambda)_f from t_1 on: that
// last term, the work of the links across the step's status change, is
// -D_contact; the budget closes to round-off. The supports' work S du is in
// W_ext.
// Elastic-plastic bodies: the plastic strains' load G p at t_{n+1}, found
// by the Newton iteration of plastic_iteration.hpp around this step.
#pragma once

#include <vector>

#include "barimpact/schemes/line_rigid.hpp"
#include "barimpact/schemes/line_scheme.hpp"

namespace barimpact {

class LineMassRedistribution final : public LineScheme {
 public:
  LineMassRedistribution(const Case& c, Line line);

  void start() override;
  void advance() override;
  [[nodiscard]] double displacement_at(std::size_t j) const override { return u_[j]; }
  [[nodiscard]] double velocity_at(std::size_t j) const override { return v_[j]; }
  [[nodiscard]] Energies energies() const override;
  [[nodiscard]] bool finite() const override;

 private:
  void advance_elastic();
  template <bool loaded>
  void free_step();
  /// A Crank-Nicolson row's right-hand side 2/dt^2 M~ (u + dt v) + Fbar - (K u)/2 at any node.
  template <bool loaded>
  [[nodiscard]] double row(std::size_t j) const;
  /// row(j), a face's equilibrium, the held rows and their neighbours.
  template <bool loaded>
  [[nodiscard]] double special_row(std::size_t j);
  /// Every link's status and force; u, v corrected.
  void settle_contacts();
  /// (K u)_f - F_f^{n+1} at face f (F with its end force).
  [[nodiscard]] double imbalance(std::size_t f, double t) const;
  void book_budget(double t0, double t1);

  Tridiagonal mass_;            // M~
  FactoredTridiagonal factor_;  // 2 M~ / dt^2 + K / 2, held rows the identity
  std::vector<double> k_;       // per bond
  std::vector<unsigned char> face_;
  std::vector<std::size_t> faces_;
  std::vector<double> face_u_old_, face_rho_;  // per face: u^n, rho^n
  std::vector<Stretch> stretches_;
  std::vector<HeldRow> held_;
  RigidLinks rigid_;
  std::vector<double> u_, v_, u_old_, y_, load_old_;
  std::vector<double> q_, lambda_;
  std::vector<unsigned char> all_;
  double near_mean_ = 0.0, far_mean_ = 0.0;  // force ends: (f(t_n) + f(t_{n+1})) / 2
  double near_u_old_ = 0.0, far_u_old_ = 0.0;
  double work_ = 0.0, contact_ = 0.0;
  // The state a step changes, as one value (state.hpp): u first.
  auto state() {
    return std::tie(u_, load_, force_, c_max_, near_force_, far_force_, v_, load_old_, face_rho_, work_, contact_);
  }
  void keep_state() override { kept_.keep(state()); }
  void restore_state() override { kept_.restore(state()); }
  [[nodiscard]] const double* kept_displacement() const override { return kept_.get<0>().data(); }
  KeptState<std::vector<double>, std::vector<double>, std::vector<double>, std::vector<double>, double, double,
            std::vector<double>, std::vector<double>, std::vector<double>, double, double>
      kept_;
};

/// M_h with point masses, every rigid link's face's element mass moved onto
/// the face's inner neighbour (the line must fit: rigid_line_misfit).
[[nodiscard]] Tridiagonal redistributed_mass(const Line& line);

}  // namespace barimpact
