// `characteristic` on lines of bodies (schemes/line_characteristic.hpp):
// exact at the nodes, to round-off, on piecewise-uniform bars (the single
// bar's exact solutions through the line engine, a step wave through a
// welded impedance jump, Saint-Venant's rods); second order with a mass; the
// budget closing to round-off; the single-bar scheme reproduced; refusals.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <cmath>
#include <functional>

#include "../support/line_parts.hpp"
#include "../support/run_case.hpp"
#include "barimpact/case/line_builder.hpp"
#include "barimpact/exact/exact.hpp"
#include "barimpact/exact/lines.hpp"
#include "barimpact/run/simulate.hpp"
#include "barimpact/schemes/line_characteristic.hpp"
#include "barimpact/schemes/registry.hpp"

namespace barimpact {
namespace {

using testing::bar;
using testing::joint;
using testing::mass;

// A line case stepped by `characteristic` at the line's own step.
Case line_case(std::vector<BodyData> bodies, std::vector<JointData> joints, double end) {
  Case c;
  c.bodies = std::move(bodies);
  c.joints = std::move(joints);
  c.time.scheme = "characteristic";
  c.time.end = end;
  c.time.step = line_characteristic_step(build_line(c)).value();
  return c;
}

// Steps `c` to its end, calling `row` at every t_n with the scheme and its line.
void step_through(const Case& c, const std::function<void(const Scheme&, const Line&)>& row) {
  const Line line = build_line(c);
  auto s = make_scheme(c);
  s->start();
  const long long steps = c.step_count();
  for (long long n = 0; n <= steps; ++n) {
    if (n > 0) s->advance();
    row(*s, line);
  }
}

// The largest nodal error of u against a line solution over the run, each
// body's nodes read on that body; and of the link force when `links`.
double nodal_error(const Case& c, const exact::LineSolution& e, bool links = true) {
  double worst = 0.0;
  step_through(c, [&](const Scheme& s, const Line& line) {
    const double t = s.time();
    if (t > e.valid_until()) return;
    for (std::size_t b = 0; b < line.bodies.size(); ++b)
      for (std::size_t j = line.bodies[b].first; j <= line.bodies[b].last; ++j)
        worst = std::max(worst, std::abs(s.displacement_at(j) - e.fields(b, line.x[j], t).u));
    if (links)
      for (std::size_t i = 0; i < e.links(); ++i)
        worst = std::max(worst, std::abs(s.link_force(i) - e.link_force(i, t)));
  });
  return worst;
}

// The budget's largest departure from its value at row `from`, over the
// largest of E_kin + E_strain and |W_ext|.
double budget_drift(const RunResult& r, std::size_t from = 0) {
  double scale = 0.0, worst = 0.0;
  for (const auto& h : r.history) scale = std::max({scale, h.E_kin + h.E_strain, std::abs(h.W_ext)});
  for (std::size_t k = from; k < r.history.size(); ++k)
    worst = std::max(worst, std::abs(r.history[k].total() - r.history[from].total()));
  return worst / scale;
}

// The single bar's case and the same bar through the line engine.
std::pair<Case, Case> single_and_line(const std::string& example, const std::vector<std::string>& sets) {
  std::vector<std::string> all = sets;
  all.push_back("time.scheme=characteristic");
  all.push_back("output.fields_at=[]");
  const Case single = testing::example(example, all);
  Case line = single;
  return {single, line};
}

// (a) and (d) through the line engine: exact at the nodes (U) and in the
// force (R, away from the steps where it jumps), the budget closed to
// round-off from row 0 (the single bar's is off by Z |V|^2 dt / 8 there,
// 0.25% of the energy: its first half step books R(0), half the force of
// the step (0, dt)).
TEST(LineCharacteristic, IsExactForTheSingleBarsExactSolutions) {
  {
    const auto [single, line] =
        single_and_line("paper-example1.toml",
                        {"obstacle.kind=rigid", "obstacle.gap=0.25", "bar.length=2", "bar.stiffness=4", "time.end=5"});
    const auto e = exact::rigid_impact(2.0, 4.0, 1.0, -1.0, 0.25);
    const RunResult r = run(line);
    double worst = 0, worst_R = 0;
    for (const auto& row : r.history) {
      worst = std::max(worst, std::abs(row.U - e->U(row.t)));
      if (std::abs(row.t - 0.25) > 0.011 && std::abs(row.t - 2.25) > 0.011)
        worst_R = std::max(worst_R, std::abs(row.R - e->R(row.t)));
    }
    EXPECT_LT(worst, 1e-12);
    EXPECT_LT(worst_R, 1e-10);  // R from differences of u over dt: round-off / dt
    EXPECT_LT(budget_drift(r), 1e-12);
    EXPECT_NEAR(r.history.back().D_contact, 0.0, 1e-12);  // the elastic impact gives everything back
  }
  {
    const auto [single, line] = single_and_line("clamped-periodic.toml", {"time.end=30"});
    const auto e = exact::clamped_periodic(1.0, 1.0, 1.0, 0.5);
    const RunResult r = run(line);
    double worst = 0;
    for (const auto& row : r.history) worst = std::max(worst, std::abs(row.U - e->U(row.t)));
    EXPECT_LT(worst, 1e-12);  // 3000 steps of round-off
    // From row 1: u0 strains the free end x = 0 (data incompatible there),
    // and the first half step's discrete energy H^{1/2} holds k (kappa h)^2 / 4
    // less than u0's (0.5% here, the single bar's too).
    EXPECT_LT(budget_drift(r, 1), 1e-12);
  }
  {
    const auto [single, line] = single_and_line("paper-example1.toml", {"obstacle.kind=rigid"});
    const RunResult r = run(line);
    EXPECT_LT(budget_drift(r), 1e-12);            // contact from t = 0
    EXPECT_LT(budget_drift(run(single)), 1e-12);  // and the single bar's, its reaction booked against V(0)
  }
}

// (b) A step force F0 = 1 on the near end of bar 1 (Z1 = 1), welded to bar 2
// (Z2 = 2 or 1/2; each bar's transit h/c = 0.02). Every nodal u is exact to
// round-off while the wave and its reflections cross both bars, and the
// axial forces read off the elements give the transmitted 2 Z2 / (Z1 + Z2)
// and the reflected (Z2 - Z1) / (Z1 + Z2) of the incident force exactly.
TEST(LineCharacteristic, IsExactThroughAWeldedImpedanceJump) {
  for (double modulus : {4.0, 0.25}) {  // c2 = 2 or 1/2 (rho = 1): Z2 = 2 or 1/2
    const double c2 = std::sqrt(modulus), Z1 = 1.0, Z2 = c2;
    BodyData second = bar("b", 1.0, static_cast<int>(std::lround(50.0 / c2)));
    second.modulus = modulus;
    Case c = line_case({bar("a", 1.0, 50), second}, {}, 5.0);
    c.near_end.law = JointLaw::force;
    c.near_end.value = "1";
    ASSERT_NEAR(c.time.step, 0.02, 1e-15);
    const auto e = exact::for_line_case(c);
    ASSERT_TRUE(e != nullptr);
    EXPECT_LT(nodal_error(c, *e), 1e-12) << modulus;
    // At t = 1.5 the transmitted wave is halfway along bar 2, the reflected
    // one halfway back along bar 1: N = -(1 + R) there, -T in bar 2 behind the front.
    const double T = 2.0 * Z2 / (Z1 + Z2), R = (Z2 - Z1) / (Z1 + Z2);
    c.time.end = 1.5;
    step_through(c, [&](const Scheme& s, const Line& line) {
      if (s.step() != c.step_count()) return;
      auto axial = [&](std::size_t j) {
        return line.bonds[j].stiffness * (s.displacement_at(j + 1) - s.displacement_at(j));
      };
      const std::size_t junction = line.bodies[1].first;
      EXPECT_NEAR(axial(junction - 1), -(1.0 + R), 1e-12) << modulus;  // incident + reflected
      EXPECT_NEAR(axial(junction), -T, 1e-12) << modulus;              // transmitted
      EXPECT_NEAR(axial(5), -1.0, 1e-12) << modulus;                   // incident only
    });
    const RunResult r = run(c);
    EXPECT_LT(budget_drift(r), 1e-12) << modulus;  // the force end's work, from row 0
  }
}

// (c) Saint-Venant's rods through a rigid joint: the joint pushes with
// Z (v1 - v2) / 2 for exactly 2 L_short / c from the step the faces meet,
// every nodal u is exact to round-off throughout (the shorter rod then moves
// rigidly at the longer one's initial velocity, the longer carries the
// pulse), the link force too (half of it on the two steps where contact
// starts and ends, the exact solution's mean), and the budget closes to
// round-off from row 0 (D_contact: what the discrete energy books where the
// faces meet and part, O(dt), not a loss of the continuum).
TEST(LineCharacteristic, IsExactForSaintVenantsRods) {
  struct Rods {
    double L1, L2, v1, v2, gap;
    int M1, M2;
  };
  for (const Rods& d : {Rods{1.0, 2.0, 1.0, 0.0, 0.1, 50, 100}, Rods{2.0, 1.0, 1.0, -0.5, 0.06, 100, 50},
                        Rods{1.0, 1.0, 2.0, 0.0, 0.0, 50, 50}}) {
    Case c = line_case({bar("a", d.L1, d.M1, fmt::format("{}", d.v1)), bar("b", d.L2, d.M2, fmt::format("{}", d.v2))},
                       {joint("a", "b", JointLaw::rigid, d.gap)}, 6.0);
    const auto e = exact::for_line_case(c);
    ASSERT_TRUE(e != nullptr);
    EXPECT_LT(nodal_error(c, *e), 1e-12) << d.L1 << " " << d.L2;
    const auto& sv = dynamic_cast<const exact::SaintVenant&>(*e);
    const RunResult r = run(c);
    double first = -1, last = -1;
    for (std::size_t k = 0; k < r.history.size(); ++k) {
      const double p = r.extra[k * r.columns.size()];  // joint.a-b.force
      if (p > 1e-9 && first < 0) first = r.history[k].t;
      if (p > 1e-9) last = r.history[k].t;
    }
    EXPECT_NEAR(first, sv.contact_start(), 1e-12);
    EXPECT_NEAR(last, sv.contact_end(), 1e-12);
    EXPECT_LT(budget_drift(r), 1e-12);
    // Unequal rods part at equal face speeds, and the pulse's two sharp ends
    // keep the discrete energy Z (v1 - v2)^2 dt / 8 below the true one; equal
    // rods part at v1 - v2, which books it back.
    const double dv = d.v1 - d.v2, kept = d.L1 == d.L2 ? 0.0 : sv.impedance() * dv * dv * c.time.step / 8.0;
    EXPECT_NEAR(r.history.back().D_contact, kept, 1e-12);
  }
}

// A mass m at v0 strikes through a rigid joint the free end of a bar clamped
// at x = 0 (Z = 1, L = c = 1): until the reflection returns at 2L/c the end
// pushes with Z |v0| exp(-Z t / m). The mass's trapezoidal rule makes the
// force and the mass's motion second order (the bar stays exact between):
// the errors over 0 < t < 2L/c (t = 0 and 2L/c, where p jumps and the scheme
// reports the mean, left out) at M = 40 ... 320 elements, dt = 1/M.
// Measured orders: force 1.98-1.99 (m = 1) and 1.91-1.98 (m = 1/4), the
// mass's u 2.00; errors at M = 320: force 2.4e-6 and 3.8e-5, u 3.0e-7 and
// 1.2e-6. The budget closes to round-off at every M (6e-13 of the energy
// at most, after 640 steps).
struct DropErrors {
  double force = 0.0, mass_u = 0.0, budget = 0.0;
};

DropErrors drop_errors(int elements, double m) {
  Case c = line_case({bar("bar", 1.0, elements), mass("mass", m, -1.0)}, {joint("bar", "mass", JointLaw::rigid)}, 2.0);
  c.near_end.law = JointLaw::clamped;
  const auto e = exact::for_line_case(c);
  const auto& drop = dynamic_cast<const exact::DropMass&>(*e);
  DropErrors out;
  step_through(c, [&](const Scheme& s, const Line& line) {
    const double t = s.time();
    if (t > 1e-9 && t < 2.0 - 1e-9) out.force = std::max(out.force, std::abs(s.link_force(0) - std::exp(-t / m)));
    out.mass_u = std::max(out.mass_u, std::abs(s.displacement_at(line.nodes() - 1) - drop.mass_u(t)));
  });
  out.budget = budget_drift(run(c));
  return out;
}

TEST(LineCharacteristic, ConvergesAtSecondOrderForAMassStrikingAClampedBar) {
  for (double m : {1.0, 0.25}) {
    std::vector<DropErrors> errors;
    for (int elements : {40, 80, 160, 320}) errors.push_back(drop_errors(elements, m));
    for (std::size_t k = 1; k < errors.size(); ++k) {
      const double force = std::log2(errors[k - 1].force / errors[k].force);
      const double u = std::log2(errors[k - 1].mass_u / errors[k].mass_u);
      EXPECT_GT(force, 1.9) << m << " " << k;
      EXPECT_GT(u, 1.9) << m << " " << k;
    }
    for (const auto& e : errors) EXPECT_LT(e.budget, 5e-12) << m;  // the trapezoidal rule's own identity
  }
}

// A busy line: an impedance jump (welded bars of Z = 1 and 2), a mass welded
// on a bar's end, a free mass between two rigid joints with gaps (links
// sharing a node: projected Gauss-Seidel), a third bar (Z = 4) with a mass
// welded on its far end pushed by f(t) = -0.5 t, the near end driven at
// v(t) = 0.1 sin 3t. Undeformed bodies moving rigidly: the budget closes to
// round-off from row 0 (1e-12 of the energy over 500 steps).
Case busy_line() {
  BodyData stiff = bar("b", 1.0, 25);  // c = 2, h = 0.04
  stiff.modulus = 4.0;
  BodyData heavy = bar("c", 0.5, 50, "-0.5");  // c = 1/2, h = 0.01, Z = A sqrt(E rho) = 4
  heavy.density = 4.0;
  heavy.area = 2.0;
  Case c =
      line_case({bar("a", 1.0, 50), stiff, mass("m1", 0.5, 0.0), mass("m2", 0.3, -1.0), heavy, mass("m3", 0.2, -0.5)},
                {joint("m1", "m2", JointLaw::rigid, 0.01), joint("m2", "c", JointLaw::rigid, 0.02)}, 10.0);
  c.near_end.law = JointLaw::velocity;
  c.near_end.value = "0.1 * sin(3 * t)";
  c.far_end.law = JointLaw::force;
  c.far_end.value = "-0.5 * t";
  return c;
}

TEST(LineCharacteristic, BudgetClosesOnABusyLine) {
  const Case c = busy_line();
  ASSERT_NEAR(c.time.step, 0.02, 1e-15);
  const RunResult r = run(c);
  ASSERT_TRUE(r.summary.complete) << r.summary.message;
  EXPECT_LT(budget_drift(r), 1e-12);
  double largest[2] = {0.0, 0.0};
  for (std::size_t k = 0; k < r.history.size(); ++k)
    for (std::size_t i = 0; i < 2; ++i) largest[i] = std::max(largest[i], r.extra[k * r.columns.size() + 2 * i]);
  EXPECT_GT(largest[0], 0.0);  // both joints pushed
  EXPECT_GT(largest[1], 0.0);
  for (const auto& h : r.history) EXPECT_GE(h.E_kin, 0.0);
}

// What the scheme cannot run exactly is refused, naming the law, joint or
// body and the schemes that can; a bar whose transit time differs is named
// with the element count that would fit; a step other than the transit
// time is refused on time.step.
TEST(LineCharacteristic, RefusesWhatItCannotRunExactly) {
  auto rule_of = [](const Case& c) {
    const auto m = scheme_misfit(c, build_line(c));
    return m ? m->key + ": " + m->rule : std::string();
  };
  auto expect = [&](const Case& c, const std::vector<std::string>& parts) {
    const std::string rule = rule_of(c);
    for (const auto& part : parts) EXPECT_NE(rule.find(part), std::string::npos) << rule;
    EXPECT_THROW((void)make_scheme(c), InputError);
  };
  const Case base = line_case({bar("a", 1.0, 50), bar("b", 1.0, 50)}, {joint("a", "b", JointLaw::rigid)}, 1.0);
  EXPECT_EQ(rule_of(base), "");
  Case c = base;
  c.bodies[1].viscosity = 0.01;
  expect(c, {"scheme: ", "viscous body \"b\"", "central-difference, newmark"});
  c = base;
  c.joints[0].law.law = JointLaw::spring;
  expect(c, {"scheme: ", "spring joint between \"a\" and \"b\"", "mass-redistribution"});
  c = base;
  c.joints[0].law.law = JointLaw::cushion;
  expect(c, {"scheme: ", "cushion link \"joint.a-b\"", "paper, newmark, central-difference, paoli-schatzman"});
  c = base;
  c.near_end.law = JointLaw::elastic;
  expect(c, {"scheme: ", "elastic link \"near_end\""});
  c = base;
  c.load.body_force = "1";
  expect(c, {"scheme: ", "body force or gravity"});
  c = base;
  c.load.gravity = 9.81;
  expect(c, {"scheme: ", "body force or gravity"});
  c = base;
  c.bodies[1].modulus = 4.0;  // c = 2: h/c = 0.01
  EXPECT_FALSE(line_characteristic_step(build_line(c)).has_value());
  expect(c, {"scheme: ", "body \"b\" has 0.01, body \"a\" 0.02", "give \"b\" 25 elements"});
  c.bodies[1].length = 1.01;
  expect(c, {"no whole number of elements of \"b\" does: L / (c dt) = 25.25"});
  c = base;
  c.time.step = 0.01;
  expect(c, {"step: = 0.01 is not the line's element transit time h/c = 0.02"});
  c.bodies = {mass("m", 1.0, 0.0)};
  c.joints.clear();
  EXPECT_FALSE(line_characteristic_step(build_line(c)).has_value());
  expect(c, {"scheme: ", "needs a bar"});
}

}  // namespace
}  // namespace barimpact
