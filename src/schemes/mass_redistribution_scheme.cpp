#include "barimpact/schemes/mass_redistribution_scheme.hpp"

#include <algorithm>

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
  // Eliminated from the far end, the two factorisations differ only in their
  // last pivot, that of node 1.
  Tridiagonal free = reduced_;
  free.diag[0] += -0.5 * a_over_h_;
  free_inverse_pivot_ = FactoredTridiagonal(free, clamped_).inverse_pivots()[0];
  reduced_rhs_.assign(m, 0.0);
}

void MassRedistributionScheme::start() {
  start_state();
  on_obstacle_ = u_[0] + law_.gap() <= 0.0 && law_.kind() == ObstacleKind::rigid;
  reaction_ = 0.0;
}

// One pass towards x = 0 forms the right-hand side
//   2/dt^2 M~ (u + dt v) + (F^n + F^{n+1})/2 - K_a u / 2   (nodes 1..M)
// inside the first sweep; node 0's status is decided at node 1 (both
// statuses cost a division); one pass back finishes the solve and updates
// u and v = 2 (u^{n+1} - u^n)/dt - v^n.
void MassRedistributionScheme::advance() {
  if (load_zero_)
    step<false>();
  else
    step<true>();
}

template <bool loaded>
void MassRedistributionScheme::step() {
  begin_step(budget_needs_old());
  const std::size_t n = mesh_.nodes(), last = n - 1;
  const double dt = dt_, c2 = 2.0 / (dt * dt);
  const double* __restrict f0 = load_.data();
  const double* __restrict f1 = load_next_.data();
  const double* __restrict inv = contact_factor_.inverse_pivots();  // node j is row j - 1
  const double* __restrict cp = contact_factor_.coupling();
  double* __restrict u = u_.data();
  double* __restrict v = v_.data();
  double* __restrict y = reduced_rhs_.data();
  const Tridiagonal &mm = mass_, &ka = stiffness_a_;
  const std::size_t inside = std::min<std::size_t>(2, last);  // a row with the interior stencils
  const double md = mm.diag[inside], mo = mm.off[inside - 1], kd = ka.diag[inside], ko = ka.off[inside - 1];
  auto force = [&](std::size_t j) {
    if constexpr (loaded) return 0.5 * (f0[j] + f1[j]);
    (void)j;
    return 0.0;
  };
  auto s = [&](std::size_t j) { return u[j] + dt * v[j]; };
  // Rows M and 1 from the matrices; rows 2..M-1 with the constant stencils.
  double carry = c2 * (mm.diag[last] * s(last) + mm.off[last - 1] * s(last - 1)) + force(last) -
                 0.5 * (ka.diag[last] * u[last] + ka.off[last - 1] * u[last - 1]);
  if (clamped_) carry = 0.0;
  if (last > 1) y[last - 1] = carry;
  for (std::size_t j = last - 1; j > 1; --j) {
    const double rj =
        c2 * (md * s(j) + mo * (s(j - 1) + s(j + 1))) + force(j) - 0.5 * (kd * u[j] + ko * (u[j - 1] + u[j + 1]));
    carry = rj - cp[j] * carry;
    y[j - 1] = carry;
  }
  double y1 = carry;  // M = 1: node 1 is the last row
  if (last > 1) {
    // M~ has no entry between nodes 0 and 1 (off_0 = 0); K_a does.
    const double r1 = c2 * (mm.diag[1] * s(1) + mm.off[1] * s(2)) + force(1) -
                      0.5 * (ka.diag[1] * u[1] + ka.off[0] * u[0] + ka.off[1] * u[2]);
    y1 = r1 - cp[1] * carry;
  }
  // Node 0: on the obstacle u_0 = -g, else u_0 = u_1 + h F_0 / a; the row of
  // node 1 then holds -A_10 u_0 (A_10 = -a/(2h)) and, when free, A_10 u_1.
  const double coupling = -0.5 * a_over_h_, F0 = load_next_[0], face = -law_.gap();
  auto node1 = [&](bool on) {
    return on ? (y1 - coupling * face) * inv[0] : (y1 - coupling * F0 / a_over_h_) * free_inverse_pivot_;
  };
  auto consistent = [&](bool on, double x1) { return on ? x1 + F0 / a_over_h_ <= face : x1 + F0 / a_over_h_ >= face; };
  const bool rigid = law_.kind() == ObstacleKind::rigid;
  bool status = rigid && on_obstacle_;
  double x = node1(status);
  if (rigid && !consistent(status, x)) {
    status = !status;  // in one unknown one of the two is consistent
    x = node1(status);
  }
  on_obstacle_ = status;
  const double u0 = status ? face : x + F0 / a_over_h_;
  v[0] = (u0 - u[0]) / dt;
  u[0] = u0;
  auto update = [&](std::size_t j) {
    v[j] = 2.0 * (x - u[j]) / dt - v[j];
    u[j] = x;
  };
  update(1);
  for (std::size_t j = 2; j < n; ++j) {
    x = y[j - 1] * inv[j - 1] - cp[j - 1] * x;
    update(j);
  }
  reaction_ = status ? std::max(0.0, a_over_h_ * (u[0] - u[1]) - F0) : 0.0;
  end_step(0.0);
}

}  // namespace barimpact
