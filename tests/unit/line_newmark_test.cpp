// Newmark's scheme on lines of bodies (line_newmark.hpp): the trapezoidal
// rule's budget, its links' laws held at the new level, and convergence to
// the welded junction.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <utility>

#include "../support/line_parts.hpp"
#include "../support/line_runs.hpp"
#include "../support/run_case.hpp"
#include "barimpact/case/line_builder.hpp"
#include "barimpact/run/simulate.hpp"
#include "barimpact/schemes/line_newmark.hpp"
#include "barimpact/schemes/registry.hpp"

namespace barimpact {
namespace {

using testing::bar;
using testing::law_joint;
using testing::line_case;
using testing::mass;
using testing::measured_order;

// The trapezoidal rule conserves a line's energy without contact to
// round-off (springs, welded masses, a force and a velocity end, gravity,
// viscosity in D_visc): 1e-10 of the scale over 4000 steps.
TEST(LineNewmark, BudgetClosesWithSpringsMassesAndDrivenEnds) {
  JointData spring = law_joint("b", "m1", JointLaw::spring, 50.0, 0.3);
  BodyData visco = bar("b", 1.0, 40, "0.2 * x");
  visco.viscosity = 0.01;
  Case c = line_case({bar("a", 1.0, 40), visco, mass("m1", 0.5, 0.0), mass("m2", 0.25, 0.0)}, {spring}, 0.002, 8.0,
                     "newmark");
  c.near_end.law = JointLaw::velocity;
  c.near_end.value = "0.1 * sin(3 * t)";
  c.far_end.law = JointLaw::force;
  c.far_end.value = "-0.5 * t";
  c.load.gravity = 0.3;
  const RunResult r = run(c);
  ASSERT_TRUE(r.summary.complete) << r.summary.message;
  double scale = 0.0;
  for (const auto& h : r.history) scale = std::max({scale, h.E_kin + h.E_strain + h.E_obstacle, std::abs(h.W_ext)});
  const double e0 = r.history.front().total();
  for (const auto& h : r.history) ASSERT_NEAR(h.total(), e0, 1e-10 * scale) << h.t;
}

// A cushion and an elastic end under Newmark: the cushion's hysteresis is
// D_contact, and the budget closes but for the penalty laws' trapezoidal
// error across their kinks (1% of the scale at dt = 1e-3, as the single
// bar's Newmark at impacts).
TEST(LineNewmark, CushionBudgetCloses) {
  JointData cushion = law_joint("pile", "ram", JointLaw::cushion, 200.0, 0.6);
  Case c = line_case({bar("pile", 1.0, 100), mass("ram", 2.0, -1.0)}, {cushion}, 0.001, 4.0, "newmark");
  c.near_end.law = JointLaw::elastic;
  c.near_end.stiffness = 1000.0;
  const RunResult r = run(c);
  ASSERT_TRUE(r.summary.complete) << r.summary.message;
  double scale = 0.0;
  for (const auto& h : r.history) scale = std::max(scale, h.E_kin + h.E_strain + h.E_obstacle);
  const double e0 = r.history.front().total();
  for (const auto& h : r.history) EXPECT_NEAR(h.total(), e0, 1e-2 * scale) << h.t;
  EXPECT_GT(r.history.back().D_contact, 0.0);
}

// Newmark solves its links' laws at t_{n+1} exactly, together: a bar
// striking a row of point masses through an elastic, a viscoelastic and a
// cushion link (each mass between two links, so that their forces move one
// another: k beta dt^2 W of order 1 at dt = 0.02), an elastic far end. At
// every step each link's force is its law at the new (c, dc/dt) (or the
// viscoelastic law's face, c = 0 with 0 <= p <= l dc/dt), to 1e-10 of the
// largest force.
TEST(LineNewmark, CoupledLinksHoldTheirLawsAtTheNewLevel) {
  JointData elastic = law_joint("a", "m1", JointLaw::elastic, 400.0);
  JointData visco = law_joint("m1", "m2", JointLaw::viscoelastic, 300.0, 5.0);
  JointData cushion = law_joint("m2", "m3", JointLaw::cushion, 500.0, 0.5);
  Case c = line_case({bar("a", 1.0, 20, "1"), mass("m1", 0.05, 0.0), mass("m2", 0.05, 0.0), mass("m3", 0.05, 0.0)},
                     {elastic, visco, cushion}, 0.02, 3.0, "newmark");
  c.far_end.law = JointLaw::elastic;
  c.far_end.stiffness = 300.0;
  const Line line = build_line(c);
  ASSERT_EQ(line.links.size(), 4u);
  auto s = make_scheme(c);
  s->start();
  std::vector<double> v(line.nodes()), c_max(line.links.size(), 0.0), largest(line.links.size(), 0.0);
  double scale = 0.0;
  for (long long n = 1; n <= c.step_count(); ++n) {
    s->advance();
    s->velocity(v);
    for (std::size_t i = 0; i < line.links.size(); ++i) {
      const double comp = -s->link_opening(i), rate = -(line.opening(i, v.data()) - line.links[i].gap);
      const double p = s->link_force(i);
      c_max[i] = std::max(c_max[i], comp);
      largest[i] = std::max(largest[i], p);
      scale = std::max(scale, p);
      const ContactLaw& law = line.links[i].law;
      const double error = std::abs(p - law.force(comp, rate, c_max[i]));
      const bool face = law.kind == LawKind::viscoelastic && std::abs(comp) * law.stiffness <= 1e-10 * scale &&
                        p >= 0.0 && p <= law.viscosity * rate + 1e-10 * scale;
      ASSERT_TRUE(error <= 1e-10 * scale || face) << "link " << i << " step " << n << ": " << p;
    }
  }
  for (double f : largest) EXPECT_GT(f, 0.0);  // every link pushed
}

// Newmark against the welded junction (a force step through two
// impedances): the near end's displacement converges at the rate of a
// discontinuous wave (measured 0.65-0.67 over four meshes), asserted above 0.55.
TEST(LineNewmark, ConvergesToTheWeldedJunction) {
  EXPECT_GT(measured_order(testing::welded_junction("newmark"), false), 0.55);
}

// The partitioned solve of A (8 chunks) against the sequential one on one
// line: a bar hitting an elastic end at x = 0 and leaving it, plain, under
// gravity, and viscous under gravity, so that every branch of the
// partitioned step runs. Tolerance 1e-12 relative to each quantity's largest size: the two
// solves differ in rounding only (kappa(A) eps ~ 1e-15 a step, A = M +
// gamma dt C + beta dt^2 K at c dt / h = 2), carried by a stable scheme
// over 600 steps (measured: 6e-16 to 3e-15 of U).
TEST(LineNewmark, PartitionedSolveGivesTheSequentialResults) {
  for (auto [viscous, loaded] : {std::pair{false, false}, std::pair{false, true}, std::pair{true, true}}) {
    BodyData b = bar("bar", 1.0, 400, "-1");
    if (viscous) b.viscosity = 0.01;
    Case c = line_case({b}, {}, 0.005, 3.0, "newmark");
    c.near_end.law = JointLaw::elastic;
    c.near_end.stiffness = 1000.0;
    if (loaded) c.load.gravity = 0.3;
    LineNewmark sequential(c, build_line(c)), partitioned(c, build_line(c));
    ASSERT_EQ(sequential.use_partitions(0), 0u);
    ASSERT_EQ(partitioned.use_partitions(8), 8u);  // the line can: else both would be sequential
    sequential.start();
    partitioned.start();
    const std::size_t n = sequential.nodes();
    double u_scale = 0.0, r_scale = 0.0, e_scale = 0.0, worst = 0.0;
    for (int step = 0; step < 600; ++step) {
      sequential.advance();
      partitioned.advance();
      for (std::size_t j = 0; j < n; ++j) u_scale = std::max(u_scale, std::abs(sequential.displacement_at(j)));
      r_scale = std::max(r_scale, std::abs(sequential.reaction()));
      const Energies es = sequential.energies(), ep = partitioned.energies();
      e_scale = std::max({e_scale, es.kinetic + es.strain + es.obstacle, std::abs(es.work), es.dissipation});
      for (std::size_t j = 0; j < n; ++j) {
        const double d = std::abs(partitioned.displacement_at(j) - sequential.displacement_at(j));
        ASSERT_LE(d, 1e-12 * u_scale) << "step " << step << ", node " << j;
        worst = std::max(worst, d / u_scale);
      }
      ASSERT_LE(std::abs(partitioned.reaction() - sequential.reaction()), 1e-12 * r_scale) << "step " << step;
      for (auto [p, s] :
           {std::pair{ep.kinetic, es.kinetic}, std::pair{ep.strain, es.strain}, std::pair{ep.obstacle, es.obstacle},
            std::pair{ep.work, es.work}, std::pair{ep.dissipation, es.dissipation}, std::pair{ep.contact, es.contact}})
        ASSERT_LE(std::abs(p - s), 1e-12 * e_scale) << "step " << step;
    }
    EXPECT_GT(r_scale, 0.0);                // the end pushed: the force at row 0 went through the reduced system
    EXPECT_EQ(sequential.reaction(), 0.0);  // and let go
    EXPECT_GT(worst, 0.0) << "not one rounding apart: the partitioned solve did not run";
  }
}

// A lone mass (one node) takes no chunks, however many the case asks: its
// step has no bond for the partitioned step's stencil (it read past node 0).
TEST(LineNewmark, ALoneMassStaysSequential) {
  Case c = Case::from_string(
      "[[body]]\nname = \"m\"\nkind = \"mass\"\nmass = 1.0\nvelocity = \"-1\"\n"
      "[near_end]\nlaw = \"elastic\"\nstiffness = 100.0\n"
      "[time]\nscheme = \"newmark\"\nstep = 0.01\nend = 0.5\npartitions = 2\n",
      {}, "mass");
  LineNewmark s(c, build_line(c));
  EXPECT_EQ(s.partitions(), 0u);
  s.start();
  for (int step = 0; step < 50; ++step) s.advance();
  EXPECT_TRUE(s.finite());
  EXPECT_GT(s.displacement_at(0), -0.2);  // pushed back by the spring (k = 100, m = 1: it turns within 0.16 s)
}

// time.partitions: a count of chunks is the scheme's, 1 the sequential solve
// however large the line; the key is written back with the case.
TEST(LineNewmark, TakesTheChunksTheCaseAsks) {
  BodyData b = bar("bar", 1.0, 3000, "-1");
  Case c = line_case({b}, {}, 0.001, 0.1, "newmark");  // 100 steps: long enough for "auto" to take chunks
  c.near_end.law = JointLaw::elastic;
  c.near_end.stiffness = 1000.0;
  c.time.partitions = 1;
  LineNewmark one(c, build_line(c));
  c.time.partitions = 0;  // "auto": 3001 nodes are past the threshold
  LineNewmark chosen(c, build_line(c));
  c.time.end = 0.01;  // 10 steps: "auto" keeps the sequential solve, whose set-up costs less
  LineNewmark brief(c, build_line(c));
  c.time.end = 0.1;
  c.time.partitions = 16;
  LineNewmark asked(c, build_line(c));
  EXPECT_EQ(one.partitions(), 0u);
  EXPECT_EQ(chosen.partitions(), LineNewmark::default_partitions);
  EXPECT_EQ(brief.partitions(), 0u);
  EXPECT_EQ(asked.partitions(), 16u);
  const Case again = Case::from_string(c.to_toml(), {}, "again");
  EXPECT_EQ(again.time.partitions, 16);
  EXPECT_EQ(Case::from_string("[time]\npartitions = \"auto\"", {}, "auto").time.partitions, 0);
  // The three steps agree within the partitioned solve's rounding (u ~ 1e-2
  // after 10 steps; the solves differ by a few eps of it).
  one.start(), chosen.start(), asked.start();
  for (int step = 0; step < 10; ++step) one.advance(), chosen.advance(), asked.advance();
  for (std::size_t j = 0; j < one.nodes(); j += 97) {
    EXPECT_NEAR(chosen.displacement_at(j), one.displacement_at(j), 1e-14);
    EXPECT_NEAR(asked.displacement_at(j), one.displacement_at(j), 1e-14);
  }
}

}  // namespace
}  // namespace barimpact
