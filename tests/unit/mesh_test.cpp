#include "barimpact/mesh.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "barimpact/expression.hpp"

namespace barimpact {
namespace {

TEST(Mesh, MassSumsToTheBarsMassAndStiffnessAnnihilatesConstants) {
  const Mesh mesh(2.0, 5);
  const std::vector<double> ones(mesh.nodes(), 1.0);
  EXPECT_NEAR(mesh.mass(3.0).quadratic_form(ones), 6.0, 1e-14);
  EXPECT_NEAR(mesh.stiffness(7.0).quadratic_form(ones), 0.0, 1e-13);
  // x^T K x = a int (x')^2 = a L for the interpolant of x.
  std::vector<double> x(mesh.nodes());
  for (std::size_t j = 0; j < x.size(); ++j) x[j] = mesh.x(j);
  EXPECT_NEAR(mesh.stiffness(7.0).quadratic_form(x), 14.0, 1e-12);
}

TEST(Mesh, LoadVectorIsExactForCubics) {
  // f = 1 + 2x - 3x^2 + 4x^3 on (0, 2): sum_i F_i = int f and sum_i x_i F_i = int x f,
  // because the hats sum to 1 and sum_i x_i phi_i = x.
  const Mesh mesh(2.0, 3);
  const Expression f("1 + 2*x - 3*x^2 + 4*x^3");
  std::vector<double> F(mesh.nodes());
  mesh.load(f, 0.0, F);
  double s0 = 0.0, s1 = 0.0;
  for (std::size_t j = 0; j < F.size(); ++j) {
    s0 += F[j];
    s1 += mesh.x(j) * F[j];
  }
  EXPECT_NEAR(s0, 2.0 + 4.0 - 8.0 + 16.0, 1e-13);                 // int_0^2 f
  EXPECT_NEAR(s1, 2.0 + 16.0 / 3.0 - 12.0 + 128.0 / 5.0, 1e-13);  // int_0^2 x f
}

TEST(Mesh, LoadVectorOfXOnTheHats) {
  // int x phi_0 = h^2/6, int x phi_j = x_j h inside, int x phi_M = h (L/2 - h/6).
  const Mesh mesh(3.0, 4);
  const double h = 0.75;
  std::vector<double> F(mesh.nodes());
  mesh.load(Expression("x"), 0.0, F);
  EXPECT_NEAR(F[0], h * h / 6.0, 1e-15);
  for (std::size_t j = 1; j < 4; ++j) EXPECT_NEAR(F[j], mesh.x(j) * h, 1e-14);
  EXPECT_NEAR(F[4], h * (1.5 - h / 6.0), 1e-14);
}

TEST(Tridiagonal, MultiplyMatchesTheQuadraticForm) {
  const Mesh mesh(1.0, 4);
  const Tridiagonal M = mesh.mass(2.0);
  const std::vector<double> x{0.1, -0.4, 0.7, 0.2, -1.0};
  std::vector<double> y(5);
  M.multiply(x, y);
  double xy = 0.0;
  for (std::size_t j = 0; j < 5; ++j) xy += x[j] * y[j];
  EXPECT_NEAR(xy, M.quadratic_form(x), 1e-15);
}

}  // namespace
}  // namespace barimpact
