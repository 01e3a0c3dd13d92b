// What the one-step schemes share (Newmark, Moreau-Jean, mass
// redistribution): the state (u^n, v^n) at t_n, the load at t_n and
// t_{n+1}, and the energy budget of the trapezoidal rule:
//   E_kin = v^T M v / 2,  E_strain = u^T K_a u / 2,  E_obstacle = k d^2 / 2,
//   dW = (u^{n+1} - u^n) . (F^n + F^{n+1}) / 2,  dD = dt vbar^T K_b vbar,
// vbar = (v^n + v^{n+1}) / 2: for the trapezoidal rule (Newmark 1/4, 1/2;
// Moreau-Jean theta = 1/2) without contact the budget closes to round-off.
#pragma once

#include <memory>
#include <vector>

#include "barimpact/case/case.hpp"
#include "barimpact/model/expression.hpp"
#include "barimpact/model/mesh.hpp"
#include "barimpact/model/obstacle.hpp"
#include "barimpact/schemes/scheme.hpp"

namespace barimpact {

class OneStepScheme : public Scheme {
 public:
  [[nodiscard]] long long step() const override { return n_; }
  [[nodiscard]] double time() const override { return static_cast<double>(n_) * dt_; }
  [[nodiscard]] std::size_t nodes() const override { return mesh_.nodes(); }
  [[nodiscard]] double end_displacement() const override { return u_[0]; }
  [[nodiscard]] double end_velocity() const override { return v_[0]; }
  [[nodiscard]] double reaction() const override { return reaction_; }
  void displacement(std::span<double> out) const override;
  void velocity(std::span<double> out) const override;
  [[nodiscard]] Energies energies() const override;
  [[nodiscard]] bool finite() const override;
  [[nodiscard]] double displacement_at(std::size_t j) const override { return j == 0 ? end_displacement() : u_[j]; }
  [[nodiscard]] double velocity_at(std::size_t j) const override { return j == 0 ? end_velocity() : v_[j]; }
  [[nodiscard]] double link_opening(std::size_t /*i*/) const override { return end_displacement() + law_.gap(); }

 protected:
  /// `kinetic_mass`: the scheme's mass matrix (for E_kin).
  OneStepScheme(const Case& c, Tridiagonal kinetic_mass);

  /// u, v from the initial data, F^0; step 0.
  void start_state();
  /// Keeps (u^n, v^n) in u_old_, v_old_ (when `keep_old`) and computes
  /// F^{n+1} into load_next_.
  void begin_step(bool keep_old = true);
  /// Whether end_step's budget reads u_old_, v_old_ (a load or viscosity).
  [[nodiscard]] bool budget_needs_old() const { return !load_zero_ || stiffness_b_.diag[0] > 0.0; }
  /// Adds the step's work and dissipation (plus `extra_dissipation`), moves
  /// F^{n+1} into load_, and n -> n + 1.
  void end_step(double extra_dissipation);

  Mesh mesh_;
  ObstacleLaw law_;
  double dt_, a_, b_;
  bool clamped_;
  Tridiagonal mass_, stiffness_a_, stiffness_b_;
  std::vector<double> u_, v_, u_old_, v_old_, load_, load_next_, work_vector_;
  bool load_zero_ = true;
  double reaction_ = 0.0;
  double contact_ = 0.0;  ///< D_contact: what the impulses took (Moreau-Jean)

 private:
  std::unique_ptr<Expression> body_force_, initial_displacement_, initial_velocity_;
  bool load_steady_ = true;
  long long n_ = 0;
  double work_ = 0.0, dissipation_ = 0.0;
};

}  // namespace barimpact
