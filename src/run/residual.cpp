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

// The forces on nodes 0..n-1 (+x up) at rest.u from the committed state in
// `rest`: gravity, the bonds, the unilateral links among those nodes and
// with the ground, Smith's shaft; and their tangent (K du = r's matrix).
// The trial slips and largest compressions they would commit go in `trial`.
struct Forces {
  std::vector<double> r, diag, off;
  LineScheme::SoilRest trial;
  double toe_force = 0.0;
};

void add_bonds(const Line& line, std::size_t n, const std::vector<double>& u, Forces& f) {
  for (std::size_t j = 0; j + 1 < n; ++j) {
    const Bond& b = line.bonds[j];
    if (b.kind == BondKind::open) continue;            // a link carries it, if anything
    const double t = b.stiffness * (u[j + 1] - u[j]);  // tension pulls its ends together
    f.r[j] += t;
    f.r[j + 1] -= t;
    f.diag[j] += b.stiffness;
    f.diag[j + 1] += b.stiffness;
    f.off[j] -= b.stiffness;
  }
}

void add_links(const Line& line, std::size_t n, const LineScheme::SoilRest& rest, Forces& f) {
  for (std::size_t i = 0; i < line.links.size(); ++i) {
    const Link& l = line.links[i];
    const bool a_in = l.a == Link::ground || l.a < n;
    if (!a_in || l.b == Link::ground || l.b >= n || l.law.rigid()) continue;
    const double ua = l.a == Link::ground ? 0.0 : rest.u[l.a];
    const double c = -(rest.u[l.b] - ua + l.gap);
    const double c_max = std::max(rest.c_max[i], c);
    f.trial.c_max[i] = c_max;
    const double p = l.law.static_force(c, c_max);
    double k = 0.0;  // d p / d c: the branch the compression is on (touching faces: closed)
    if (c >= 0.0) {
      const bool loading = c >= rest.c_max[i];
      k = l.law.kind == LawKind::cushion && !loading ? l.law.largest_stiffness() : l.law.stiffness;
      if (l.law.kind == LawKind::smith && p >= l.law.soil.ultimate) k = 0.0;  // slipping
    }
    if (l.is_end && l.law.kind == LawKind::smith) f.toe_force = p;
    f.r[l.b] += p;
    f.diag[l.b] += k;
    if (l.a != Link::ground) {
      f.r[l.a] -= p;
      f.diag[l.a] += k;
      f.off[l.a] -= k;  // neighbours: a + 1 = b
    }
  }
}

void add_shaft(const Line& line, std::size_t n, const LineScheme::SoilRest& rest, Forces& f) {
  const Shaft& s = line.shaft;
  for (std::size_t j = 0; j < n && j < s.ultimate.size(); ++j) {
    if (!(s.ultimate[j] > 0.0)) continue;
    const double w = -rest.u[j];  // penetration, down
    const double slip = smith_slip(rest.shaft_slip[j], w, s.quake[j]);
    f.trial.shaft_slip[j] = slip;
    f.r[j] += s.stiffness[j] * (w - slip);
    f.diag[j] += slip == rest.shaft_slip[j] ? s.stiffness[j] : 0.0;  // elastic, or slipping
  }
}

Forces forces(const Line& line, std::size_t n, const std::vector<double>& weight, const LineScheme::SoilRest& rest) {
  Forces f{std::vector<double>(n, 0.0), std::vector<double>(n, 0.0), std::vector<double>(n > 1 ? n - 1 : 0, 0.0), rest,
           0.0};
  for (std::size_t j = 0; j < n; ++j) f.r[j] = -weight[j];
  add_bonds(line, n, rest.u, f);
  add_links(line, n, rest, f);
  add_shaft(line, n, rest, f);
  return f;
}

}  // namespace

double settle(const Line& line, std::size_t count, double gravity, LineScheme::SoilRest& rest, double tolerance) {
  std::vector<double> weight = line.lumped_mass();
  weight.resize(count);
  for (double& w : weight) w *= gravity;
  double stiffest = 0.0;
  for (const Bond& b : line.bonds) stiffest = std::max(stiffest, b.stiffness);
  for (int iteration = 0; iteration < 200; ++iteration) {
    Forces f = forces(line, count, weight, rest);
    double worst = 0.0;
    for (std::size_t i = 0; i < count; ++i) {
      worst = std::max(worst, std::abs(f.r[i]));
      f.diag[i] += 1e-12 * stiffest;  // a line with every spring slipping still has a step
    }
    if (worst <= tolerance) {
      rest.shaft_slip = f.trial.shaft_slip;
      rest.c_max = f.trial.c_max;
      return f.toe_force;
    }
    solve_tangent(f.diag, f.off, {}, f.r);  // K du = r: forces(u + du) ~ forces(u) - K du = 0
    for (std::size_t i = 0; i < count; ++i) rest.u[i] += f.r[i];
  }
  throw std::runtime_error(fmt::format("the pile's static rest did not converge to {:.3g} N", tolerance));
}

namespace {

bool within_percent(double a, double b) {
  return std::abs(a - b) <= 0.01 * std::abs(b);
}

// The ram: [hammer]'s, else [blow]'s, else the outermost body.
std::size_t ram_body(const Case& c) {
  const std::string& name = c.hammer ? c.hammer->ram : c.blow.ram;
  for (std::size_t i = 0; i < c.bodies.size() && !name.empty(); ++i)
    if (c.bodies[i].name == name) return i;
  return c.bodies.size() - 1;
}

// The nodes below the ram: what rests on the soil before a blow.
std::size_t below_ram(const Case& c, const Line& line) {
  return line.bodies[ram_body(c)].first;
}

// The ram (and whatever is above it) touching the body below, at its start.
void touch_ram(const Case& c, const Line& line, LineScheme::SoilRest& rest) {
  const std::size_t first = below_ram(c, line);
  for (std::size_t j = first; first > 0 && j < rest.u.size(); ++j) rest.u[j] = rest.u[first - 1];
}

// A soil of Smith's springs alone whose capacity is below the weight resting
// on it has no static rest: the pile sinks under its own weight (a capacity
// in kN read as N, most likely).
void check_soil_holds(const Case& c, const Line& line, double weight) {
  const bool toe_link = !line.links.empty() && line.links.front().name == "near_end";
  if (toe_link && line.links.front().law.kind != LawKind::smith) return;  // a stop that holds any weight
  const double toe = toe_link ? line.links.front().law.soil.ultimate : 0.0;
  const double capacity = toe + std::accumulate(line.shaft.ultimate.begin(), line.shaft.ultimate.end(), 0.0);
  if (capacity >= weight) return;
  c.refuse(toe_link ? "near_end.ultimate" : "body.shaft.ultimate",
           fmt::format("= {:g}: the soil's static capacity, toe and shaft, {:.4g} N, is below the weight resting on "
                       "it under [load] gravity ({:.4g} N, the pile and what sits on it): no static rest (capacities "
                       "are in N: kN?)",
                       toe_link ? toe : capacity, capacity, weight));
}

}  // namespace

bool start_at_rest(const Case& c, Scheme& scheme) {
  auto* line_scheme = dynamic_cast<LineScheme*>(&scheme);
  if (line_scheme == nullptr || !line_scheme->keeps_soil_rest()) return false;
  if (line_scheme->resuming()) return true;  // a residual analysis's blow: its rest is set
  const Line& line = *scheme.line();
  LineScheme::SoilRest rest{std::vector<double>(line.nodes(), 0.0), std::vector<double>(line.nodes(), 0.0),
                            std::vector<double>(line.links.size(), 0.0)};
  const std::size_t count = below_ram(c, line);
  const std::vector<double> mass = line.lumped_mass();
  const double weight = line.gravity * std::accumulate(mass.begin(), mass.begin() + static_cast<long>(count), 0.0);
  check_soil_holds(c, line, weight);
  (void)settle(line, count, line.gravity, rest, 1e-9 * std::max(weight, 1.0));  // the weight's balance to 1e-9
  touch_ram(c, line, rest);
  line_scheme->resume_soil(std::move(rest));
  return true;
}

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
    const std::size_t last = line.bodies[pile].last;  // the pile head
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
      if (i != toe) end.c_max[i] = 0.0;                                            // the hammer's cushions unloaded
    for (std::size_t j = last + 1; j < end.u.size(); ++j) end.u[j] = end.u[last];  // its bodies on the pile head
    locked_toe = settle(line, below_ram(c, line), line.gravity, end, 1e-6 * std::max(capacity, 1.0));
    touch_ram(c, line, end);
    rest = std::move(end);
  }
  BlowSummary& b = *r.summary.blow;
  b.first_set = first_set;
  b.blows_run = blows;
  b.residual_toe_force = locked_toe;
  return r;
}

}  // namespace barimpact
