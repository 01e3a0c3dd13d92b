#include "barimpact/run/health.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <numeric>

#include "barimpact/case/line_builder.hpp"
#include "barimpact/model/tridiagonal.hpp"
#include "barimpact/schemes/registry.hpp"

namespace barimpact {

// Beyond the scheme's tolerance (registry.hpp) the run is not resolved: the
// README's k = 1e4 penalty case at dt = 1e-3 drifts by 64%.
double energy_balance_bound(const Case& c) {
  return scheme_info(c.time.scheme).energy_tolerance;
}

double energy_scale(const std::vector<HistoryRow>& history) {
  if (history.empty()) return 0.0;
  const auto& h0 = history.front();
  double scale = std::abs(h0.total());
  for (const auto& h : history) scale = std::max(scale, std::abs(h.W_ext));
  if (scale > 0.0) return scale;
  for (const auto& h : history) scale = std::max(scale, h.E_kin + h.E_strain + h.E_obstacle);
  return scale;
}

std::vector<PenaltyTimeConstant> penalty_time_constants(const Case& c) {
  return penalty_time_constants(c, build_line(c));
}

std::vector<PenaltyTimeConstant> penalty_time_constants(const Case& c, const Line& line) {
  std::vector<PenaltyTimeConstant> out;
  if (const auto one = c.one_bar()) {  // the paper's obstacle, by its name there
    const auto kind = one->obstacle.kind;
    if ((kind == ObstacleKind::elastic || kind == ObstacleKind::viscoelastic) && one->obstacle.stiffness > 0.0)
      out.push_back({"obstacle", std::sqrt(one->bar.density * one->bar.stiffness) / one->obstacle.stiffness, "Z/k"});
    return out;
  }
  const std::vector<double> m = line.lumped_mass();
  // The impedance A sqrt(E rho) of the element a node ends, or 0 at a point mass.
  auto impedance = [&](std::size_t node) {
    for (std::size_t j : {node, node - 1})  // the element above the node, else the one below
      if (j < line.bonds.size() && line.bonds[j].kind == BondKind::element)
        return std::sqrt(line.bonds[j].axial * line.bonds[j].mass / line.bonds[j].h);
    return 0.0;
  };
  for (const auto& l : line.links) {
    if (l.law.rigid() || !(l.law.stiffness > 0.0)) continue;
    const double k = l.law.stiffness;
    std::vector<double> z, mass;  // the faces' impedances; masses where a face is a point mass
    for (std::size_t node : {l.a, l.b}) {
      if (node == Link::ground) continue;
      const double zn = impedance(node);
      if (zn > 0.0)
        z.push_back(zn);
      else
        mass.push_back(m[node]);
    }
    if (z.size() == 2)  // two bars: their impedances in series
      out.push_back({l.name, z[0] * z[1] / (z[0] + z[1]) / k, "Z1 Z2/((Z1 + Z2) k)"});
    else if (z.size() == 1 && !mass.empty() && std::sqrt(mass[0] / k) < z[0] / k)  // a light mass on a bar
      out.push_back({l.name, std::sqrt(mass[0] / k), "sqrt(m/k)"});
    else if (z.size() == 1)
      out.push_back({l.name, z[0] / k, "Z/k"});
    else if (mass.size() == 2)
      out.push_back({l.name, std::sqrt(mass[0] * mass[1] / (mass[0] + mass[1]) / k), "sqrt(m1 m2/((m1 + m2) k))"});
    else if (mass.size() == 1)
      out.push_back({l.name, std::sqrt(mass[0] / k), "sqrt(m/k)"});
  }
  return out;
}

namespace {

void check_energy(const Case& c, const Summary& s, const std::vector<HistoryRow>& history,
                  std::vector<std::string>& out) {
  const double scale = energy_scale(history);
  if (!(scale > 0.0) || !std::isfinite(s.energy_error_max)) return;
  const double drift = s.energy_error_max / scale, bound = energy_balance_bound(c);
  if (drift > bound)
    out.push_back(fmt::format(
        "energy-balance: the energy budget drifts by {:.3g}% of the run's energy, above {}'s {:.3g}% for a resolved "
        "run (refine time.step or bar.elements)",
        100.0 * drift, c.time.scheme, 100.0 * bound));
}

void check_penalty(const Case& c, const Line& line, std::vector<std::string>& out) {
  for (const auto& p : penalty_time_constants(c, line))
    if (p.tau < c.time.step)
      out.push_back(fmt::format(
          "penalty-unresolved: {}'s time constant {} = {:.3g} is below time.step = {:.3g}, so its force is not "
          "resolved in time (take time.step below {:.3g}, or a rigid law)",
          p.link, p.basis, p.tau, c.time.step, p.tau));
}

// omega_max^2, the largest eigenvalue of K x = omega^2 M x (consistent mass,
// the penalty k at x = 0, a clamped end fixed), by power iteration from the
// sawtooth (-1)^j, which is nearly the top mode already: the Rayleigh
// quotient settles to a few digits in tens of iterations.
double largest_frequency_squared(const Case& c) {
  const Line line = build_line(c);
  const Tridiagonal M = line.mass(true);
  Tridiagonal K = line.stiffness();
  // Every penalty link as a spring (its stiffness while in contact).
  for (const auto& l : line.links) {
    if (l.law.rigid()) continue;
    const double k = l.law.largest_stiffness();
    if (l.a != Link::ground) K.diag[l.a] += k;
    if (l.b != Link::ground) K.diag[l.b] += k;
    if (l.a != Link::ground && l.b != Link::ground) K.off[l.a] -= k;
  }
  const bool clamped = line.fixed(line.nodes() - 1);
  const FactoredTridiagonal solver(M, clamped);
  std::vector<double> x(M.size()), y(M.size());
  for (std::size_t j = 0; j < x.size(); ++j) x[j] = j % 2 == 0 ? 1.0 : -1.0;
  if (clamped) x.back() = 0.0;
  double lambda = 0.0;
  for (int iteration = 0; iteration < 60; ++iteration) {
    K.multiply(x, y);
    lambda = std::inner_product(x.begin(), x.end(), y.begin(), 0.0) / M.quadratic_form(x);
    solver.solve(y);
    const double norm = std::sqrt(std::inner_product(y.begin(), y.end(), y.begin(), 0.0));
    if (!(norm > 0.0)) break;
    for (std::size_t j = 0; j < x.size(); ++j) x[j] = y[j] / norm;
  }
  return lambda;
}

}  // namespace

std::optional<double> conditional_stable_step(const Case& c) {
  const auto family = scheme_info(c.time.scheme).family;
  if (!family) return std::nullopt;
  const auto [beta, gamma, rule] = family(c);
  if (gamma < 0.5 || 2.0 * beta >= gamma) return std::nullopt;  // unconditionally stable (or not this family's rule)
  return 1.0 / std::sqrt(largest_frequency_squared(c) * (0.5 * gamma - beta));
}

namespace {

// The implicit schemes below the trapezoidal rule are only conditionally
// stable (conditional_stable_step).
void check_stability(const Case& c, std::vector<std::string>& out) {
  const auto limit = conditional_stable_step(c);
  if (limit && c.time.step > *limit)
    out.push_back(fmt::format(
        "unstable-step: time.step = {:.3g} is above {}'s stable step {:.3g} for this mesh and obstacle (with these "
        "parameters the scheme is only conditionally stable)",
        c.time.step, c.time.scheme, *limit));
}

void check_chatter(const Case& c, const Summary& s, std::vector<std::string>& out) {
  // Chatter: many episodes, most of them a step or two long.
  constexpr std::size_t many = 10;
  const double short_episode = 2.5 * c.time.step;
  const auto brief =
      static_cast<std::size_t>(std::count_if(s.contacts.begin(), s.contacts.end(), [&](const ContactInterval& e) {
        return e.closed && e.end - e.start < short_episode;
      }));
  if (s.contacts.size() >= many && 2 * brief > s.contacts.size())
    out.push_back(fmt::format(
        "contact-chatter: {} of {} contact episodes last under {:.3g} (2.5 steps); the contact switches on and off "
        "numerically (refine time.step, or add restitution or damping)",
        brief, s.contacts.size(), short_episode));
  // The line's other links (the near end is the obstacle above): measured
  // between the steps that saw the contact, so a one-step episode lasts 0.
  for (std::size_t i = 0; i < s.link_names.size(); ++i) {
    const auto& list = s.link_episodes[i];
    if (s.link_names[i] == "near_end" || list.size() < many) continue;
    const auto few = static_cast<std::size_t>(std::count_if(
        list.begin(), list.end(), [&](const LinkEpisode& e) { return e.closed && e.end - e.start < short_episode; }));
    if (2 * few > list.size())
      out.push_back(fmt::format(
          "contact-chatter: {} of {} contact episodes of {} last under {:.3g} (2.5 steps); the contact switches on "
          "and off numerically (refine time.step, or add restitution or damping)",
          few, list.size(), s.link_names[i], short_episode));
  }
}

// A pile case's numbers that are possible but unlikely in SI, each a
// warning naming the key and the unit it was probably meant in:
//   - a static capacity (toe or shaft) below the pile's own weight rho A L g:
//     a pile that light a soil could not hold up is a capacity in kN;
//   - a ram moving away from the pile (the line runs up from the toe, +x
//     upwards): it strikes only if it comes back down.
void check_pile(const Case& c, std::vector<std::string>& out) {
  const BodyData* pile = c.pile();
  if (pile == nullptr) return;
  constexpr double g = 9.80665;
  const double weight = pile->density * pile->area * pile->length * g;
  std::vector<std::pair<std::string, double>> capacities;
  if (c.near_end.law == JointLaw::smith) capacities.emplace_back("near_end.ultimate", c.near_end.soil.ultimate);
  for (const auto& b : c.bodies)
    if (b.shaft) capacities.emplace_back(fmt::format("body.{}.shaft.ultimate", b.name), b.shaft->soil.ultimate);
  for (const auto& [key, capacity] : capacities)
    if (capacity > 0.0 && capacity < weight)
      out.push_back(fmt::format(
          "pile-capacity: {} = {:g}: {}below the pile's own weight ({:.4g} N): capacities are in N ({:g} kN is "
          "{:g})",
          key, capacity, capacity * 1e3 >= weight ? "kN? " : "", weight, capacity, capacity * 1e3));
  const BodyData& ram = c.blow.ram.empty() ? c.bodies.back()
                                           : *std::find_if(c.bodies.begin(), c.bodies.end(),
                                                           [&](const BodyData& b) { return b.name == c.blow.ram; });
  char* end = nullptr;
  const double v = std::strtod(ram.velocity.c_str(), &end);
  if (&ram != pile && end != ram.velocity.c_str() && *end == '\0' && v > 0.0)
    out.push_back(fmt::format(
        "ram-velocity: body.{}.velocity = {:g} moves the ram away from the pile (+x runs up from the toe): {:g}?",
        ram.name, v, -v));
}

}  // namespace

std::string join_warnings(const std::vector<std::string>& warnings) {
  std::string joined;
  for (const auto& w : warnings) joined += (joined.empty() ? "" : " | ") + w;
  return joined;
}

std::vector<std::string> check_health(const Case& c, const Line& line, const Summary& s,
                                      const std::vector<HistoryRow>& history) {
  std::vector<std::string> out;
  if (s.method == "exact") return out;
  check_energy(c, s, history, out);
  check_penalty(c, line, out);
  check_stability(c, out);
  check_chatter(c, s, out);
  check_pile(c, out);
  return out;
}

}  // namespace barimpact
