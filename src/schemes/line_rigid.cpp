#include "barimpact/schemes/line_rigid.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "barimpact/case/line_builder.hpp"
#include "barimpact/schemes/line_mass_redistribution.hpp"
#include "barimpact/schemes/line_moreau_jean.hpp"
#include "barimpact/schemes/line_paoli_schatzman.hpp"

namespace barimpact {

std::vector<HeldRow> hold_rows(const Line& line, Tridiagonal& a) {
  std::vector<HeldRow> held;
  const std::size_t n = line.nodes();
  for (const End* e : {&line.near, &line.far}) {
    if (e->kind != EndKind::clamped && e->kind != EndKind::velocity) continue;
    if (e == &line.far && !held.empty() && held.front().node == e->node) continue;  // one node, held once
    HeldRow h;
    h.node = e->node;
    h.near = e == &line.near;
    h.driven = e->kind == EndKind::velocity;
    h.diagonal = a.diag[h.node];
    if (n > 1) {
      const std::size_t bond = h.node == 0 ? 0 : h.node - 1;  // the end's one bond
      h.neighbour = h.node == 0 ? 1 : h.node - 1;
      h.coupling = a.off[bond];
      a.off[bond] = 0.0;
    }
    a.diag[h.node] = 1.0;
    held.push_back(h);
  }
  return held;
}

EndReport end_report(const Line& line, const std::vector<double>& link_force, double near_value, double far_value,
                     const std::vector<HeldRow>& held, double support_scale) {
  EndReport r;
  for (const auto& h : held) (h.near ? r.near : r.far) = h.support * support_scale;
  r.far = -r.far;  // the support pushes along +x at the near end, along -x at the far end
  if (line.near.kind == EndKind::force) r.near = near_value;
  if (line.far.kind == EndKind::force) r.far = -far_value;
  for (std::size_t i = 0; i < line.links.size(); ++i) {
    if (line.links[i].name == "near_end") r.near = link_force[i];
    if (line.links[i].name == "far_end") r.far = link_force[i];
  }
  return r;
}

std::vector<Stretch> uniform_stretches(const Line& line, std::vector<unsigned char> special,
                                       const std::vector<HeldRow>& held) {
  const std::size_t n = line.nodes();
  for (const auto& h : held) {
    special[h.node] = 1;
    if (h.neighbour != HeldRow::none) special[h.neighbour] = 1;
  }
  auto plastic = [&](const Bond& b) { return b.body < line.plasticity.size() && line.plasticity[b.body]; };
  auto uniform = [&](std::size_t j) {
    if (j == 0 || j + 1 >= n || special[j] || line.fixed(j) || line.point_mass[j] != 0.0) return false;
    const Bond &l = line.bonds[j - 1], &r = line.bonds[j];
    // A stretch is elastic or elastic-plastic of one E A throughout (the plastic strains' forces E A (p_{j-1} - p_j)).
    return l.kind == BondKind::element && r.kind == BondKind::element && l.stiffness == r.stiffness &&
           l.viscosity == r.viscosity && l.mass == r.mass && plastic(l) == plastic(r) &&
           (!plastic(l) || l.axial == r.axial);
  };
  std::vector<Stretch> out;
  for (std::size_t j = 1; j + 1 < n; ++j) {
    if (!uniform(j)) continue;
    if (!out.empty() && out.back().last == j)
      ++out.back().last;  // bond j - 1 equals bond j and, by the run so far, the stretch's
    else
      out.push_back({j, j + 1});
  }
  return out;
}

RigidLinks::RigidLinks(const Line& line, const FactoredTridiagonal& factor, double scale) {
  const std::size_t n = line.nodes();
  std::vector<double> w(n);
  auto movable = [&](std::size_t j) { return j != Link::ground && !line.fixed(j); };
  for (std::size_t i = 0; i < line.links.size(); ++i) {
    const Link& l = line.links[i];
    if (!l.law.rigid()) continue;
    std::fill(w.begin(), w.end(), 0.0);
    if (movable(l.a)) w[l.a] -= scale;
    if (movable(l.b)) w[l.b] += scale;
    factor.solve(w);
    // Exact zeros outside the clusters the link touches: keep the span between.
    std::size_t lo = 0, hi = n;
    while (lo < n && w[lo] == 0.0) ++lo;
    while (hi > lo && w[hi - 1] == 0.0) --hi;
    const double d = (movable(l.b) ? w[l.b] : 0.0) - (movable(l.a) ? w[l.a] : 0.0);
    if (!(d > 0.0)) continue;  // both faces held or on the ground: nothing moves
    link_.push_back(i);
    a_.push_back(l.a);
    b_.push_back(l.b);
    first_.push_back(lo);
    response_.emplace_back(w.begin() + static_cast<std::ptrdiff_t>(lo), w.begin() + static_cast<std::ptrdiff_t>(hi));
    restitution_.push_back(l.law.restitution);
    diag_.push_back(d);
  }
  lower_.assign(size(), 0.0);
  for (std::size_t k = 1; k < size(); ++k) {
    lower_[k] = response_at(k - 1, b_[k]) - response_at(k - 1, a_[k]);  // h_k^T w_{k-1}
    coupled_ = coupled_ || lower_[k] != 0.0;
  }
}

int RigidLinks::solve(const double* q, const unsigned char* active, double* p) const {
  const std::size_t m = size();
  double scale = 0.0;
  for (std::size_t k = 0; k < m; ++k) {
    p[k] = 0.0;
    if (active[k]) scale = std::max(scale, std::abs(q[k]));
  }
  if (scale == 0.0) return 0;
  for (int sweep = 1; sweep <= max_sweeps; ++sweep) {
    double moved = 0.0;
    for (std::size_t k = 0; k < m; ++k) {
      if (!active[k]) continue;
      double y = q[k] + diag_[k] * p[k];  // the link's opening rate (or opening) with the current p
      if (k > 0) y += lower_[k] * p[k - 1];
      if (k + 1 < m) y += lower_[k + 1] * p[k + 1];
      const double next = std::max(0.0, p[k] - y / diag_[k]);
      moved = std::max(moved, std::abs(next - p[k]) * diag_[k]);
      p[k] = next;
    }
    if (!coupled_ || moved <= tolerance * scale) return sweep;
  }
  return max_sweeps;
}

void RigidLinks::add_responses(const double* p, double s, double* x) const {
  for (std::size_t k = 0; k < size(); ++k) {
    if (p[k] == 0.0) continue;
    const double c = s * p[k];
    const double* __restrict w = response_[k].data();
    double* __restrict out = x + first_[k];
    for (std::size_t j = 0; j < response_[k].size(); ++j) out[j] += c * w[j];
  }
}

double RigidLinks::on_node(std::size_t j, const double* p) const {
  double f = 0.0;
  for (std::size_t k = 0; k < size(); ++k) {
    if (a_[k] == j) f -= p[k];
    if (b_[k] == j) f += p[k];
  }
  return f;
}

// Mass redistribution needs, at every rigid link's face, a bar element whose
// mass it can move inward: not a point mass, not a face of two rigid links;
// and no dashpots (its faces carry no inertia to damp).
std::optional<SchemeMisfit> redistribution_misfit(const Case& /*c*/, const Line& line) {
  const std::string s = "= \"mass-redistribution\"";
  auto refuse = [](std::string rule) { return SchemeMisfit{"scheme", std::move(rule)}; };
  for (const auto& b : line.bonds)
    if (b.viscosity > 0.0)
      return refuse(
          fmt::format("{} needs elastic bodies and springs without dashpots (viscosity 0); schemes that "
                      "can run viscosity with rigid links: moreau-jean, paoli-schatzman, central-difference",
                      s));
  std::vector<unsigned char> face(line.nodes(), 0);
  for (const auto& l : line.links)
    for (std::size_t j : {l.a, l.b})
      if (j != Link::ground) ++face[j];
  for (const auto& l : line.links)
    for (std::size_t j : {l.a, l.b}) {
      if (j == Link::ground) continue;
      const std::size_t inner = j == l.a ? j - 1 : j + 1;
      const bool bar_end = inner < line.nodes() && line.bonds[std::min(j, inner)].kind == BondKind::element;
      if (line.point_mass[j] != 0.0 || !bar_end)
        return refuse(
            fmt::format("{} cannot run the rigid link \"{}\": it touches a mass body, which cannot give "
                        "its mass away; schemes that can: moreau-jean, paoli-schatzman, central-difference",
                        s, l.name));
      if (face[j] > 1 || face[inner] > 0)
        return refuse(
            fmt::format("{} cannot run the rigid link \"{}\": a bar between two rigid links needs 2 "
                        "elements or more; schemes that can: moreau-jean, paoli-schatzman, central-difference",
                        s, l.name));
    }
  return std::nullopt;
}

}  // namespace barimpact
