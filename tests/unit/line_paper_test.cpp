// The paper's scheme on lines of bodies (line_paper.hpp): the single bar's
// numbers on one bar, the alpha-scheme's identity on a line, its penalty
// links' budget and momentum, and convergence to the lines' exact solutions.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <cmath>

#include "../support/line_parts.hpp"
#include "../support/line_runs.hpp"
#include "../support/run_case.hpp"
#include "barimpact/case/line_builder.hpp"
#include "barimpact/run/simulate.hpp"
#include "barimpact/schemes/registry.hpp"

namespace barimpact {
namespace {

using testing::bar;
using testing::column;
using testing::law_joint;
using testing::line_case;
using testing::mass;
using testing::measured_order;

// The paper's scheme on a line: the single bar's on one bar (the same
// equations with per-row coefficients, solved from one end instead of two),
// the elastic, viscoelastic (through its three statuses) and no obstacle
// with a gap, free and clamped far ends, with and without the shift lambda,
// a load in x and t and a viscous bar. A three-level scheme carries its
// round-off into u as n^2 eps (u^{n+1} - 2u^n + u^{n-1} is what a step
// resolves), which R = k d multiplies by k: measured up to 3.3e-10 of the
// scale on R, 5e-11 elsewhere, after 600 steps; asserted at 1e-9.
TEST(LinePaper, MatchesTheSingleBarSchemeOnOneBar) {
  for (const char* kind : {"elastic", "viscoelastic", "none"})
    for (const char* far : {"free", "clamped"})
      for (const char* lambda : {"0", "0.25"}) {
        const bool clamped = std::string(far) == "clamped";
        Case single = testing::example(
            "paper-example1.toml",
            {"time.step=0.005", "time.end=3", "output.fields_at=[1.0]", std::string("obstacle.kind=") + kind,
             "obstacle.viscosity=2", "obstacle.gap=0.001", "bar.viscosity=0.01", std::string("bar.far_end=") + far,
             std::string("initial.velocity=") + (clamped ? "\"-(1 - x)\"" : "\"-1\""),
             std::string("time.lambda=") + lambda, "load.body_force=\"-1 + x * t\""});
        Case line = single;
        line.bodies = {bar("bar", 1.0, 100, single.one_bar()->initial.velocity)};
        line.bodies[0].viscosity = 0.01;
        line.near_end.law = std::string(kind) == "elastic"        ? JointLaw::elastic
                            : std::string(kind) == "viscoelastic" ? JointLaw::viscoelastic
                                                                  : JointLaw::free;
        line.near_end.stiffness = single.one_bar()->obstacle.stiffness;
        line.near_end.viscosity = single.one_bar()->obstacle.viscosity;
        line.near_end.gap = single.one_bar()->obstacle.gap;
        line.far_end.law = clamped ? JointLaw::clamped : JointLaw::free;
        const RunResult a = run(single), b = testing::run_line_engine(line);
        ASSERT_EQ(a.history.size(), b.history.size());
        for (std::size_t k = 0; k < a.history.size(); ++k) {
          const HistoryRow &x = a.history[k], &y = b.history[k];
          for (auto [p, q] :
               {std::pair{x.U, y.U}, std::pair{x.V, y.V}, std::pair{x.R, y.R}, std::pair{x.E_kin, y.E_kin},
                std::pair{x.E_strain, y.E_strain}, std::pair{x.E_obstacle, y.E_obstacle}, std::pair{x.W_ext, y.W_ext},
                std::pair{x.D_visc, y.D_visc}})
            ASSERT_NEAR(p, q, 1e-9 * (1.0 + std::abs(p))) << kind << " " << far << " " << lambda << " row " << k;
        }
      }
}

// The alpha-scheme's identity (7.1) on a line: without links and with
// lambda = 0, E_kin + E_strain + E_obstacle (springs) - W_ext + D_visc is
// constant from row 1 on to round-off (springs, dashpots, welded masses, a
// force and a velocity end, gravity, a viscous bar; 1e-10 of the scale over
// 4000 steps; measured 1.7e-11) for every alpha; row 0 to row 1 carries the Taylor
// start's O(dt^2) (1.8e-7).
TEST(LinePaper, BudgetClosesWithSpringsMassesAndDrivenEnds) {
  for (double alpha : {0.25, 0.4}) {
    JointData spring = law_joint("b", "m1", JointLaw::spring, 50.0, 0.3);
    BodyData visco = bar("b", 1.0, 40, "0.2 * x");
    visco.viscosity = 0.01;
    Case c = line_case({bar("a", 1.0, 40), visco, mass("m1", 0.5, 0.0), mass("m2", 0.25, 0.0)}, {spring}, 0.002, 8.0,
                       "paper");
    c.time.alpha = alpha;
    c.near_end.law = JointLaw::velocity;
    c.near_end.value = "0.1 * sin(3 * t)";
    c.far_end.law = JointLaw::force;
    c.far_end.value = "-0.5 * t";
    c.load.gravity = 0.3;
    const RunResult r = run(c);
    ASSERT_TRUE(r.summary.complete) << r.summary.message;
    double scale = 0.0;
    for (const auto& h : r.history) scale = std::max({scale, h.E_kin + h.E_strain + h.E_obstacle, std::abs(h.W_ext)});
    const double e1 = r.history[1].total();
    for (std::size_t k = 1; k < r.history.size(); ++k)
      ASSERT_NEAR(r.history[k].total(), e1, 1e-10 * scale) << alpha << " t " << r.history[k].t;
    EXPECT_NEAR(r.history[1].total(), r.history[0].total(), 1e-5 * scale);
    EXPECT_GT(r.history.back().D_visc, 0.0);
    EXPECT_NE(r.history.back().W_ext, 0.0);
    EXPECT_EQ(column(r, "body.m1.u", 10), column(r, "body.m2.u", 10));  // welded: one node
  }
}

// Penalty links of every law at joints and ends (an elastic near end, a
// viscoelastic joint with a gap, a cushion under a mass, gravity): their
// explicit halves and statuses close the budget at O(dt^2), with the
// cushion's hysteresis in D_contact and the dashpot's work in D_visc. The
// largest drift depends on where each switch falls between steps, so the
// order from one halving to the next is erratic (drifts 4.9e-4, 2.0e-4,
// 6.9e-5, 9.1e-6 of the scale from dt = 0.002 to 0.00025: 1.3, 1.5, 2.9);
// over the three halvings it is 1.9, asserted above 1.6, the finest below 3e-5.
TEST(LinePaper, PenaltyLinksBudgetClosesAtSecondOrder) {
  auto drift = [](double dt) {
    JointData visco = law_joint("a", "b", JointLaw::viscoelastic, 400.0, 1.0);
    visco.law.gap = 0.01;
    JointData cushion = law_joint("b", "ram", JointLaw::cushion, 300.0, 0.6);
    Case c = line_case({bar("a", 1.0, 40, "-0.5"), bar("b", 1.0, 40), mass("ram", 1.0, -2.0)}, {visco, cushion}, dt,
                       3.0, "paper");
    c.near_end.law = JointLaw::elastic;
    c.near_end.stiffness = 200.0;
    c.load.gravity = 0.5;
    const RunResult r = run(c);
    EXPECT_TRUE(r.summary.complete) << r.summary.message;
    EXPECT_GT(r.history.back().D_contact, 0.0);
    EXPECT_GT(r.history.back().D_visc, 0.0);
    double scale = 0.0, e = 0.0;
    for (const auto& h : r.history) scale = std::max({scale, h.E_kin + h.E_strain + h.E_obstacle, std::abs(h.W_ext)});
    for (const auto& h : r.history) e = std::max(e, std::abs(h.total() - r.history.front().total()));
    return e / scale;
  };
  const double coarse = drift(0.002), finest = drift(0.00025);
  EXPECT_GT(std::log2(coarse / finest) / 3.0, 1.6);
  EXPECT_LT(finest, 3e-5);
}

// The links' forces are equal and opposite, explicit and implicit halves
// alike: a free line without load keeps its momentum (row sums of M_h with
// the point masses times the centred velocities) through elastic,
// viscoelastic and cushion joints to round-off: the levels' rounding over
// 2 dt, 9.2e-12 of a momentum of 1.5 after 800 steps; asserted at 5e-11.
TEST(LinePaper, JointsConserveMomentum) {
  JointData elastic = law_joint("a", "b", JointLaw::elastic, 500.0);
  JointData visco = law_joint("b", "m", JointLaw::viscoelastic, 300.0, 2.0);
  JointData cushion = law_joint("m", "c", JointLaw::cushion, 400.0, 0.5);
  Case c = line_case({bar("a", 1.0, 30, "2"), bar("b", 1.0, 30), mass("m", 0.5, 0.0), bar("c", 0.5, 20, "-1")},
                     {elastic, visco, cushion}, 0.005, 4.0, "paper");
  const Line line = build_line(c);
  const std::vector<double> m = line.lumped_mass();
  auto s = make_scheme(c);
  s->start();
  const double p0 = testing::momentum(m, *s);
  double largest[3] = {0, 0, 0};
  for (long long n = 1; n <= c.step_count(); ++n) {
    s->advance();
    for (std::size_t i = 0; i < 3; ++i) largest[i] = std::max(largest[i], s->link_force(i));
    ASSERT_NEAR(testing::momentum(m, *s), p0, 5e-11) << "step " << n;
  }
  for (double f : largest) EXPECT_GT(f, 0.0);  // every joint pushed
}

// The paper's scheme against the welded junction (a force step through two
// impedances): the near end's displacement converges at the rate of a
// discontinuous wave (measured 0.66, as Newmark), asserted above 0.55.
TEST(LinePaper, ConvergesToTheWeldedJunction) {
  EXPECT_GT(measured_order(testing::welded_junction("paper"), false), 0.55);
}

// Penalty to rigid: Saint-Venant's rods through an elastic joint approach
// the rigid joint's exact solution as k grows (the near end's displacement,
// max error; 100 + 200 elements, dt = 5e-4 below Z/k so that the explicit
// half resolves the contact): measured 0.0143 at k = 100 and 0.0100 at
// k = 1000, where the mesh's own error of the discontinuous wave (about
// 0.009, what k = 1e5 leaves) dominates.
TEST(LinePaper, ElasticJointApproachesSaintVenantsRigidRods) {
  auto error = [](double k) {
    JointData j = law_joint("a", "b", JointLaw::elastic, k);
    Case c = line_case({bar("a", 1.0, 100, "1"), bar("b", 2.0, 200)}, {j}, 0.0005, 6.0, "paper");
    Case rigid = c;
    rigid.joints[0].law.law = JointLaw::rigid;
    const auto solution = exact::line_end(rigid);
    EXPECT_TRUE(solution != nullptr);
    const RunResult r = run(c);
    double e = 0.0;
    for (const auto& h : r.history) {
      if (h.t > solution->valid_until()) break;
      e = std::max(e, std::abs(h.U - solution->U(h.t)));
    }
    return e;
  };
  const double soft = error(1e2), stiff = error(1e3);
  EXPECT_LT(stiff, 0.8 * soft);
  EXPECT_LT(stiff, 0.011);
}

}  // namespace
}  // namespace barimpact
