#include "barimpact/run/residual.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <optional>
#include <stdexcept>
#include <vector>

#include "barimpact/model/tridiagonal.hpp"
#include "barimpact/schemes/registry.hpp"

namespace barimpact {

namespace {

// The springs' forces on the pile's nodes (+x up) at `u` from the committed
// state in `rest`, their tangents, and the trial slips they would commit.
struct SoilForces {
  std::vector<double> force, tangent, slip;
  double toe_force = 0.0, toe_c_max = 0.0, toe_tangent = 0.0;
};

SoilForces soil_forces(const Line& line, std::size_t first, std::size_t last, std::size_t toe,
                       const LineScheme::SoilRest& rest) {
  const std::size_t n = last - first + 1;
  SoilForces f{std::vector<double>(n, 0.0), std::vector<double>(n, 0.0), rest.shaft_slip, 0.0, 0.0, 0.0};
  const Shaft& s = line.shaft;
  for (std::size_t j = first; j <= last && !s.ultimate.empty(); ++j) {
    if (!(s.ultimate[j] > 0.0)) continue;
    const double w = -rest.u[j];  // penetration, down
    const double slip = smith_slip(rest.shaft_slip[j], w, s.quake[j]);
    f.slip[j] = slip;
    f.force[j - first] = s.stiffness[j] * (w - slip);
    f.tangent[j - first] = slip == rest.shaft_slip[j] ? s.stiffness[j] : 0.0;  // elastic, or slipping
  }
  if (toe != Link::ground) {
    const Link& link = line.links[toe];
    const double c = -(rest.u[first] + link.gap), q = link.law.soil.quake;
    f.toe_c_max = std::max(rest.c_max[toe], c);
    const double slipped = std::max(0.0, f.toe_c_max - q);
    f.toe_force = link.law.static_force(c, f.toe_c_max);
    f.toe_tangent = c > slipped && !(c >= rest.c_max[toe] && c > q) ? link.law.stiffness : 0.0;
    f.force[0] += f.toe_force;
    f.tangent[0] += f.toe_tangent;
  }
  return f;
}

}  // namespace

double settle(const Line& line, std::size_t first, std::size_t last, std::size_t toe, LineScheme::SoilRest& rest,
              double tolerance) {
  const std::size_t n = last - first + 1;
  std::vector<double> diag(n), off(n > 1 ? n - 1 : 0), r(n);
  double stiffest = 0.0;
  for (std::size_t j = first; j < last; ++j) stiffest = std::max(stiffest, line.bonds[j].stiffness);
  for (int iteration = 0; iteration < 200; ++iteration) {
    const SoilForces f = soil_forces(line, first, last, toe, rest);
    double worst = 0.0;
    std::fill(diag.begin(), diag.end(), 0.0);
    for (std::size_t i = 0; i < n; ++i) r[i] = f.force[i];
    for (std::size_t j = first; j < last; ++j) {  // the bar's tension pulls its ends together
      const double k = line.bonds[j].stiffness, t = k * (rest.u[j + 1] - rest.u[j]);
      r[j - first] += t;
      r[j + 1 - first] -= t;
      diag[j - first] += k;
      diag[j + 1 - first] += k;
      off[j - first] = -k;
    }
    for (std::size_t i = 0; i < n; ++i) {
      worst = std::max(worst, std::abs(r[i]));
      diag[i] += f.tangent[i] + 1e-12 * stiffest;  // a pile with every spring slipping still has a step
    }
    if (worst <= tolerance) {
      rest.shaft_slip = f.slip;
      if (toe != Link::ground) rest.c_max[toe] = f.toe_c_max;
      return f.toe_force;
    }
    solve_tangent(diag, off, {}, r);  // K du = r: forces(u + du) ~ forces(u) - K du = 0
    for (std::size_t i = 0; i < n; ++i) rest.u[first + i] += r[i];
  }
  throw std::runtime_error(fmt::format("the pile's static rest between blows did not converge to {:.3g} N", tolerance));
}

namespace {

bool within_percent(double a, double b) {
  return std::abs(a - b) <= 0.01 * std::abs(b);
}

// The hammer's nodes (every node above the pile) back on the pile head.
void touch_head(LineScheme::SoilRest& rest, std::size_t last) {
  for (std::size_t j = last + 1; j < rest.u.size(); ++j) rest.u[j] = rest.u[last];
}

}  // namespace

RunResult run_residual(const FittedCase& fitted, const RunOptions& options) {
  const Case& c = fitted.c;
  const int most = c.drive->blows;
  std::optional<LineScheme::SoilRest> rest;
  RunResult r;
  double first_set = 0.0, set = 0.0, locked_toe = 0.0;
  RunOptions held = options;
  held.fields = nullptr;  // each blow's snapshots held: only the last's are the result's
  int blows = 1;
  for (;; ++blows) {
    FittedCase f = fitted;
    auto scheme = make_scheme(f);
    auto* line_scheme = dynamic_cast<LineScheme*>(scheme.get());
    if (line_scheme == nullptr || !line_scheme->keeps_soil_rest())
      c.refuse("drive.blows", fmt::format("= {} > 1 (residual stresses) runs on central-difference only", most));
    const Line& line = *scheme->line();
    const std::size_t pile = [&] {
      for (std::size_t i = 0; i < c.bodies.size(); ++i)
        if (c.bodies[i].name == c.drive->pile) return i;
      return std::size_t{0};
    }();
    const std::size_t first = line.bodies[pile].first, last = line.bodies[pile].last;
    const std::size_t toe = !line.links.empty() && line.links.front().name == "near_end" ? 0 : Link::ground;
    const double slip_before =
        rest && toe != Link::ground ? std::max(0.0, rest->c_max[toe] - line.links[toe].law.soil.quake) : 0.0;
    if (rest) line_scheme->resume_soil(*rest);
    r = run_scheme(f.c, *scheme, f.c.step_count(), held);
    if (r.summary.status != RunStatus::complete || !r.summary.blow) return r;
    LineScheme::SoilRest end = line_scheme->soil_rest();
    const double slip_after =
        toe != Link::ground ? std::max(0.0, end.c_max[toe] - line.links[toe].law.soil.quake) : r.summary.blow->set;
    r.summary.blow->set = std::max(0.0, slip_after - slip_before);  // this blow's, not the soil's since the first
    const double capacity = (toe != Link::ground ? line.links[toe].law.soil.ultimate : 0.0) +
                            std::accumulate(line.shaft.ultimate.begin(), line.shaft.ultimate.end(), 0.0);
    const double this_set = r.summary.blow->set;
    if (blows == 1) first_set = this_set;
    if ((blows > 1 && within_percent(this_set, set)) || blows == most) break;
    set = this_set;
    for (std::size_t i = 0; i < end.c_max.size(); ++i)
      if (i != toe) end.c_max[i] = 0.0;  // the hammer's cushions unloaded
    locked_toe = settle(line, first, last, toe, end, 1e-6 * std::max(capacity, 1.0));
    touch_head(end, last);
    rest = std::move(end);
  }
  BlowSummary& b = *r.summary.blow;
  b.first_set = first_set;
  b.blows_run = blows;
  b.residual_toe_force = locked_toe;
  return r;
}

}  // namespace barimpact
