#include "barimpact/model/line.hpp"

#include "barimpact/model/setup_polling.hpp"

#include <array>
#include <cmath>

#include "barimpact/model/expression.hpp"

namespace barimpact {

std::string_view to_string(LawKind kind) {
  switch (kind) {
    case LawKind::elastic:
      return "elastic";
    case LawKind::viscoelastic:
      return "viscoelastic";
    case LawKind::cushion:
      return "cushion";
    case LawKind::rigid:
      return "rigid";
    case LawKind::smith:
      return "smith";
    case LawKind::diesel:
      return "diesel";
  }
  return "?";
}

namespace {
// Assembles per-bond coefficients c_j as c_j [[p, q], [q, p]].
Tridiagonal assemble(const Bonds& bonds, std::size_t nodes, double Bond::*field, double p, double q) {
  poll_setup();  // line-sized: a study's case polls its interrupt between such phases
  Tridiagonal t{std::vector<double>(nodes, 0.0), std::vector<double>(nodes > 0 ? nodes - 1 : 0, 0.0)};
  for (std::size_t j = 0; j < bonds.size(); ++j) {
    const double c = bonds[j].*field;
    t.diag[j] += p * c;
    t.diag[j + 1] += p * c;
    t.off[j] = q * c;
  }
  return t;
}
}  // namespace

Tridiagonal Line::mass(bool consistent) const {
  Tridiagonal m = consistent ? assemble(bonds, nodes(), &Bond::mass, 1.0 / 3.0, 1.0 / 6.0)
                             : Tridiagonal{lumped_mass(), std::vector<double>(nodes() - 1, 0.0)};
  if (consistent)
    for (std::size_t j = 0; j < nodes(); ++j) m.diag[j] += point_mass[j];
  return m;
}

Tridiagonal Line::stiffness() const {
  return assemble(bonds, nodes(), &Bond::stiffness, 1.0, -1.0);
}

Tridiagonal Line::viscosity() const {
  return assemble(bonds, nodes(), &Bond::viscosity, 1.0, -1.0);
}

std::vector<double> Line::lumped_mass() const {
  poll_setup();
  std::vector<double> m = point_mass;
  for (std::size_t j = 0; j < bonds.size(); ++j) {
    m[j] += 0.5 * bonds[j].mass;
    m[j + 1] += 0.5 * bonds[j].mass;
  }
  return m;
}

void Line::load(const Expression& f, double t, std::vector<double>& out) const {
  // 3-point Gauss-Legendre per element: exact for f phi_i of degree <= 5.
  static const double r = std::sqrt(0.6);
  static constexpr std::array<double, 3> weight{5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0};
  const std::array<double, 3> xi{-r, 0.0, r};
  out.assign(nodes(), 0.0);
  const bool zero = f.is_zero();
  for (std::size_t e = 0; e < bonds.size() && !zero; ++e) {
    if (bonds[e].kind != BondKind::element) continue;
    const double h = bonds[e].h;
    for (std::size_t q = 0; q < 3; ++q) {
      const double s = 0.5 * (1.0 + xi[q]);
      const double fw = f(x[e] + s * h, t) * weight[q] * 0.5 * h;
      out[e] += fw * (1.0 - s);
      out[e + 1] += fw * s;
    }
  }
  if (gravity != 0.0) {
    // The lumped mass node by node (no temporary: the schemes call this inside their steps).
    for (std::size_t j = 0; j < nodes(); ++j) out[j] -= gravity * node_mass(j);
  }
}

std::vector<double> Line::initial(int which) const {
  poll_setup();
  std::vector<double> out(nodes(), 0.0);
  for (const auto& b : bodies) {
    const Expression g(which == 0 ? b.displacement : b.velocity);
    for (std::size_t j = b.first; j <= b.last; ++j) out[j] = g(x[j], 0.0);
  }
  return out;
}

double Line::bond_form(BondKind kind, bool viscous, const double* a, const double* b) const {
  double s = 0.0;
  for (std::size_t j = 0; j < bonds.size(); ++j) {
    if (bonds[j].kind != kind) continue;
    const double c = viscous ? bonds[j].viscosity : bonds[j].stiffness;
    s += c * (a[j + 1] - a[j]) * (b[j + 1] - b[j]);
  }
  return s;
}

double Line::smallest_transit() const {
  double t = 0.0;
  for (const auto& b : bonds) {
    if (b.kind != BondKind::element) continue;
    const double c = std::sqrt(b.stiffness * b.h / (b.mass / b.h));  // sqrt(E A / (rho A))
    const double s = b.h / c;
    if (t == 0.0 || s < t) t = s;
  }
  return t;
}

}  // namespace barimpact
