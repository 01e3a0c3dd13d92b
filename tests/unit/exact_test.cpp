#include "barimpact/exact/exact.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace barimpact::exact {
namespace {

TEST(Example1, EndStaysOnTheObstacleThenLeavesWithTheReversedVelocity) {
  const Example1 e(2.0, 4.0, 1.0, -0.5);  // c = 2, contact until 2L/c = 2
  EXPECT_DOUBLE_EQ(e.wave_speed(), 2.0);
  EXPECT_DOUBLE_EQ(e.contact_end(), 2.0);
  for (double t : {0.1, 0.7, 1.3, 1.99}) {
    EXPECT_DOUBLE_EQ(e.U(t), 0.0);
    EXPECT_DOUBLE_EQ(e.R(t), 1.0);  // rho c |v0|
  }
  EXPECT_DOUBLE_EQ(e.U(3.0), 0.5);
  EXPECT_DOUBLE_EQ(e.V(3.0), 0.5);
  EXPECT_DOUBLE_EQ(e.R(3.0), 0.0);
}

TEST(Example1, StartsUndeformedAtTheInitialVelocity) {
  const Example1 e(1.0, 1.0, 1.0, -1.0);
  for (double x : {0.1, 0.5, 0.9}) {
    EXPECT_DOUBLE_EQ(e.u(x, 0.0), 0.0);
    EXPECT_DOUBLE_EQ(e.v(x, 0.0), -1.0);
    EXPECT_DOUBLE_EQ(e.strain(x, 0.0), 0.0);
  }
  // Before the wave from x = 0 arrives the bar moves rigidly.
  EXPECT_DOUBLE_EQ(e.u(0.8, 0.3), -0.3);
  EXPECT_DOUBLE_EQ(e.v(0.8, 0.3), -1.0);
  // Behind it, at rest and compressed with strain -|v0|/c.
  EXPECT_DOUBLE_EQ(e.v(0.2, 0.3), 0.0);
  EXPECT_DOUBLE_EQ(e.strain(0.2, 0.3), -1.0);
  EXPECT_DOUBLE_EQ(e.u(0.2, 0.3), -0.2);
}

TEST(Example1, IsContinuousAtLiftOffAndConservesEnergy) {
  const Example1 e(1.0, 9.0, 4.0, -2.0);  // c = 1.5
  const double T = e.contact_end();
  for (double x : {0.0, 0.3, 1.0}) EXPECT_NEAR(e.u(x, T - 1e-12), e.u(x, T + 1e-12), 1e-10);
  // Kinetic + strain energy by the midpoint rule on 20000 cells: the
  // integrand is piecewise constant, so only the cells cut by the fronts err.
  for (double t : {0.2, 0.5, 1.0, 1.2}) {
    const int cells = 20000;
    double E = 0.0;
    for (int i = 0; i < cells; ++i) {
      const double x = (i + 0.5) / cells;
      E += (0.5 * 4.0 * std::pow(e.v(x, t), 2) + 0.5 * 9.0 * std::pow(e.strain(x, t), 2)) / cells;
    }
    EXPECT_NEAR(E, e.energy(), 1e-3) << t;
  }
  EXPECT_DOUBLE_EQ(e.energy(), 8.0);
}

TEST(Example1, WithoutApproachVelocityThereIsNoContact) {
  const Example1 e(1.0, 1.0, 1.0, 0.5);
  EXPECT_DOUBLE_EQ(e.U(2.0), 1.0);
  EXPECT_DOUBLE_EQ(e.R(0.5), 0.0);
}

}  // namespace
}  // namespace barimpact::exact
