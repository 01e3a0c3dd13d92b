#include "barimpact/moreau_jean_scheme.hpp"

#include <algorithm>

namespace barimpact {

MoreauJeanScheme::MoreauJeanScheme(const Case& c)
    : OneStepScheme(c, Mesh(c.bar.length, c.bar.elements).mass(c.bar.density)),
      theta_(c.time.theta),
      restitution_(c.time.restitution) {
  const double th = theta_ * dt_;
  const Tridiagonal W =
      Tridiagonal::combine(1.0, Tridiagonal::combine(1.0, mass_, th, stiffness_b_), th * th, stiffness_a_);
  factor_ = FactoredTridiagonal(W, clamped_);
  const std::size_t n = mesh_.nodes();
  response_ = factor_.response_to_end_force();
  rhs_.assign(n, 0.0);
  scratch_.assign(n, 0.0);
}

void MoreauJeanScheme::advance() {
  begin_step();
  const std::size_t n = mesh_.nodes();
  const double dt = dt_, th = theta_;
  // rhs = M v + dt th (F^{n+1} - K_a (u + dt (1 - th) v)) + dt (1 - th) (F^n - K_a u - K_b v).
  for (std::size_t j = 0; j < n; ++j) scratch_[j] = u_[j] + dt * (1.0 - th) * v_[j];
  stiffness_a_.multiply(scratch_, rhs_);
  for (std::size_t j = 0; j < n; ++j) rhs_[j] = dt * th * (load_next_[j] - rhs_[j]);
  stiffness_a_.multiply(u_, scratch_);
  for (std::size_t j = 0; j < n; ++j) rhs_[j] += dt * (1.0 - th) * (load_[j] - scratch_[j]);
  stiffness_b_.multiply(v_, scratch_);
  for (std::size_t j = 0; j < n; ++j) rhs_[j] -= dt * (1.0 - th) * scratch_[j];
  mass_.multiply(v_, scratch_);
  for (std::size_t j = 0; j < n; ++j) rhs_[j] += scratch_[j];
  if (clamped_) rhs_[n - 1] = 0.0;
  factor_.solve(rhs_);  // v_free

  // Contact predicted active: Newton's law on V^{n+1}, p >= 0.
  double p = 0.0;
  const double V = v_old_[0];
  if (law_.kind() == ObstacleKind::rigid && u_old_[0] + law_.gap() + 0.5 * dt * V <= 0.0)
    p = std::max(0.0, (-restitution_ * V - rhs_[0]) / response_[0]);
  for (std::size_t j = 0; j < n; ++j) {
    v_[j] = rhs_[j] + p * response_[j];
    u_[j] = u_old_[j] + dt * (th * v_[j] + (1.0 - th) * v_old_[j]);
  }
  reaction_ = p / dt;
  end_step(0.0);
}

}  // namespace barimpact
