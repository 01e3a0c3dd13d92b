#include "barimpact/mass_redistribution_scheme.hpp"

namespace barimpact {

Tridiagonal redistributed_mass(const Mesh& mesh, double density) {
  Tridiagonal m = mesh.mass(density);
  const double h = mesh.h();
  m.diag[0] -= density * h / 3.0;  // element 0: [[2,1],[1,2]] rho h/6 -> [[0,0],[0,6]] rho h/6
  m.off[0] -= density * h / 6.0;
  m.diag[1] += 2.0 * density * h / 3.0;
  m.diag[0] = m.off[0] = 0.0;  // exactly zero, not round-off
  return m;
}

MassRedistributionScheme::MassRedistributionScheme(const Case& c)
    : OneStepScheme(c, redistributed_mass(Mesh(c.bar.length, c.bar.elements), c.bar.density)),
      a_over_h_(c.bar.stiffness / mesh_.h()) {
  const std::size_t n = mesh_.nodes(), m = n - 1;
  const double c2 = 2.0 / (dt_ * dt_);
  reduced_.diag.assign(m, 0.0);
  reduced_.off.assign(m > 0 ? m - 1 : 0, 0.0);
  for (std::size_t j = 0; j < m; ++j) {
    reduced_.diag[j] = c2 * mass_.diag[j + 1] + 0.5 * stiffness_a_.diag[j + 1];
    if (j + 1 < m) reduced_.off[j] = c2 * mass_.off[j + 1] + 0.5 * stiffness_a_.off[j + 1];
  }
  contact_factor_ = FactoredTridiagonal(reduced_, clamped_);
  // Free: u_0 = u_1 + h F_0 / a adds the coupling A_10 = -a/(2h) to A_11.
  Tridiagonal free = reduced_;
  free.diag[0] += -0.5 * a_over_h_;
  free_factor_ = FactoredTridiagonal(free, clamped_);
  rhs_.assign(n, 0.0);
  reduced_rhs_.assign(m, 0.0);
  scratch_.assign(n, 0.0);
}

void MassRedistributionScheme::start() {
  start_state();
  on_obstacle_ = u_[0] + law_.gap() <= 0.0 && law_.kind() == ObstacleKind::rigid;
  reaction_ = 0.0;
}

bool MassRedistributionScheme::solve(bool on_obstacle) {
  const std::size_t n = mesh_.nodes(), m = n - 1;
  const double coupling = -0.5 * a_over_h_;  // A_10
  const double F0 = load_next_[0], face = -law_.gap();
  for (std::size_t j = 0; j < m; ++j) reduced_rhs_[j] = rhs_[j + 1];
  reduced_rhs_[0] -= coupling * (on_obstacle ? face : F0 / a_over_h_);
  if (clamped_) reduced_rhs_[m - 1] = 0.0;
  (on_obstacle ? contact_factor_ : free_factor_).solve(reduced_rhs_);
  const double free_position = reduced_rhs_[0] + F0 / a_over_h_;  // u_1 + h F_0 / a
  return on_obstacle ? free_position <= face : free_position >= face;
}

void MassRedistributionScheme::advance() {
  begin_step();
  const std::size_t n = mesh_.nodes();
  const double c2 = 2.0 / (dt_ * dt_);
  // rhs = 2/dt^2 M~ (u + dt v) + (F^n + F^{n+1})/2 - K_a u / 2, on every node.
  for (std::size_t j = 0; j < n; ++j) scratch_[j] = u_[j] + dt_ * v_[j];
  mass_.multiply(scratch_, rhs_);
  stiffness_a_.multiply(u_, scratch_);
  for (std::size_t j = 0; j < n; ++j) rhs_[j] = c2 * rhs_[j] + 0.5 * (load_[j] + load_next_[j]) - 0.5 * scratch_[j];

  const bool rigid = law_.kind() == ObstacleKind::rigid;
  bool status = rigid && on_obstacle_;
  if (!solve(status) && rigid) {
    status = !status;
    solve(status);  // the other status; in one unknown one of the two is consistent
  }
  on_obstacle_ = status;
  for (std::size_t j = 1; j < n; ++j) u_[j] = reduced_rhs_[j - 1];
  const double F0 = load_next_[0];
  u_[0] = status ? -law_.gap() : u_[1] + F0 / a_over_h_;
  for (std::size_t j = 1; j < n; ++j) v_[j] = 2.0 * (u_[j] - u_old_[j]) / dt_ - v_old_[j];
  v_[0] = (u_[0] - u_old_[0]) / dt_;
  reaction_ = status ? std::max(0.0, a_over_h_ * (u_[0] - u_[1]) - F0) : 0.0;
  end_step(0.0);
}

}  // namespace barimpact
