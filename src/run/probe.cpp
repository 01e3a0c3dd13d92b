#include "barimpact/run/probe.hpp"

#include <cmath>
#include <limits>
#include <unordered_map>

namespace barimpact {

namespace {
// Each link's index by its name (one look-up a joint: a line of 10^5 joints is not O(n^2)).
std::unordered_map<std::string, std::size_t> links_by_name(const Line& line) {
  std::unordered_map<std::string, std::size_t> index;
  for (std::size_t i = 0; i < line.links.size(); ++i) index.emplace(line.links[i].name, i);
  return index;
}
std::size_t link_named(const std::unordered_map<std::string, std::size_t>& links, const std::string& name) {
  const auto it = links.find(name);
  return it == links.end() ? Link::ground : it->second;
}
}  // namespace

Probes::Probes(const Case& c, const Line& line) : line_(&line) {
  auto add = [&](std::string name, Kind kind, std::size_t index) {
    names_.push_back(std::move(name));
    columns_.push_back({kind, index});
  };
  const auto links = links_by_name(line);
  const BodyIndex body_index(c.bodies);
  for (const auto& j : c.joints) {
    const std::string stem = j.column_stem();
    if (const std::size_t i = link_named(links, stem); i != Link::ground) {
      add(stem + ".force", Kind::link_force, i);
      add(stem + ".opening", Kind::link_opening, i);
      if (j.law.law == JointLaw::diesel) add(stem + ".pressure", Kind::link_pressure, i);
      continue;
    }
    // A spring or welded joint: the bond (or, welded, the first element of
    // the upper body, else the last of the lower) that carries its force.
    const BodyRange& upper = line.bodies[body_index(j.upper)];
    const BodyRange& lower = line.bodies[body_index(j.lower)];
    const bool welded = j.law.law == JointLaw::welded;
    std::size_t bond = upper.first - 1;
    if (welded)
      bond = upper.last > upper.first ? upper.first : lower.last > lower.first ? lower.last - 1 : Link::ground;
    add(stem + ".force", Kind::bond_force, bond);  // two welded masses share a node: no force to read (NaN)
    add(stem + ".opening", welded ? Kind::link_opening : Kind::bond_opening, welded ? Link::ground : bond);
  }
  if (c.far_end.law != JointLaw::free) {
    add("far_end.force", Kind::far_force, link_named(links, "far_end"));
    add("far_end.opening", Kind::far_opening, link_named(links, "far_end"));
  }
  for (const auto& b : line.bodies)
    if (b.is_mass) {
      add("body." + b.name + ".u", Kind::node_u, b.first);
      add("body." + b.name + ".v", Kind::node_v, b.first);
    }
  for (std::size_t g = 0; g < line.gauges.size(); ++g) {
    const std::string stem = "gauge." + line.gauges[g].name;
    add(stem + ".strain", Kind::gauge_strain, g);
    add(stem + ".velocity", Kind::gauge_velocity, g);
    add(stem + ".force", Kind::gauge_force, g);
  }
}

double bond_tension(const Line& line, const Scheme& s, std::size_t j) {
  const Bond& b = line.bonds[j];
  double t = b.stiffness * (s.displacement_at(j + 1) - s.displacement_at(j));
  if (b.viscosity != 0.0) t += b.viscosity * (s.velocity_at(j + 1) - s.velocity_at(j));
  return t - b.axial * s.plastic_strain(j);  // E A (eps - eps_p): 0 in an elastic body
}

double gauge_force(const Line& line, const Scheme& s, const GaugePoint& g) {
  return 0.5 * (bond_tension(line, s, g.left) + bond_tension(line, s, g.right));
}

double gauge_velocity(const Scheme& s, const GaugePoint& g) {
  return (1.0 - g.weight) * s.velocity_at(g.node) + g.weight * s.velocity_at(g.node + 1);
}

double Probes::value(const Scheme& s, const Column& col) const {
  const std::size_t i = col.index;
  switch (col.kind) {
    case Kind::link_force:
      return s.link_force(i);
    case Kind::link_opening:
      return i == Link::ground ? 0.0 : s.link_opening(i);
    case Kind::link_pressure:  // a diesel cylinder's gas, burnt once the ram struck
      return line_->links[i].law.gas.pressure(s.link_opening(i), s.link_largest_compression(i) > 0.0);
    case Kind::bond_force:
      return i == Link::ground ? std::numeric_limits<double>::quiet_NaN() : -bond_tension(*line_, s, i);
    case Kind::bond_opening:
      return s.displacement_at(i + 1) - s.displacement_at(i);
    case Kind::far_force: {
      if (i != Link::ground) return s.link_force(i);
      const double f = s.far_force();
      if (!std::isnan(f) || line_->bonds.empty()) return f;
      return -bond_tension(*line_, s, line_->bonds.size() - 1);
    }
    case Kind::far_opening:
      return i != Link::ground ? s.link_opening(i) : -s.displacement_at(line_->nodes() - 1);
    case Kind::node_u:
      return s.displacement_at(i);
    case Kind::node_v:
      return s.velocity_at(i);
    case Kind::gauge_strain: {
      const GaugePoint& g = line_->gauges[i];
      auto strain = [&](std::size_t j) {
        return (s.displacement_at(j + 1) - s.displacement_at(j)) / line_->bonds[j].h;
      };
      return 0.5 * (strain(g.left) + strain(g.right));
    }
    case Kind::gauge_velocity:
      return gauge_velocity(s, line_->gauges[i]);
    case Kind::gauge_force:
      return gauge_force(*line_, s, line_->gauges[i]);
  }
  return 0.0;
}

void Probes::read(const Scheme& s, double* out) const {
  for (std::size_t k = 0; k < columns_.size(); ++k) out[k] = value(s, columns_[k]);
}

}  // namespace barimpact
