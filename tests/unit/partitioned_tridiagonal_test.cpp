#include "barimpact/model/partitioned_tridiagonal.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "../support/line_parts.hpp"
#include "../support/line_runs.hpp"
#include "barimpact/case/line_builder.hpp"
#include "barimpact/model/line.hpp"
#include "barimpact/model/tridiagonal.hpp"

namespace barimpact {
namespace {

constexpr double eps = std::numeric_limits<double>::epsilon();
const std::size_t partition_counts[] = {1, 2, 3, 4, 7, 8, 16, 64};

// Random diagonally dominant: d_j = |off_{j-1}| + |off_j| + a positive margin
// spanning six decades, off of either sign.
Tridiagonal dominant(std::size_t n, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0), decades(-3.0, 3.0);
  Tridiagonal a{std::vector<double>(n), std::vector<double>(n - 1)};
  for (double& o : a.off) o = u(rng) * std::pow(10.0, decades(rng));
  for (std::size_t j = 0; j < n; ++j)
    a.diag[j] =
        (j > 0 ? std::abs(a.off[j - 1]) : 0.0) + (j + 1 < n ? std::abs(a.off[j]) : 0.0) + std::pow(10.0, decades(rng));
  return a;
}

// M + beta dt^2 K of a line of bar elements, as the implicit schemes factor
// it (consistent mass, free ends): element masses m_e and stiffnesses k_e
// each spanning four decades, dt^2 k_e / m_e up to 10^4, so that A is far
// from diagonally dominant (its off-diagonals exceed half the diagonal).
Tridiagonal mass_plus_stiffness(std::size_t n, std::mt19937& rng) {
  std::uniform_real_distribution<double> decades(-2.0, 2.0);
  Tridiagonal a{std::vector<double>(n, 0.0), std::vector<double>(n - 1, 0.0)};
  const double dt2 = 25.0;
  for (std::size_t e = 0; e + 1 < n; ++e) {
    const double m = std::pow(10.0, decades(rng)), k = std::pow(10.0, decades(rng));
    a.diag[e] += m / 3.0 + dt2 * k;
    a.diag[e + 1] += m / 3.0 + dt2 * k;
    a.off[e] += m / 6.0 - dt2 * k;
  }
  if (n == 1) a.diag[0] = 1.0;
  return a;
}

// ||A||_inf ||A^{-1}||_inf, A^{-1}'s columns by the sequential solve: the
// factor by which two backward-stable solves' results may differ, relative
// to their size, per unit of rounding.
double condition(const Tridiagonal& a, bool fix_last) {
  const std::size_t n = a.size(), rows = fix_last ? n - 1 : n;
  if (rows == 0) return 1.0;
  const FactoredTridiagonal f(a, fix_last);
  std::vector<double> inverse_row_sums(n, 0.0), e(n);
  for (std::size_t c = 0; c < rows; ++c) {
    std::fill(e.begin(), e.end(), 0.0);
    e[c] = 1.0;
    f.solve(e);
    for (std::size_t i = 0; i < n; ++i) inverse_row_sums[i] += std::abs(e[i]);
  }
  double norm = 0.0;
  for (std::size_t i = 0; i < rows; ++i)
    norm = std::max(
        norm, std::abs(a.diag[i]) + (i > 0 ? std::abs(a.off[i - 1]) : 0.0) + (i + 1 < rows ? std::abs(a.off[i]) : 0.0));
  return norm * *std::max_element(inverse_row_sums.begin(), inverse_row_sums.end());
}

double max_abs(const std::vector<double>& v) {
  double m = 0.0;
  for (double x : v) m = std::max(m, std::abs(x));
  return m;
}

std::vector<double> random_rhs(std::size_t n, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<double> b(n);
  for (double& x : b) x = u(rng);
  return b;
}

std::vector<std::size_t> sizes_for(std::size_t p) {
  std::vector<std::size_t> s = {1, 2, 3, 5, p, p + 1, 2 * p - 1, 2 * p, 2 * p + 1, 5 * p + 3, 257, 1000};
  if (p > 1) s.push_back(p - 1);
  return s;
}

// Every P, size and end: the partitioned solve against the sequential one.
// Tolerance: both are LDL^T solves of an SPD tridiagonal, backward stable
// with a backward error of a few eps per row (Higham, Accuracy and
// Stability, 2nd ed., sec. 9.5), so each is within about kappa eps of the
// exact x relative to ||x||_inf, kappa = ||A|| ||A^{-1}|| in the inf-norm;
// 4 kappa eps covers both and the reduced system's own elimination (the
// largest difference measured is 0.3 kappa eps, kappa up to 10^6).
template <class Make>
void against_sequential(Make make, std::uint32_t seed) {
  std::mt19937 rng(seed);
  for (bool fix_last : {false, true})
    for (std::size_t p : partition_counts)
      for (std::size_t n : sizes_for(p)) {
        const Tridiagonal a = make(n, rng);
        const std::vector<double> b = random_rhs(n, rng);
        std::vector<double> expected = b, x = b;
        FactoredTridiagonal(a, fix_last).solve(expected);
        PartitionedTridiagonal solver(a, fix_last, p);
        const std::size_t rows = fix_last ? n - 1 : n;
        // The chunks asked for, unless A has too few rows to give each its own.
        ASSERT_EQ(solver.partitions(), std::max<std::size_t>(1, std::min(p, (rows + 1) / 2)));
        solver.solve(x);
        const double tolerance = 4.0 * condition(a, fix_last) * eps * max_abs(expected);
        const std::string where =
            "P " + std::to_string(p) + ", n " + std::to_string(n) + ", fix_last " + std::to_string(fix_last);
        for (std::size_t i = 0; i < n; ++i) ASSERT_NEAR(x[i], expected[i], tolerance) << where << ", row " << i;
        if (fix_last) {
          EXPECT_EQ(x[n - 1], 0.0) << where;
        }
      }
}

TEST(PartitionedTridiagonal, MatchesTheSequentialSolveOnDiagonallyDominantSystems) {
  against_sequential(dominant, 1);
}

TEST(PartitionedTridiagonal, MatchesTheSequentialSolveOnMassPlusStiffness) {
  against_sequential(mass_plus_stiffness, 2);
}

// The implicit schemes' own matrices on a line of welded bars of different
// materials and meshes with a point mass: newmark's M + gamma dt C + beta
// dt^2 K, moreau-jean's M + theta dt C + theta^2 dt^2 K, paper's A =
// M / dt^2 + alpha S + D / (2 dt) (lambda = 0.05, alpha = 1/4),
// mass-redistribution's 2 M / dt^2 + K / 2 and paoli-schatzman's M, at a
// step near and one far beyond the line's stable explicit step. Tolerance
// as above.
TEST(PartitionedTridiagonal, MatchesTheSequentialSolveOnTheSchemesMatrices) {
  BodyData soft = testing::bar("soft", 0.5, 70), stiff = testing::bar("stiff", 0.3, 130);
  soft.viscosity = 0.02;
  stiff.modulus = 50.0;
  stiff.density = 0.2;
  Case c = testing::line_case(
      {soft, stiff, testing::mass("ram", 3.0, 0.0), testing::bar("tail", 1.0, 41)},
      {testing::joint("soft", "stiff", JointLaw::welded), testing::joint("stiff", "ram", JointLaw::welded),
       testing::joint("ram", "tail", JointLaw::welded)},
      1e-3, 1.0);
  const Line line = build_line(c);
  const Tridiagonal m = line.mass(true), k = line.stiffness(), visc = line.viscosity();
  std::mt19937 rng(6);
  for (double dt : {1e-3, 1e-1}) {
    const double lambda = 0.05, alpha = 0.25, theta = 0.6;
    const Tridiagonal s = Tridiagonal::combine(1.0, Tridiagonal::combine(lambda * lambda, m, 1.0, k), lambda, visc);
    const Tridiagonal d = Tridiagonal::combine(2.0 * lambda, m, 1.0, visc);
    const std::vector<Tridiagonal> matrices = {
        Tridiagonal::combine(1.0, Tridiagonal::combine(1.0, m, 0.5 * dt, visc), 0.25 * dt * dt, k),
        Tridiagonal::combine(1.0, Tridiagonal::combine(1.0, m, theta * dt, visc), theta * theta * dt * dt, k),
        Tridiagonal::combine(1.0, Tridiagonal::combine(1.0 / (dt * dt), m, alpha, s), 0.5 / dt, d),
        Tridiagonal::combine(2.0 / (dt * dt), m, 0.5, k), m};
    for (const Tridiagonal& a : matrices)
      for (bool fix_last : {false, true})
        for (std::size_t p : partition_counts) {
          const std::vector<double> b = random_rhs(a.size(), rng);
          std::vector<double> expected = b, x = b;
          FactoredTridiagonal(a, fix_last).solve(expected);
          PartitionedTridiagonal solver(a, fix_last, p);
          ASSERT_EQ(solver.partitions(), p);
          solver.solve(x);
          const double tolerance = 4.0 * condition(a, fix_last) * eps * max_abs(expected);
          for (std::size_t i = 0; i < a.size(); ++i)
            ASSERT_NEAR(x[i], expected[i], tolerance) << "dt " << dt << ", P " << p << ", row " << i;
        }
  }
}

// One chunk is the sequential solve, operation for operation: the same bits.
TEST(PartitionedTridiagonal, OneChunkIsTheSequentialSolveBitForBit) {
  std::mt19937 rng(3);
  for (bool fix_last : {false, true})
    for (std::size_t n : {1, 2, 3, 100, 1001}) {
      const Tridiagonal a = mass_plus_stiffness(n, rng);
      std::vector<double> expected = random_rhs(n, rng), x = expected;
      FactoredTridiagonal(a, fix_last).solve(expected);
      PartitionedTridiagonal solver(a, fix_last, 1);
      solver.solve(x);
      for (std::size_t i = 0; i < n; ++i) ASSERT_EQ(x[i], expected[i]) << "n " << n << ", row " << i;
    }
}

// The two phases with a force at row 0 found between them (a contact
// decided from x_0): x_0 before it, x_0 after it, the whole x after the
// second phase, against the sequential solve of b and of b + f e_0, and
// (A^{-1})_00 against response_to_end_force. Tolerance as above.
TEST(PartitionedTridiagonal, EndForceBetweenThePhasesEqualsSolvingWithIt) {
  std::mt19937 rng(4);
  for (bool fix_last : {false, true})
    for (std::size_t p : partition_counts)
      for (std::size_t n : sizes_for(p)) {
        const Tridiagonal a = mass_plus_stiffness(n, rng);
        const FactoredTridiagonal sequential(a, fix_last);
        const double f = 3.0;
        std::vector<double> b = random_rhs(n, rng), free = b, x = b;
        sequential.solve(free);
        b[0] += f;
        std::vector<double> forced = b;
        sequential.solve(forced);
        PartitionedTridiagonal solver(a, fix_last, p);
        const double scale = std::max(max_abs(free), max_abs(forced));
        const double tolerance = 4.0 * condition(a, fix_last) * eps * scale;
        const std::string where =
            "P " + std::to_string(p) + ", n " + std::to_string(n) + ", fix_last " + std::to_string(fix_last);
        EXPECT_NEAR(solver.end_response(), sequential.response_to_end_force()[0],
                    4.0 * condition(a, fix_last) * eps * std::abs(sequential.response_to_end_force()[0]))
            << where;
        EXPECT_NEAR(solver.eliminate(x), free[0], tolerance) << where;
        EXPECT_NEAR(solver.add_end_force(x, f), forced[0], tolerance) << where;
        solver.substitute(x);
        for (std::size_t i = 0; i < n; ++i) ASSERT_NEAR(x[i], forced[i], tolerance) << where << ", row " << i;
      }
}

// Factored once, solved many times: the workspace carries nothing over
// from one right-hand side to the next.
TEST(PartitionedTridiagonal, RepeatedSolvesDoNotInterfere) {
  std::mt19937 rng(5);
  const std::size_t n = 500;
  const Tridiagonal a = mass_plus_stiffness(n, rng);
  const FactoredTridiagonal sequential(a, false);
  PartitionedTridiagonal solver(a, false, 8);
  const double tolerance_factor = 4.0 * condition(a, false) * eps;  // as above
  for (int repeat = 0; repeat < 3; ++repeat) {
    std::vector<double> expected = random_rhs(n, rng), x = expected;
    sequential.solve(expected);
    solver.solve(x);
    for (std::size_t i = 0; i < n; ++i) ASSERT_NEAR(x[i], expected[i], tolerance_factor * max_abs(expected));
  }
}

}  // namespace
}  // namespace barimpact
