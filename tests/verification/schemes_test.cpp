// Every scheme against the exact solutions it fits (docs/methods.md):
// observed orders in h with dt tied to h, penetration, energy behaviour,
// penalty -> rigid, and the viscoelastic obstacle's dissipation.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "../support/run_case.hpp"
#include "barimpact/exact/exact.hpp"

namespace barimpact {
namespace {

using testing::example;
using testing::total_energy;

std::string num(double v) {
  return fmt::format("{}", v);
}

// Example 1 (exact (a), no gap) at M elements with `scheme`, dt = ratio h.
RunResult example1(const std::string& scheme, int M, double ratio, const std::string& kind,
                   std::vector<std::string> extra = {}) {
  std::vector<std::string> sets{"bar.elements=" + std::to_string(M), "time.scheme=\"" + scheme + "\"",
                                "obstacle.kind=" + kind, "output.fields_at=[]", "time.step=" + num(ratio / M)};
  for (auto& e : extra) sets.push_back(e);
  return run(example("paper-example1.toml", sets));
}

struct Errors {
  double U_l1 = 0;     // int |U - U_exact| dt
  double impulse = 0;  // max_t |int_0^t (R - R_exact)|
  double penetration = 0;
};

Errors errors(const RunResult& r, const exact::Solution& e, double dt) {
  Errors out;
  double I = 0, I_exact = 0;
  for (const auto& row : r.history) {
    out.U_l1 += std::abs(row.U - e.U(row.t)) * dt;
    I += row.R * dt;
    I_exact += e.R(row.t) * dt;
    out.impulse = std::max(out.impulse, std::abs(I - I_exact));
    out.penetration = std::max(out.penetration, -row.U);
  }
  return out;
}

TEST(Characteristic, IsExactAtTheNodesForTheRigidImpactWithGap) {
  // Exact (a) with a gap: flight, 2L/c on the wall, flight. Tolerance: round-off of 500 steps.
  const auto r =
      run(example("paper-example1.toml", {"obstacle.kind=rigid", "time.scheme=\"characteristic\"", "obstacle.gap=0.25",
                                          "bar.length=2", "bar.stiffness=4", "time.end=5", "output.fields_at=[]"}));
  // c = 2, h = 0.02, dt = h/c = 0.01 set by the scheme.
  const auto e = exact::rigid_impact(2.0, 4.0, 1.0, -1.0, 0.25);
  double worst = 0, worst_R = 0;
  for (const auto& row : r.history) {
    worst = std::max(worst, std::abs(row.U - e->U(row.t)));
    if (std::abs(row.t - 0.25) > 0.011 && std::abs(row.t - 2.25) > 0.011)
      worst_R = std::max(worst_R, std::abs(row.R - e->R(row.t)));
  }
  EXPECT_LT(worst, 1e-12);
  EXPECT_LT(worst_R, 1e-10);  // away from the two steps where R jumps
  ASSERT_EQ(r.summary.contacts.size(), 1u);
  EXPECT_NEAR(r.summary.contacts[0].start, 0.25, 1e-9);
  EXPECT_NEAR(r.summary.contacts[0].end, 2.25, 1e-9);
}

TEST(Characteristic, IsExactOnThePeriodicClampedBenchmark) {
  const auto r = run(example("clamped-periodic.toml", {"time.end=30", "output.fields_at=[]"}));
  const auto e = exact::clamped_periodic(1.0, 1.0, 1.0, 0.5);
  double worst = 0;
  for (const auto& row : r.history) worst = std::max(worst, std::abs(row.U - e->U(row.t)));
  EXPECT_LT(worst, 1e-12);  // 3000 steps of round-off
  EXPECT_EQ(r.summary.contacts.size(), 10u);
  EXPECT_NEAR(r.summary.max_reaction, 0.5, 1e-11);  // R from differences of G: round-off / h
}

TEST(Characteristic, RefusesAConflictingStep) {
  EXPECT_THROW((void)example("clamped-periodic.toml", {"time.step=0.02"}), InputError);
  EXPECT_NO_THROW((void)example("clamped-periodic.toml", {"time.step=0.01"}));
}

struct OrderCase {
  const char* scheme;
  double ratio;  // dt / h
  double min_U;  // asserted order of the L1 error of U
  double min_I;  // asserted order of the impulse error
  const char* measured;
};

void PrintTo(const OrderCase& c, std::ostream* os) {
  *os << c.scheme;
}

std::string test_name(const ::testing::TestParamInfo<OrderCase>& p) {
  std::string n = p.param.scheme;
  std::erase(n, '-');
  return n;
}

class RigidOrders : public ::testing::TestWithParam<OrderCase> {};

TEST_P(RigidOrders, ConvergeToExampleOnesRigidSolution) {
  const auto& p = GetParam();
  const auto e = exact::rigid_impact(1.0, 1.0, 1.0, -1.0, 0.0);
  std::vector<Errors> err;
  for (int M : {50, 100, 200, 400}) err.push_back(errors(example1(p.scheme, M, p.ratio, "rigid"), *e, p.ratio / M));
  for (std::size_t i = 1; i < err.size(); ++i) {
    EXPECT_GT(std::log2(err[i - 1].U_l1 / err[i].U_l1), p.min_U)
        << p.scheme << " level " << i << " (" << p.measured << ")";
    EXPECT_GT(std::log2(err[i - 1].impulse / err[i].impulse), p.min_I) << p.scheme << " level " << i;
  }
}

// Margins below the measured orders (docs/methods.md) for the pre-asymptotic levels.
INSTANTIATE_TEST_SUITE_P(Schemes, RigidOrders,
                         ::testing::Values(OrderCase{"central-difference", 1.0, 0.9, 0.9, "1.00, 1.00"},
                                           OrderCase{"paoli-schatzman", 0.5, 0.55, 0.6, "0.66, 0.73"},
                                           OrderCase{"moreau-jean", 1.0, 0.7, 0.6, "0.82-0.88, 0.70-0.72"},
                                           OrderCase{"mass-redistribution", 1.0, 0.5, 0.45, "0.57-0.64, 0.51-0.61"}),
                         test_name);

class PenaltyOrders : public ::testing::TestWithParam<OrderCase> {};

TEST_P(PenaltyOrders, ConvergeToTheElasticObstaclesExactSolution) {
  // Exact (c), k = 100 fixed: tau = rho c / k = 0.01, separation at 2 + 1.6783 tau.
  const auto& p = GetParam();
  const auto e = exact::elastic_impact(1.0, 1.0, 1.0, -1.0, 100.0);
  std::vector<Errors> err;
  for (int M : {100, 200, 400, 800})
    err.push_back(errors(example1(p.scheme, M, p.ratio, "elastic", {"obstacle.stiffness=100"}), *e, p.ratio / M));
  for (std::size_t i = 1; i < err.size(); ++i)
    EXPECT_GT(std::log2(err[i - 1].impulse / err[i].impulse), p.min_I) << p.scheme << " level " << i;
}

INSTANTIATE_TEST_SUITE_P(Schemes, PenaltyOrders,
                         ::testing::Values(OrderCase{"paper", 1.0, 0, 0.8, "1.10, 1.08, 1.25"},
                                           OrderCase{"newmark", 1.0, 0, 0.8, "0.92, 1.14, 1.28"},
                                           OrderCase{"central-difference", 0.5, 0, 0.8, "0.97, 1.19, 1.34"}),
                         test_name);

TEST(PenaltySchemes, ConvergeToTheRigidSolutionAsKGrowsWithTheMesh) {
  // k = 50 / h and dt tied to h: measured L1 orders of U 0.83-0.94 for paper,
  // newmark and central-difference.
  const auto e = exact::rigid_impact(1.0, 1.0, 1.0, -1.0, 0.0);
  for (auto [scheme, ratio] :
       {std::pair{"paper", 1.0}, std::pair{"newmark", 1.0}, std::pair{"central-difference", 0.5}}) {
    std::vector<double> err;
    for (int M : {100, 200, 400})
      err.push_back(
          errors(example1(scheme, M, ratio, "elastic", {"obstacle.stiffness=" + num(0.5 * M)}), *e, ratio / M).U_l1);
    for (std::size_t i = 1; i < err.size(); ++i) EXPECT_GT(std::log2(err[i - 1] / err[i]), 0.75) << scheme;
  }
}

TEST(RigidSchemes, NeverPenetrateBeyondRoundOff) {
  for (auto [scheme, ratio] : {std::pair{"central-difference", 1.0}, std::pair{"characteristic", 1.0},
                               std::pair{"paoli-schatzman", 0.5}, std::pair{"mass-redistribution", 1.0}}) {
    for (const char* file : {"paper-example1.toml", "clamped-periodic.toml"}) {
      const auto r = run(example(file, {"obstacle.kind=rigid", std::string("time.scheme=\"") + scheme + "\"",
                                        "time.step=" + num(ratio * 0.01), "output.fields_at=[]"}));
      double lowest = 0;
      for (const auto& row : r.history) lowest = std::min(lowest, row.U);
      EXPECT_GT(lowest, -1e-14) << scheme << " " << file;
    }
  }
}

TEST(MoreauJean, PenetratesOnlyByTheVelocityStep) {
  // The constraint is on velocities: U may go below 0 by at most dt |V| per impact.
  const auto r = example1("moreau-jean", 100, 1.0, "rigid");
  double lowest = 0;
  for (const auto& row : r.history) lowest = std::min(lowest, row.U);
  EXPECT_LE(-lowest, 0.01 * 1.0 + 1e-12);
  EXPECT_GT(-lowest, 0.0);
}

TEST(EnergyBudget, EverySchemeConservesItWithoutContactToRoundOffOver10000Steps) {
  // A free-free bar vibrating about rest (no rigid drift to cancel) under a
  // time-dependent load, 10^4 steps: the budget closes to round-off.
  for (auto [scheme, dt] :
       {std::pair{"paper", 0.01}, std::pair{"newmark", 0.01}, std::pair{"central-difference", 0.005},
        std::pair{"paoli-schatzman", 0.005}, std::pair{"moreau-jean", 0.01}, std::pair{"mass-redistribution", 0.01}}) {
    const auto r =
        run(example("paper-example1.toml",
                    {std::string("time.scheme=\"") + scheme + "\"", "obstacle.kind=none", "time.step=" + num(dt),
                     "time.end=" + num(dt * 10000), "output.fields_at=[]", "initial.displacement=\"0.1*sin(3*x)\"",
                     "initial.velocity=\"x - 0.5\"", "load.body_force=\"cos(3*x)*sin(t)\""}));
    double worst = 0, size = 0;
    for (std::size_t i = 1; i < r.history.size(); ++i) {
      worst = std::max(worst, std::abs(total_energy(r.history[i]) - total_energy(r.history[1])));
      size = std::max(size, r.history[i].E_kin + r.history[i].E_strain);
    }
    // The paper's three-level displacement form (A z^{n+1} = B1 z^n + B0 z^{n-1}
    // with B ~ 2M/dt^2) loses digits to cancellation every step: round-off
    // grows linearly, measured 1.1e-10 at 10^4 steps; the others <= 1e-11.
    const double tolerance = std::string(scheme) == "paper" ? 5e-10 : 1e-10;
    EXPECT_LT(worst, tolerance * size) << scheme << " relative drift " << worst / size;
  }
}

TEST(EnergyBudget, MoreauJeanWithFullRestitutionConservesItOver10000Steps) {
  // theta = 1/2, e = 1 on the periodic benchmark, 33 periods: measured 1.3e-12.
  const auto r = run(example("clamped-periodic.toml", {"time.scheme=\"moreau-jean\"", "time.step=0.01",
                                                       "time.restitution=1", "time.end=100", "output.fields_at=[]"}));
  ASSERT_EQ(r.history.size(), 10001u);
  for (const auto& row : r.history) EXPECT_NEAR(total_energy(row), 0.125, 1e-10);
}

TEST(EnergyBudget, DissipativeRigidSchemesNeverGainEnergy) {
  // e = 0 (central-difference, Paoli-Schatzman): non-increasing step by step
  // to round-off (measured largest increase 6e-15), 10^4 steps.
  for (auto [scheme, dt] : {std::pair{"central-difference", 0.01}, std::pair{"paoli-schatzman", 0.005}}) {
    const auto r =
        run(example("clamped-periodic.toml", {std::string("time.scheme=\"") + scheme + "\"", "time.step=" + num(dt),
                                              "time.end=" + num(dt * 10000), "output.fields_at=[]"}));
    for (std::size_t i = 1; i < r.history.size(); ++i)
      ASSERT_LE(total_energy(r.history[i]), total_energy(r.history[i - 1]) + 1e-13) << scheme << " row " << i;
    EXPECT_LT(total_energy(r.history.back()), 0.125 - 1e-4) << scheme;  // and do dissipate
  }
}

TEST(EnergyBudget, MoreauJeanLosesWhatNewtonsLawPredicts) {
  // theta = 1/2: E^{n+1} - E^n = p (V^n + V^{n+1}) / 2 with p = R dt, and at
  // an impact V^{n+1} = -e V^n, so the loss is p (1 - e) |V^n| / 2: booked
  // in D_contact, the budget closes (1e-12: a step's round-off).
  for (double e : {0.0, 0.5, 1.0}) {
    const double dt = 0.01;
    const auto r =
        run(example("clamped-periodic.toml", {"time.scheme=\"moreau-jean\"", "time.step=0.01",
                                              "time.restitution=" + num(e), "time.end=10", "output.fields_at=[]"}));
    int impacts = 0;
    for (std::size_t i = 1; i < r.history.size(); ++i) {
      const auto &a = r.history[i - 1], &b = r.history[i];
      const double p = b.R * dt;
      EXPECT_NEAR(b.D_contact - a.D_contact, -p * 0.5 * (a.V + b.V), 1e-12) << "e " << e << " row " << i;
      EXPECT_NEAR(total_energy(b), total_energy(a), 1e-12) << "e " << e << " row " << i;
      if (p > 0 && a.R == 0) {
        ++impacts;
        EXPECT_NEAR(b.V, -e * a.V, 1e-12);
      }
    }
    // The end falls on the obstacle at t = 1, 4, 7; with e > 0 it also
    // bounces during the resting phases (a velocity-level law cannot rest).
    EXPECT_GE(impacts, 3) << e;
  }
}

TEST(ViscoelasticObstacle, DissipatesAtImpactAndLessAsKGrows) {
  // l = 1/2 fixed. The continuum predicts O(1/k) (the end's velocity relaxes
  // in tau = (rho c + l)/k): measured D(100)/D(400) = 3.6. The balance,
  // dashpot included in D_visc, closes within 0.1%.
  std::vector<double> dissipated;
  for (double k : {100.0, 400.0}) {
    const auto r =
        run(example("paper-example1.toml", {"obstacle.kind=viscoelastic", "obstacle.viscosity=0.5",
                                            "obstacle.stiffness=" + num(k), "bar.elements=1000", "time.step=0.00025",
                                            "time.end=3", "output.every=10", "output.fields_at=[]"}));
    dissipated.push_back(r.history.back().D_visc);
    EXPECT_LT(r.summary.energy_error_max, 1e-3 * 0.5);
    EXPECT_LT(r.history.back().E_kin + r.history.back().E_strain, 0.5 - 0.5 * dissipated.back());
  }
  EXPECT_GT(dissipated[0], 1e-3);
  const double order = std::log2(dissipated[0] / dissipated[1]) / 2.0;
  EXPECT_GT(order, 0.7);
  EXPECT_LT(order, 1.2);
}

TEST(ViscoelasticObstacle, PaperReactionConvergesWhereTheLawClips) {
  // k = 1000, l = 5 > rho c: right after the impact the dashpot throws the end
  // back, and k d + l dd/dt < 0 while d > 0 for t in (0.010, 0.014): the law
  // clips, R = 0. At fixed h (M = 20), R converges in dt to the semi-discrete
  // solution, Newmark's at dt = 2e-6 (it solves the law implicitly).
  auto at = [](const std::string& scheme, double dt, int every) {
    return run(example("paper-example1.toml",
                       {"obstacle.kind=viscoelastic", "obstacle.stiffness=1000", "obstacle.viscosity=5",
                        "bar.elements=20", "time.end=0.5", "time.scheme=\"" + scheme + "\"", "time.step=" + num(dt),
                        "output.every=" + std::to_string(every), "output.fields_at=[]"}));
  };
  const double coarse = 2.5e-4;
  const auto ref = at("newmark", 2e-6, 125);  // a row every 2.5e-4
  int clipped = 0;
  for (const auto& row : ref.history) clipped += row.U < 0 && row.R == 0;
  ASSERT_GE(clipped, 10) << "the case must clip during contact";
  std::vector<double> err;  // int |R - R_ref| dt
  for (int r : {8, 4, 2, 1}) {
    const auto paper = at("paper", r * coarse, 1);
    double e = 0;
    for (std::size_t i = 0; i < paper.history.size(); ++i)
      e += std::abs(paper.history[i].R - ref.history[i * static_cast<std::size_t>(r)].R) * r * coarse;
    err.push_back(e);
  }
  // R jumps by l |V| = 5 when the dashpot engages at impact: a jump placed to
  // O(dt) caps the L1 order at 1. Measured 1.23, 1.09, 1.05 (0.67, 0.47, 0.22
  // while the spring stayed in the update with R reported 0).
  for (std::size_t i = 1; i < err.size(); ++i) EXPECT_GT(std::log2(err[i - 1] / err[i]), 0.9) << "level " << i;
}

TEST(EnergyBudget, PenaltySchemesBookTheSpringWhenTheViscoelasticLawClips) {
  // A soft, strongly damped obstacle (k = 10, l = 3): the end leaves while
  // still penetrating, k d + l dd/dt < 0 with d > 0, R = 0. The spring's
  // k d^2 / 2, in E_obstacle while stored, goes to D_visc as it is released.
  for (auto scheme : {"paper", "newmark", "central-difference"}) {
    const auto r =
        run(example("paper-example1.toml", {std::string("time.scheme=\"") + scheme + "\"", "obstacle.kind=viscoelastic",
                                            "obstacle.stiffness=10", "obstacle.viscosity=3", "bar.elements=50",
                                            "time.step=0.001", "time.end=4", "output.fields_at=[]"}));
    int clipped = 0;
    double worst = 0;
    const double initial = total_energy(r.history.front());
    for (const auto& row : r.history) {
      clipped += row.U < 0 && row.R == 0;
      worst = std::max(worst, std::abs(total_energy(row) - initial));
    }
    ASSERT_GE(clipped, 10) << scheme;
    // What remains is O(dt^2): the spring's energy against its discrete work
    // across the face and at the switches. Measured 5.8e-6 (paper), 8.6e-7
    // (newmark), 8.5e-6 (central-difference); 7.3e-2 and 7.2e-2 for the last
    // two when the released energy was booked nowhere.
    EXPECT_LT(worst / initial, 1e-4) << scheme;
  }
}

TEST(PaperScheme, IsSecondOrderInTimeWithANonzeroInitialAcceleration) {
  // Example 2's load f = -1 on a bar clamped at x = L, at rest, without
  // obstacle: a0 = M^{-1} F != 0. At fixed h (M = 20) the max error of U
  // against the semi-discrete solution (Newmark at dt = 0.01/64), dt halved
  // from 0.01. Shifted (lambda = 0.25, with viscosity) and not.
  for (const std::vector<std::string>& variant :
       {std::vector<std::string>{}, std::vector<std::string>{"time.lambda=0.25", "bar.viscosity=0.01"}}) {
    auto at = [&](const std::string& scheme, double dt) {
      std::vector<std::string> sets = variant;
      for (const char* key : {"obstacle.kind=none", "bar.far_end=\"clamped\"", "initial.velocity=\"0\"",
                              "bar.elements=20", "time.end=2", "output.fields_at=[]"})
        sets.emplace_back(key);
      sets.push_back("time.scheme=\"" + scheme + "\"");
      sets.push_back("time.step=" + num(dt));
      return run(example("paper-example2.toml", sets));
    };
    const auto ref = at("newmark", 0.01 / 64);
    std::vector<double> err;
    for (int r : {64, 32, 16, 8}) {
      const auto paper = at("paper", r * 0.01 / 64);
      double e = 0;
      for (std::size_t i = 0; i < paper.history.size(); ++i)
        e = std::max(e, std::abs(paper.history[i].U - ref.history[i * static_cast<std::size_t>(r)].U));
      err.push_back(e);
    }
    // A linear problem with a smooth solution: the scheme's order, 2, once the
    // start is second order. Measured 1.96-2.02 (1.00-1.02 with the
    // first-order start z^1 = u0 + dt (v0 - lambda u0)).
    for (std::size_t i = 1; i < err.size(); ++i)
      EXPECT_GT(std::log2(err[i - 1] / err[i]), 1.8)
          << (variant.empty() ? "lambda = 0" : "lambda = 0.25") << " level " << i;
  }
}

}  // namespace
}  // namespace barimpact
