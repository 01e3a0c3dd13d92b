#include "barimpact/schemes/paper_scheme.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "../support/dense.hpp"
#include "../support/run_case.hpp"

namespace barimpact {
namespace {

using testing::case_from;

// Two elements, worked by hand. L = 2, M = 2 (h = 1), rho = 6, a = 1, b = 0,
// k = 4, dt = 1, alpha = 1/4, lambda = 0, u0 = 0, v0 = -1. Then
//   M = [[2,1,0],[1,4,1],[0,1,2]],  S = K_a + 2 e0 e0^T = [[3,-1,0],[-1,2,-1],[0,-1,1]],
//   z^0 = 0, z^1 = -(1,1,1),  A = M + S/4,
//   rhs = M (2 z^1 - z^0) - S (z^1/2 + z^0/4) + (k/2)|z^1_0| e0 = (-3, -12, -6),
// and 4A z^2 = 4 rhs, i.e. [[11,3,0],[3,18,3],[0,3,9]] z^2 = (-12,-48,-24), solved by
// elimination: z^2 = (-42, -202, -170) / 89. Second step, the same way (in exact
// fractions): rhs = M (2 z^2 - z^1) - S (z^2/2 + z^1/4) + 2 |z^2_0| e0
// = (-429/178, -1410/89, -833/89), z^3 = (-499/7921, -70873/23763, -25075/7921).
constexpr const char* two_elements = R"toml([bar]
length = 2
density = 6
stiffness = 1
elements = 2
[initial]
velocity = "-1"
[obstacle]
stiffness = 4
[time]
step = 1
end = 2
alpha = 0.25
)toml";

TEST(PaperScheme, FirstStepsOfTwoElementsMatchTheHandComputation) {
  PaperScheme s(case_from(two_elements));
  s.start();
  ASSERT_EQ(s.step(), 0);
  EXPECT_EQ(s.end_displacement(), 0.0);
  EXPECT_EQ(s.end_velocity(), -1.0);
  for (std::size_t j = 0; j < 3; ++j) EXPECT_EQ(s.next_level()[j], -1.0);  // (6.3)(iii)
  s.advance();
  ASSERT_EQ(s.step(), 1);
  const auto z2 = s.next_level();
  // Tolerance: a few ulps of the elimination's round-off.
  EXPECT_NEAR(z2[0], -42.0 / 89.0, 1e-14);
  EXPECT_NEAR(z2[1], -202.0 / 89.0, 1e-14);
  EXPECT_NEAR(z2[2], -170.0 / 89.0, 1e-14);
  // At t_1: U = -1, R = k U^- = 4, V = (z^2_0 - z^0_0) / (2 dt) = -21/89.
  EXPECT_DOUBLE_EQ(s.end_displacement(), -1.0);
  EXPECT_DOUBLE_EQ(s.reaction(), 4.0);
  EXPECT_NEAR(s.end_velocity(), -21.0 / 89.0, 1e-15);
  s.advance();
  const auto z3 = s.next_level();
  EXPECT_NEAR(z3[0], -499.0 / 7921.0, 1e-14);
  EXPECT_NEAR(z3[1], -70873.0 / 23763.0, 1e-14);
  EXPECT_NEAR(z3[2], -25075.0 / 7921.0, 1e-14);
  EXPECT_NEAR(s.reaction(), 4.0 * 42.0 / 89.0, 1e-14);  // R^2 = k (z^2_0)^-
}

// A dense, independent transcription of the scheme's matrix form (docs/methods.md): full
// matrices assembled element by element, Gaussian elimination every step.
struct DenseReference {
  using Matrix = testing::DenseMatrix;
  std::size_t n;
  Matrix A, B1, B0, Mh, Ka, Kb;

  DenseReference(int M, double L, double rho, double a, double b, double k, double dt, double alpha, double lambda)
      : n(static_cast<std::size_t>(M) + 1), A(n, std::vector<double>(n)), B1(A), B0(A), Mh(A), Ka(A), Kb(A) {
    const double h = L / M;
    for (std::size_t e = 0; e + 1 < n; ++e) {
      const double me[2][2] = {{rho * h / 3, rho * h / 6}, {rho * h / 6, rho * h / 3}};
      const double ke[2][2] = {{1 / h, -1 / h}, {-1 / h, 1 / h}};
      for (int p = 0; p < 2; ++p)
        for (int q = 0; q < 2; ++q) {
          Mh[e + p][e + q] += me[p][q];
          Ka[e + p][e + q] += a * ke[p][q];
          Kb[e + p][e + q] += b * ke[p][q];
        }
    }
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = 0; j < n; ++j) {
        const double S = lambda * lambda * Mh[i][j] + Ka[i][j] + lambda * Kb[i][j] + (i == 0 && j == 0 ? k / 2 : 0.0);
        const double D = 2 * lambda * Mh[i][j] + Kb[i][j];
        A[i][j] = Mh[i][j] / (dt * dt) + alpha * S + D / (2 * dt);
        B1[i][j] = 2 * Mh[i][j] / (dt * dt) - (1 - 2 * alpha) * S;
        B0[i][j] = -Mh[i][j] / (dt * dt) - alpha * S + D / (2 * dt);
      }
  }
};

class PaperDense : public ::testing::TestWithParam<int> {};

// M = 1, 2, 5, 6, 7: the two-ended solve's halves are equal (M even) or the
// lower one has a row more (M odd), and M = 1 has no upper half at all.
INSTANTIATE_TEST_SUITE_P(Elements, PaperDense, ::testing::Values(1, 2, 5, 6, 7));

TEST_P(PaperDense, MatchesADenseTranscriptionWithEveryTermActive) {
  // Viscosity, shift, gap, initial displacement, a load f = x t whose hat
  // integrals are known in closed form, and contact during the run.
  const int M = GetParam();
  const double L = 1.5, rho = 2.0, a = 3.0, b = 0.05, k = 40.0, g = 0.01, dt = 0.02, alpha = 0.3, lambda = 0.4;
  const Case c = case_from(R"toml([bar]
length = 1.5
density = 2
stiffness = 3
viscosity = 0.05
elements = )toml" + std::to_string(M) +
                           R"toml(
[load]
body_force = "x * t"
[initial]
displacement = "0.02 * x"
velocity = "-1 + x / 3"
[obstacle]
stiffness = 40
gap = 0.01
[time]
step = 0.02
end = 0.4
alpha = 0.3
lambda = 0.4
)toml");
  PaperScheme s(c);
  s.start();
  DenseReference ref(M, L, rho, a, b, k, dt, alpha, lambda);
  const std::size_t n = ref.n;
  const double h = L / M;
  auto load = [&](double t) {  // exp(-lambda t) (x t, phi_i)
    std::vector<double> F(n);
    for (std::size_t j = 0; j < n; ++j) F[j] = static_cast<double>(j) * h * h;
    F[0] = h * h / 6;
    F[n - 1] = h * (L / 2 - h / 6);
    for (auto& f : F) f *= t * std::exp(-lambda * t);
    return F;
  };
  // The Taylor start: z^1 = u0 + dt (v0 - lambda u0) + (dt^2/2) (a0 - 2 lambda v0 + lambda^2 u0),
  // M_h a0 = F(0) - K_a u0 - K_b v0 + k ((u0_0 + g)^-) e0 (F(0) = 0 here).
  std::vector<double> u0(n), v0(n), f0(n);
  for (std::size_t j = 0; j < n; ++j) {
    u0[j] = 0.02 * static_cast<double>(j) * h;
    v0[j] = -1 + static_cast<double>(j) * h / 3;
  }
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j < n; ++j) f0[i] -= ref.Ka[i][j] * u0[j] + ref.Kb[i][j] * v0[j];
  f0[0] += k * std::max(0.0, -(u0[0] + g));
  const auto a0 = testing::dense_solve(ref.Mh, f0);
  std::vector<double> zm(n), z(n);
  for (std::size_t j = 0; j < n; ++j) {
    zm[j] = u0[j];
    z[j] =
        u0[j] + dt * (v0[j] - lambda * u0[j]) + 0.5 * dt * dt * (a0[j] - 2 * lambda * v0[j] + lambda * lambda * u0[j]);
  }
  bool touched = false;
  for (int m = 1; m <= 20; ++m) {
    const double t = m * dt;
    const auto Fp = load(t + dt), F0 = load(t), Fm = load(t - dt);
    const double e = std::exp(-lambda * t);
    const double ebar =
        alpha * std::exp(-lambda * (t + dt)) + (1 - 2 * alpha) * e + alpha * std::exp(-lambda * (t - dt));
    std::vector<double> r(n);
    for (std::size_t i = 0; i < n; ++i) {
      for (std::size_t j = 0; j < n; ++j) r[i] += ref.B1[i][j] * z[j] + ref.B0[i][j] * zm[j];
      r[i] += alpha * Fp[i] + (1 - 2 * alpha) * F0[i] + alpha * Fm[i];
    }
    r[0] += 0.5 * k * (std::abs(z[0] + g * e) - g * ebar);
    touched = touched || z[0] + g * e < 0;
    const auto zp = testing::dense_solve(ref.A, r);
    s.advance();
    // Tolerance: the two solvers round differently; 1e-12 relative is far
    // below any modelling change (a dropped term moves the answer by > 1e-6).
    for (std::size_t j = 0; j < n; ++j) EXPECT_NEAR(s.next_level()[j], zp[j], 1e-12 * (1 + std::abs(zp[j]))) << m;
    zm = z;
    z = zp;
  }
  EXPECT_TRUE(touched) << "the case must exercise the contact term";
}

TEST(PaperScheme, ShiftedAndUnshiftedRunsAgreeAtPlotScale) {
  // The paper: lambda = 0 and 0.25 show "no distinction at the adopted scale".
  // Plot scale: 1% of U's range (about 2 on (0, 4)), i.e. 0.02.
  auto U = [](double lambda) {
    auto c = testing::example("paper-example1.toml", {"time.lambda=" + std::to_string(lambda)});
    std::vector<double> out;
    for (const auto& r : run(c).history) out.push_back(r.U);
    return out;
  };
  const auto u0 = U(0.0), u1 = U(0.25);
  ASSERT_EQ(u0.size(), u1.size());
  double worst = 0.0;
  for (std::size_t i = 0; i < u0.size(); ++i) worst = std::max(worst, std::abs(u0[i] - u1[i]));
  EXPECT_LT(worst, 0.02);
  EXPECT_GT(worst, 0.0) << "lambda must change the computation";
}

TEST(PaperScheme, NonFiniteStateStopsTheRunAndNamesTheStep) {
  // alpha = 0 is explicit in the stiffness: dt = 0.1 on h = 0.01 is far above
  // its stability limit, the state grows until it overflows.
  auto c =
      testing::example("paper-example1.toml", {"time.alpha=0", "time.step=0.1", "time.end=400", "output.every=1000"});
  const auto r = run(c);
  EXPECT_FALSE(r.summary.complete);
  EXPECT_EQ(r.summary.status, RunStatus::non_finite);
  EXPECT_NE(r.summary.message.find("step"), std::string::npos);
  EXPECT_LT(r.summary.steps_done, r.summary.steps);
  ASSERT_FALSE(r.history.empty());
  EXPECT_EQ(r.history.front().t, 0.0);
  for (const auto& row : r.history) EXPECT_TRUE(std::isfinite(row.U));
}

// The partitioned solve (Wang's method, for bars of partition_threshold
// nodes and more) against the two-ended one on 401 nodes, over 600 steps
// of contact and release. Variants: the elastic obstacle alone; viscosity,
// an unsteady load, lambda and a gap; the viscoelastic obstacle (its dashpot
// a force at row 0 of the partitioned solve) with a steady load. History
// rows alternate between the fused form (begin_energies, the sums inside the
// step) and energies() after it. Each solve is backward stable (residual
// 2e-16 |A| |x|, as the two-ended solve's), and the first steps agree to
// 1e-15 of each quantity's scale; over the run the step's dynamics amplify
// the rounding difference (a momentum difference drifts U linearly; the
// release step is the most sensitive; E_kin divides differences by dt), as
// they do for any reordering of the solve: the one-ended Thomas solve
// (P = 1) differs from the two-ended one by 1e-11 on the same runs.
// Measured worst over the run: U 8e-12 to 9e-11, R 4e-12 to 3e-11, the
// energies 5e-11 to 3.4e-10 (lambda, viscosity and the unsteady load the
// largest); asserted: 1e-12 over the first 10 steps, 1e-9 (U, R) and 1e-8
// (energies) over the run.
TEST(PaperScheme, PartitionedSolveGivesTheTwoEndedResults) {
  const std::string common = R"toml([bar]
elements = 400
length = 0.125
[initial]
velocity = "-1"
[time]
step = 0.00125
end = 3
)toml";
  const std::vector<std::vector<std::string>> variants = {
      {"obstacle.stiffness=100"},
      {"obstacle.stiffness=100", "obstacle.gap=0.001", "bar.viscosity=0.01", "load.body_force=\"0.3 * x * t\"",
       "time.lambda=0.25"},
      {"obstacle.kind=\"viscoelastic\"", "obstacle.stiffness=100", "obstacle.viscosity=1", "load.body_force=\"0.3\""},
  };
  for (const auto& sets : variants) {
    const Case c = case_from(common, sets);
    PaperScheme sequential(c), partitioned(c);
    ASSERT_EQ(sequential.use_partitions(0), 0u);
    ASSERT_EQ(partitioned.use_partitions(8), 8u);
    ASSERT_TRUE(partitioned.partitioned());
    sequential.start();
    partitioned.start();
    const std::size_t n = sequential.nodes();
    // The largest difference so far of U (every node), R and the energies,
    // each relative to its quantity's largest magnitude up to that step.
    double u_scale = 0.0, r_scale = 0.0, e_scale = 0.0, worst_u = 0.0, worst_r = 0.0, worst_e = 0.0;
    for (int step = 0; step < 600; ++step) {
      if (step == 10) {
        EXPECT_LE(std::max({worst_u, worst_r, worst_e}), 1e-12) << "the first steps, one rounding apart";
        EXPECT_GT(worst_u, 0.0) << "not one rounding apart: the partitioned solve did not run";
      }
      Energies es, ep;
      if (step % 2 == 0) {  // a history row's half steps summed inside the next step
        const bool done_s = sequential.begin_energies(es), done_p = partitioned.begin_energies(ep);
        ASSERT_EQ(done_s, done_p);
        sequential.advance();
        partitioned.advance();
        if (!done_s) sequential.finish_energies(es), partitioned.finish_energies(ep);
      } else {
        sequential.advance();
        partitioned.advance();
        es = sequential.energies(), ep = partitioned.energies();
      }
      for (std::size_t j = 0; j < n; ++j) u_scale = std::max(u_scale, std::abs(sequential.displacement_at(j)));
      r_scale = std::max(r_scale, std::abs(sequential.reaction()));
      e_scale = std::max({e_scale, es.kinetic + es.strain + es.obstacle, std::abs(es.work), es.dissipation});
      for (std::size_t j = 0; j < n; ++j)
        worst_u = std::max(worst_u, std::abs(partitioned.displacement_at(j) - sequential.displacement_at(j)) / u_scale);
      if (r_scale > 0.0)
        worst_r = std::max(worst_r, std::abs(partitioned.reaction() - sequential.reaction()) / r_scale);
      for (auto [p, s] :
           {std::pair{ep.kinetic, es.kinetic}, std::pair{ep.strain, es.strain}, std::pair{ep.obstacle, es.obstacle},
            std::pair{ep.work, es.work}, std::pair{ep.dissipation, es.dissipation}})
        worst_e = std::max(worst_e, std::abs(p - s) / e_scale);
    }
    EXPECT_LE(worst_u, 1e-9) << sets[0];
    EXPECT_LE(worst_r, 1e-9) << sets[0];
    EXPECT_LE(worst_e, 1e-8) << sets[0];
    EXPECT_GT(r_scale, 0.0);                // the end pushed
    EXPECT_EQ(sequential.reaction(), 0.0);  // and let go
  }
}

// A bar of partition_threshold nodes and more takes the partitioned solve; below, the two-ended one.
TEST(PaperScheme, LargeBarsTakeThePartitionedSolve) {
  const auto bar_of = [](std::size_t elements) {
    return PaperScheme(
        case_from("[bar]\nelements = " + std::to_string(elements) + "\n[time]\nstep = 0.001\nend = 1\n"));
  };
  EXPECT_FALSE(bar_of(PaperScheme::partition_threshold - 2).partitioned());
  EXPECT_TRUE(bar_of(PaperScheme::partition_threshold - 1).partitioned());
  // time.partitions: 1 keeps a large bar's two-ended solve; a count asks for chunks at any size.
  EXPECT_FALSE(
      PaperScheme(case_from("[bar]\nelements = 5000\n[time]\nstep = 0.001\nend = 1\npartitions = 1\n")).partitioned());
  EXPECT_TRUE(
      PaperScheme(case_from("[bar]\nelements = 100\n[time]\nstep = 0.001\nend = 1\npartitions = 4\n")).partitioned());
}

}  // namespace
}  // namespace barimpact
