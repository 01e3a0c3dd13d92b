#include "barimpact/model/tridiagonal.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "../support/dense.hpp"
#include "barimpact/model/expression.hpp"
#include "barimpact/model/line.hpp"

namespace barimpact {
namespace {

// A uniform bar of M elements on (0, L) as a line: density rho, modulus E, area 1.
Line uniform_bar(double length, int elements, double density = 1.0, double modulus = 1.0) {
  Line line;
  const double h = length / elements;
  for (int j = 0; j <= elements; ++j) {
    line.x.push_back(j * h);
    line.point_mass.push_back(0.0);
    if (j > 0) line.bonds.push_back({BondKind::element, h, modulus / h, 0.0, density * h, 1.0, 0, modulus, 0.0});
  }
  line.bodies.push_back({"bar", false, 0, static_cast<std::size_t>(elements), "0", "0"});
  return line;
}

TEST(LineMatrices, MassSumsToTheBarsMassAndStiffnessAnnihilatesConstants) {
  const Line line = uniform_bar(2.0, 5, 3.0, 7.0);
  const std::vector<double> ones(line.nodes(), 1.0);
  EXPECT_NEAR(line.mass(true).quadratic_form(ones), 6.0, 1e-14);
  EXPECT_NEAR(line.stiffness().quadratic_form(ones), 0.0, 1e-13);
  // x^T K x = E int (x')^2 = E L for the interpolant of x.
  EXPECT_NEAR(line.stiffness().quadratic_form(line.x), 14.0, 1e-12);
}

TEST(LineMatrices, LoadVectorIsExactForCubics) {
  // f = 1 + 2x - 3x^2 + 4x^3 on (0, 2): sum_i F_i = int f and sum_i x_i F_i = int x f,
  // because the hats sum to 1 and sum_i x_i phi_i = x.
  const Line line = uniform_bar(2.0, 3);
  const Expression f("1 + 2*x - 3*x^2 + 4*x^3");
  std::vector<double> F;
  line.load(f, 0.0, F);
  double s0 = 0.0, s1 = 0.0;
  for (std::size_t j = 0; j < F.size(); ++j) {
    s0 += F[j];
    s1 += line.x[j] * F[j];
  }
  EXPECT_NEAR(s0, 2.0 + 4.0 - 8.0 + 16.0, 1e-13);                 // int_0^2 f
  EXPECT_NEAR(s1, 2.0 + 16.0 / 3.0 - 12.0 + 128.0 / 5.0, 1e-13);  // int_0^2 x f
}

TEST(LineMatrices, LoadVectorOfXOnTheHats) {
  // int x phi_0 = h^2/6, int x phi_j = x_j h inside, int x phi_M = h (L/2 - h/6).
  const Line line = uniform_bar(3.0, 4);
  const double h = 0.75;
  std::vector<double> F;
  line.load(Expression("x"), 0.0, F);
  EXPECT_NEAR(F[0], h * h / 6.0, 1e-15);
  for (std::size_t j = 1; j < 4; ++j) EXPECT_NEAR(F[j], line.x[j] * h, 1e-14);
  EXPECT_NEAR(F[4], h * (1.5 - h / 6.0), 1e-14);
}

TEST(Tridiagonal, MultiplyMatchesTheQuadraticForm) {
  const Tridiagonal M = uniform_bar(1.0, 4, 2.0).mass(true);
  const std::vector<double> x{0.1, -0.4, 0.7, 0.2, -1.0};
  std::vector<double> y(5);
  M.multiply(x, y);
  double xy = 0.0;
  for (std::size_t j = 0; j < 5; ++j) xy += x[j] * y[j];
  EXPECT_NEAR(xy, M.quadratic_form(x), 1e-15);
}

// The tridiagonal system written dense, and solved by elimination (the reference).
std::vector<double> dense_reference(const Tridiagonal& t, std::vector<double> r, bool fix_last) {
  const std::size_t n = t.size();
  testing::DenseMatrix m(n, std::vector<double>(n, 0.0));
  for (std::size_t i = 0; i < n; ++i) {
    m[i][i] = t.diag[i];
    if (i + 1 < n) m[i][i + 1] = m[i + 1][i] = t.off[i];
  }
  if (fix_last) {
    for (std::size_t j = 0; j < n; ++j) m[n - 1][j] = m[j][n - 1] = 0.0;
    m[n - 1][n - 1] = 1.0;
    r[n - 1] = 0.0;
  }
  return testing::dense_solve(m, r);
}

TEST(FactoredTridiagonal, SolvesLikeDenseEliminationFreeAndClamped) {
  for (std::size_t n : {2, 3, 4, 7, 8}) {
    for (bool fix_last : {false, true}) {
      SCOPED_TRACE(::testing::Message() << "n = " << n << (fix_last ? " clamped" : " free"));
      // A mass-plus-stiffness-like SPD matrix with every entry different.
      Tridiagonal t{std::vector<double>(n), std::vector<double>(n - 1)};
      std::vector<double> r(n);
      for (std::size_t i = 0; i < n; ++i) {
        t.diag[i] = 3.0 + 0.1 * static_cast<double>(i);
        if (i + 1 < n) t.off[i] = -1.0 + 0.05 * static_cast<double>(i);
        r[i] = std::sin(1.0 + static_cast<double>(i));
      }
      const FactoredTridiagonal f(t, fix_last);
      const auto expected = dense_reference(t, r, fix_last);
      std::vector<double> x = r;
      f.solve(x);
      // Tolerance: two eliminations of a well-conditioned (cond < 10) system
      // differ by a few ulps.
      for (std::size_t i = 0; i < n; ++i) EXPECT_NEAR(x[i], expected[i], 1e-14) << i;
      if (fix_last) {
        EXPECT_EQ(x[n - 1], 0.0);
      }
      // The answer to a unit force at node 0, whose first entry the kernels
      // read as inverse_pivots()[0].
      const auto w = f.response_to_end_force();
      std::vector<double> e0(n, 0.0);
      e0[0] = 1.0;
      const auto w_expected = dense_reference(t, e0, fix_last);
      for (std::size_t i = 0; i < n; ++i) EXPECT_NEAR(w[i], w_expected[i], 1e-14) << i;
      EXPECT_EQ(w[0], f.inverse_pivots()[0]);
    }
  }
}

// The two-ended factorisation against dense elimination: every size from
// one row (a line of one mass) up, odd and even (the lower half's extra
// row), every entry different, some couplings zero (a held row's, or an
// open bond's); the right-hand side formed row by row through solve(row, x).
TEST(TwistedTridiagonal, SolvesLikeDenseElimination) {
  for (std::size_t n : {1, 2, 3, 4, 5, 8, 11}) {
    SCOPED_TRACE(::testing::Message() << "n = " << n);
    Tridiagonal t{std::vector<double>(n), std::vector<double>(n - 1)};
    std::vector<double> r(n);
    for (std::size_t i = 0; i < n; ++i) {
      t.diag[i] = 3.0 + 0.1 * static_cast<double>(i);
      if (i + 1 < n) t.off[i] = i % 3 == 2 ? 0.0 : -1.0 + 0.05 * static_cast<double>(i);
      r[i] = std::sin(1.0 + static_cast<double>(i));
    }
    const TwistedTridiagonal f(t);
    EXPECT_EQ(f.twist(), (n - 1) / 2);
    const auto expected = dense_reference(t, r, false);
    std::vector<double> x(n, 0.0);
    int asked = 0;
    f.solve(
        [&](std::size_t j) {
          ++asked;
          return r[j];
        },
        x.data());
    EXPECT_EQ(asked, static_cast<int>(n));  // each row once
    for (std::size_t i = 0; i < n; ++i) EXPECT_NEAR(x[i], expected[i], 1e-14) << i;
    std::vector<double> y = r;  // in place
    f.solve(y.data());
    for (std::size_t i = 0; i < n; ++i) EXPECT_EQ(y[i], x[i]) << i;
  }
}

}  // namespace
}  // namespace barimpact
