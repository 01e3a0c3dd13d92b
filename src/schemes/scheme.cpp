#include "barimpact/schemes/scheme.hpp"

#include "barimpact/case/line_builder.hpp"
#include "barimpact/schemes/line_characteristic.hpp"
#include "barimpact/schemes/line_scheme.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>

#include "barimpact/schemes/central_difference_scheme.hpp"
#include "barimpact/schemes/characteristic_scheme.hpp"
#include "barimpact/schemes/mass_redistribution_scheme.hpp"
#include "barimpact/schemes/moreau_jean_scheme.hpp"
#include "barimpact/schemes/newmark_scheme.hpp"
#include "barimpact/schemes/paoli_schatzman_scheme.hpp"
#include "barimpact/schemes/paper_scheme.hpp"

namespace barimpact {

namespace {

struct SchemeSpec {
  std::string_view name;
  std::vector<ObstacleKind> kinds;
  bool viscous_bar;  // accepts bar.viscosity > 0
};

const std::vector<SchemeSpec>& specs() {
  using K = ObstacleKind;
  static const std::vector<SchemeSpec> s{
      {"paper", {K::none, K::elastic, K::viscoelastic}, true},
      {"newmark", {K::none, K::elastic, K::viscoelastic}, true},
      {"central-difference", {K::none, K::elastic, K::viscoelastic, K::rigid}, true},
      {"mass-redistribution", {K::none, K::rigid}, false},
      {"paoli-schatzman", {K::none, K::rigid}, true},
      {"moreau-jean", {K::none, K::rigid}, true},
      {"characteristic", {K::none, K::rigid}, false},
  };
  return s;
}

const SchemeSpec& spec(std::string_view name) {
  for (const auto& s : specs())
    if (s.name == name) return s;
  throw InputError(fmt::format("time.scheme: unknown scheme \"{}\"", name));
}

}  // namespace

std::vector<std::string_view> scheme_names() {
  std::vector<std::string_view> names;
  for (const auto& s : specs()) names.push_back(s.name);
  return names;
}

double stable_step(const Case& c, bool consistent_mass) {
  // Gershgorin bounds of M^-1 K (frequency^2) and M^-1 C (damping rate),
  // node by node, with the penalty k and dashpot l at x = 0. Consistent P1
  // mass has eigenvalues 3 times smaller than lumped at the top of the
  // spectrum, hence the factor 3.
  const double h = c.bar.length / c.bar.elements, rho = c.bar.density;
  const bool penalty = c.obstacle.kind == ObstacleKind::elastic || c.obstacle.kind == ObstacleKind::viscoelastic;
  const double k = penalty ? c.obstacle.stiffness : 0.0;
  const double l = c.obstacle.kind == ObstacleKind::viscoelastic ? c.obstacle.viscosity : 0.0;
  const double a = c.bar.stiffness, b = c.bar.viscosity;
  double omega2 = 4.0 * a / (rho * h * h);
  double eta = 4.0 * b / (rho * h * h);
  omega2 = std::max(omega2, (2.0 * a / h + k) / (0.5 * rho * h));
  eta = std::max(eta, (2.0 * b / h + l) / (0.5 * rho * h));
  if (consistent_mass) {
    omega2 *= 3.0;
    eta *= 3.0;
  }
  // (u^{n+1} - 2u^n + u^{n-1})/dt^2 + eta (u^n - u^{n-1})/dt + omega^2 u^n = 0
  // is stable for omega^2 dt^2 + 2 eta dt <= 4.
  return (-eta + std::sqrt(eta * eta + 4.0 * omega2)) / omega2;
}

namespace {

// time.step = "auto": 0.9 of the explicit scheme's stable limit (its
// Gershgorin bound, already below the true limit, with a margin for the
// soil's damping, which grows with its static force).
std::optional<SchemeMisfit> choose_step(Case& c, const Line* line) {
  const std::string& name = c.time.scheme;
  if (name == "characteristic") return std::nullopt;  // it sets dt = h/c itself
  if (name != "central-difference" && name != "paoli-schatzman")
    return SchemeMisfit{"step", fmt::format("= \"auto\" chooses a stable step for the explicit schemes "
                                            "(central-difference, paoli-schatzman, characteristic); \"{}\" needs a "
                                            "number",
                                            name)};
  const bool consistent = name == "paoli-schatzman";
  c.time.step = auto_step_fraction * (line ? line_stable_step(*line, consistent) : stable_step(c, consistent));
  if (!(c.time.step > 0) || !std::isfinite(c.time.step))
    return SchemeMisfit{"step", "= \"auto\" finds no stable limit for this line (nothing stiff in it): give a number"};
  return std::nullopt;
}

}  // namespace

std::optional<SchemeMisfit> scheme_misfit(Case& c, bool step_given) {
  if (!c.single_bar) {
    const Line line = build_line(c);
    if (c.time.step_auto)
      if (auto m = choose_step(c, &line)) return m;
    // The characteristic scheme steps at the bars' common transit time h/c
    // (an elastic-plastic line it refuses first, below, whatever the step).
    if (c.time.scheme == "characteristic" && !line.plastic())
      if (const auto dt = line_characteristic_step(line)) {
        if (step_given && std::abs(c.time.step - *dt) > 1e-9 * *dt)
          return SchemeMisfit{"step", fmt::format("= {} conflicts with characteristic, which sets dt = h/c = {} "
                                                  "(omit time.step or give that value)",
                                                  c.time.step, *dt)};
        c.time.step = *dt;
      }
    if (auto m = line_scheme_misfit(c, line)) return SchemeMisfit{m->key, m->rule};
    return std::nullopt;
  }
  const SchemeSpec& s = spec(c.time.scheme);
  if (c.time.step_auto)
    if (auto m = choose_step(c, nullptr)) return m;
  if (std::find(s.kinds.begin(), s.kinds.end(), c.obstacle.kind) == s.kinds.end()) {
    std::vector<std::string_view> fit;
    for (const auto& other : specs())
      if (std::find(other.kinds.begin(), other.kinds.end(), c.obstacle.kind) != other.kinds.end())
        fit.push_back(other.name);
    return SchemeMisfit{"scheme", fmt::format("= \"{}\" does not handle obstacle.kind = \"{}\"; schemes that do: {}",
                                              s.name, to_string(c.obstacle.kind), fmt::join(fit, ", "))};
  }
  if (!s.viscous_bar && c.bar.viscosity > 0)
    return SchemeMisfit{
        "scheme", fmt::format("= \"{}\" needs an elastic bar (bar.viscosity = 0, got {})", s.name, c.bar.viscosity)};
  if (s.name == "characteristic") {
    const double h = c.bar.length / c.bar.elements;
    const double dt = h / std::sqrt(c.bar.stiffness / c.bar.density);
    if (step_given && std::abs(c.time.step - dt) > 1e-9 * dt)
      return SchemeMisfit{"step", fmt::format("= {} conflicts with characteristic, which sets dt = h/c = {} "
                                              "(omit time.step or give that value)",
                                              c.time.step, dt)};
    c.time.step = dt;
  }
  if (s.name == "central-difference" || s.name == "paoli-schatzman") {
    const double limit = stable_step(c, s.name == "paoli-schatzman");
    if (c.time.step > limit * (1.0 + 1e-12))  // a step at the limit (Courant 1) is stable
      return SchemeMisfit{"step", fmt::format("= {} is above {}'s stable limit {:.6g} for this mesh and obstacle",
                                              c.time.step, s.name, limit)};
  }
  return std::nullopt;
}

double Scheme::far_force() const {
  return std::numeric_limits<double>::quiet_NaN();
}

std::unique_ptr<Scheme> make_scheme(const Case& c) {
  const auto& name = c.time.scheme;
  if (!c.single_bar) return make_line_scheme(c);
  if (name == "paper") return std::make_unique<PaperScheme>(c);
  if (name == "newmark") return std::make_unique<NewmarkScheme>(c);
  if (name == "central-difference") return std::make_unique<CentralDifferenceScheme>(c);
  if (name == "characteristic") return std::make_unique<CharacteristicScheme>(c);
  if (name == "paoli-schatzman") return std::make_unique<PaoliSchatzmanScheme>(c);
  if (name == "moreau-jean") return std::make_unique<MoreauJeanScheme>(c);
  if (name == "mass-redistribution") return std::make_unique<MassRedistributionScheme>(c);
  throw InputError(fmt::format("time.scheme: unknown scheme \"{}\"", name));
}

}  // namespace barimpact
