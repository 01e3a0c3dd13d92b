// What the line schemes share (line_scheme.hpp): the explicit stable step
// of a line, line_stable_step, against Gershgorin's bound worked by hand.
#include "barimpact/schemes/line_scheme.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "../support/line_parts.hpp"
#include "../support/line_runs.hpp"
#include "barimpact/case/line_builder.hpp"

namespace barimpact {
namespace {

using testing::bar;
using testing::line_case;
using testing::mass;

// A uniform free bar of 10 elements, E = 4, rho = A = 1 (c = 2, h = 0.1):
// bonds k = E A / h = 40, interior nodes of mass rho A h = 0.1 with 4 k on
// their row, the end nodes half of both: omega^2 = 4 c^2 / h^2 = 1600 at
// every node, dt = 2 / omega = h / c = 0.05, and 0.05 / sqrt(3) with the
// consistent mass (3 times stiffer at the top of the spectrum). Tolerance
// 1e-14 relative: the rounding of h = L / M and of the square root.
TEST(LineStableStep, AUniformBarsIsItsElementTransitTime) {
  Case c = line_case({bar("b", 1.0, 10)}, {}, 0.01, 1.0);
  c.bodies[0].modulus = 4.0;
  const Line line = build_line(c);
  EXPECT_NEAR(line_stable_step(line, false), 0.05, 1e-14);
  EXPECT_NEAR(line_stable_step(line, true), 0.05 / std::sqrt(3.0), 1e-14);
}

// The same bar on an elastic near end of k = 10: node 0's row holds 2 x 40
// + 10 over its mass 0.05, omega^2 = 1800 above the interior's 1600, dt =
// 2 / sqrt(1800). A point mass of 1 welded on top leaves the step to the
// rest of the bar: its node's omega^2 = 80 / 1.05. A clamped near end does
// not count its held node: the step stays h / c.
TEST(LineStableStep, ALinkStiffensItsNodeAndAHeldNodeDoesNotCount) {
  Case c = line_case({bar("b", 1.0, 10)}, {}, 0.01, 1.0);
  c.bodies[0].modulus = 4.0;
  c.near_end.law = JointLaw::elastic;
  c.near_end.stiffness = 10.0;
  EXPECT_NEAR(line_stable_step(build_line(c), false), 2.0 / std::sqrt(1800.0), 1e-14);
  c.bodies.push_back(mass("m", 1.0, 0.0));
  EXPECT_NEAR(line_stable_step(build_line(c), false), 2.0 / std::sqrt(1800.0), 1e-14);
  c.near_end.law = JointLaw::clamped;
  EXPECT_NEAR(line_stable_step(build_line(c), false), 0.05, 1e-14);
}

// A dashpot only (no stiffness): the central-difference recurrence's
// condition omega^2 dt^2 + 2 eta dt <= 4 becomes eta dt <= 2, with eta =
// 2 l / m on each of two masses m = 1 joined by l = 4: dt = 0.25. Nothing
// stiff nor damped (a rigid joint does not count): no limit at all.
TEST(LineStableStep, ADashpotAloneLimitsTheStepToTwoOverItsRate) {
  JointData dashpot = testing::law_joint("m1", "m2", JointLaw::viscoelastic, 0.0, 4.0);
  const Case c = line_case({mass("m1", 1.0, 0.0), mass("m2", 1.0, 0.0)}, {dashpot}, 0.01, 1.0);
  EXPECT_NEAR(line_stable_step(build_line(c), false), 0.25, 1e-15);
  const Case idle =
      line_case({mass("m1", 1.0, 0.0), mass("m2", 1.0, 0.0)}, {testing::joint("m1", "m2", JointLaw::rigid)}, 0.01, 1.0);
  EXPECT_TRUE(std::isinf(line_stable_step(build_line(idle), false)));
}

}  // namespace
}  // namespace barimpact
