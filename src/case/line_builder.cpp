#include "barimpact/case/line_builder.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "../model/huge_pages.hpp"
#include "barimpact/model/setup_polling.hpp"

namespace barimpact {

namespace {

bool unilateral(JointLaw law) {
  return law == JointLaw::elastic || law == JointLaw::viscoelastic || law == JointLaw::rigid ||
         law == JointLaw::cushion || law == JointLaw::smith || law == JointLaw::diesel;
}

ContactLaw contact_law(const Case& c, const LawData& d) {
  ContactLaw l;
  l.stiffness = d.stiffness;
  l.viscosity = d.viscosity;
  l.restitution = d.restitution;
  switch (d.law) {
    case JointLaw::elastic:
      l.kind = LawKind::elastic;
      l.viscosity = 0.0;
      break;
    case JointLaw::viscoelastic:
      l.kind = LawKind::viscoelastic;
      break;
    case JointLaw::cushion:
      l.kind = LawKind::cushion;
      l.viscosity = 0.0;
      break;
    case JointLaw::diesel:
      l.kind = LawKind::diesel;
      l.gas = d.gas;
      l.viscosity = 0.0;
      break;
    case JointLaw::smith:
      l.kind = LawKind::smith;
      l.soil = d.soil;
      l.stiffness = d.soil.stiffness();
      l.viscosity = 0.0;
      l.restitution = 1.0;
      break;
    default:
      l.kind = LawKind::rigid;
      l.stiffness = l.viscosity = 0.0;
      l.restitution = rigid_restitution(c, d);
      break;
  }
  return l;
}

// The joint below each body (null for the first, and where the line is welded without one).
std::vector<const JointData*> joints_below(const Case& c, const BodyIndex& index) {
  std::vector<const JointData*> below(c.bodies.size(), nullptr);
  for (const auto& j : c.joints) {
    const std::size_t lower = index(j.lower), upper = index(j.upper);
    if (upper < below.size() && lower + 1 == upper && below[upper] == nullptr) below[upper] = &j;
  }
  return below;
}

End end_of(const LawData& d, std::size_t node) {
  End e;
  e.node = node;
  e.value = d.value;
  switch (d.law) {
    case JointLaw::clamped:
      e.kind = EndKind::clamped;
      break;
    case JointLaw::force:
      e.kind = EndKind::force;
      break;
    case JointLaw::velocity:
      e.kind = EndKind::velocity;
      break;
    default:
      e.kind = EndKind::free;
      break;
  }
  return e;
}

// Nodes built between two looks at the set-up's interrupt.
constexpr int setup_poll_nodes = 1 << 16;

// Appends node at x, joined to the previous node (if any) by `bond`.
void add_node(Line& line, double x, const Bond& bond) {
  if (!line.x.empty()) line.bonds.push_back(bond);
  line.x.push_back(x);
  line.point_mass.push_back(0.0);
}

// Body i's nodes; `join` is the bond to the previous body (ignored when welded).
void add_body(Line& line, const BodyData& b, std::size_t index, bool welded, const Bond& join, double start) {
  BodyRange range{b.name, b.kind == BodyKind::mass, 0, 0, b.displacement, b.velocity};
  if (!welded || line.x.empty()) add_node(line, start, join);
  range.first = line.x.size() - 1;
  if (b.kind == BodyKind::mass) {
    line.point_mass[range.first] += b.mass;
  } else {
    const double h = b.length / b.elements;
    const double ea = b.modulus * b.area, eta_a = b.viscosity * b.area;
    const Bond e{BondKind::element, h, ea / h, eta_a / h, b.density * b.area * h, b.area, index, ea, eta_a};
    line.bonds.append(e, static_cast<std::size_t>(b.elements));
    for (int k = 1; k <= b.elements; ++k) {
      if (k % setup_poll_nodes == 0) poll_setup();  // a line of millions of nodes takes seconds
      line.x.push_back(start + static_cast<double>(k) * h);
    }
    line.point_mass.resize(line.x.size(), 0.0);
  }
  range.last = line.x.size() - 1;
  line.bodies.push_back(range);
  line.plasticity.push_back(b.kind == BodyKind::bar && b.material.kind == MaterialKind::plastic
                                ? std::optional<Plasticity>(Plasticity(b.modulus, b.material))
                                : std::nullopt);
}

// The soil of a shaft's node at x along the body (ShaftPiece's rule).
const SoilSpring& piece_soil(const ShaftData& d, double x) {
  for (const auto& p : d.profile)
    if (p.from < x && x <= p.to) return p.soil;
  for (const auto& p : d.profile)
    if (p.from <= x && x <= p.to) return p.soil;
  return d.soil;
}

// [body.shaft] of body `b` (nodes r.first..r.last): the distribution's or
// the profile's consistent nodal shares, each node with its soil's quake
// and damping.
void add_shaft(Line& line, const BodyRange& r, const ShaftData& d) {
  const std::size_t n = line.nodes();
  Shaft& s = line.shaft;
  for (auto* v : {&s.ultimate, &s.stiffness, &s.quake, &s.smith, &s.viscous}) v->resize(n, 0.0);  // the bodies so far
  const double le = d.embedded;
  if (d.profile.empty())
    add_shares(
        line, r, 0.0, le,
        [&](double xi) {
          return d.distribution == ShaftDistribution::uniform ? d.soil.ultimate / le
                                                              : 2.0 * d.soil.ultimate / le * (1.0 - xi / le);
        },
        s.ultimate);
  for (const auto& p : d.profile)
    add_shares(
        line, r, p.from, p.to, [&](double xi) { return p.resistance_at(xi); }, s.ultimate);
  for (std::size_t j = r.first; j <= r.last; ++j) {
    if (s.ultimate[j] <= 0.0) continue;
    const SoilSpring& soil = piece_soil(d, line.x[j] - line.x[r.first]);
    s.stiffness[j] = s.ultimate[j] / soil.quake;
    s.quake[j] = soil.quake;
    (soil.damping_law == DampingLaw::smith ? s.smith[j] : s.viscous[j]) =
        soil.damping_law == DampingLaw::smith ? soil.damping : soil.damping * s.ultimate[j];
  }
}

GaugePoint gauge_point(const Line& line, const Case& c, const BodyIndex& index, const GaugeData& g) {
  const std::size_t i = index(g.body);
  const BodyData& b = c.bodies[i];
  const BodyRange& r = line.bodies[i];
  const double s = g.at / (b.length / b.elements);  // in elements
  const double k = std::round(s);
  GaugePoint p{g.name, 0, 0, 0, 0.0};
  const std::size_t last_bond = r.last - 1;
  if (std::abs(s - k) <= 1e-9 * std::max(1.0, s)) {  // on a node
    const auto kn = static_cast<std::size_t>(k);
    p.left = kn == 0 ? r.first : r.first + kn - 1;
    p.right = kn == static_cast<std::size_t>(b.elements) ? last_bond : r.first + kn;
    p.node = std::min(r.first + kn, last_bond);
    p.weight = r.first + kn > last_bond ? 1.0 : 0.0;
  } else {
    const auto e = std::min(static_cast<std::size_t>(std::floor(s)), static_cast<std::size_t>(b.elements) - 1);
    p.left = p.right = p.node = r.first + e;
    p.weight = s - static_cast<double>(e);
  }
  return p;
}

Line build(const Case& c);

}  // namespace

double rigid_restitution(const Case& c, const LawData& law) {
  return law.restitution_given ? law.restitution : c.time.restitution;
}

Line build_line(const Case& c) {
  return build(c);
}

namespace {

Line build(const Case& c) {
  Line line;
  std::size_t nodes = 0;  // reserved: a bar of 10^6 elements grows no copies
  for (const auto& b : c.bodies) nodes += b.kind == BodyKind::bar ? static_cast<std::size_t>(b.elements) + 1 : 1;
  detail::reserve_huge(line.x, nodes);
  line.bonds.reserve(nodes);
  detail::reserve_huge(line.point_mass, nodes);
  double x = 0.0;
  const BodyIndex index(c.bodies);
  const auto below = joints_below(c, index);
  for (std::size_t i = 0; i < c.bodies.size(); ++i) {
    const BodyData& b = c.bodies[i];
    const JointData* j = below[i];
    const bool welded = i > 0 && (j == nullptr || j->law.law == JointLaw::welded);
    Bond join{BondKind::open, 0.0, 0.0, 0.0, 0.0, 1.0, i, 0.0, 0.0};
    if (j != nullptr && j->law.law == JointLaw::spring) {
      join.kind = BondKind::spring;
      join.stiffness = j->law.stiffness;
      join.viscosity = j->law.viscosity;
    }
    const std::size_t lower_last = line.x.empty() ? 0 : line.x.size() - 1;
    if (j != nullptr && unilateral(j->law.law)) x += j->law.gap;
    add_body(line, b, i, welded, join, x);
    if (b.shaft && b.shaft->soil.ultimate > 0.0) add_shaft(line, line.bodies.back(), *b.shaft);
    if (b.kind == BodyKind::bar) x += b.length;
    if (j != nullptr && unilateral(j->law.law))
      line.links.push_back(
          {j->column_stem(), contact_law(c, j->law), lower_last, line.bodies.back().first, j->law.gap, false});
  }
  const std::size_t last = line.x.size() - 1;
  if (unilateral(c.near_end.law))
    line.links.insert(line.links.begin(),
                      Link{"near_end", contact_law(c, c.near_end), Link::ground, 0, c.near_end.gap, true});
  if (unilateral(c.far_end.law))
    line.links.push_back({"far_end", contact_law(c, c.far_end), last, Link::ground, c.far_end.gap, true});
  line.near = end_of(c.near_end, 0);
  line.far = end_of(c.far_end, last);
  for (const auto& g : c.gauges) line.gauges.push_back(gauge_point(line, c, index, g));
  if (!line.shaft.ultimate.empty())
    for (auto* v :
         {&line.shaft.ultimate, &line.shaft.stiffness, &line.shaft.quake, &line.shaft.smith, &line.shaft.viscous})
      v->resize(line.nodes(), 0.0);
  for (std::size_t j = 0; j < line.shaft.ultimate.size(); ++j)
    if (line.shaft.ultimate[j] > 0.0) line.shaft.nodes.push_back(j);
  line.body_force = c.load.body_force;
  line.gravity = c.load.gravity;
  return line;
}

}  // namespace

}  // namespace barimpact
