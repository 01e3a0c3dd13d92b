// The paper's obstacle law at x = 0 (obstacle.hpp): penetration, reaction
// and stored energy by the formulas of (2.8) and its viscoelastic variant.
#include "barimpact/model/obstacle.hpp"

#include <gtest/gtest.h>

namespace barimpact {
namespace {

ObstacleLaw law(ObstacleKind kind, double k, double gap, double l = 0.0) {
  ObstacleData d;
  d.kind = kind;
  d.stiffness = k;
  d.gap = gap;
  d.viscosity = l;
  return ObstacleLaw(d);
}

// The face at u = -g = -0.01: U = -0.03 penetrates by d = 0.02, so k = 100
// pushes with R = k d = 2 and stores k d^2 / 2 = 0.02; U above the face
// gives nothing. Tolerances: round-off of U + g.
TEST(ObstacleLaw, ElasticReactionIsKTimesThePenetration) {
  const ObstacleLaw o = law(ObstacleKind::elastic, 100.0, 0.01);
  EXPECT_NEAR(o.penetration(-0.03), 0.02, 1e-16);
  EXPECT_NEAR(o.reaction(-0.03, -5.0), 2.0, 1e-14);  // the velocity plays no part
  EXPECT_NEAR(o.energy(-0.03), 0.02, 1e-16);
  EXPECT_EQ(o.penetration(-0.005), 0.0);
  EXPECT_EQ(o.reaction(-0.005, -1.0), 0.0);
  EXPECT_EQ(o.energy(-0.005), 0.0);
  EXPECT_EQ(o.stiffness(), 100.0);
  EXPECT_EQ(o.viscosity(), 0.0);
  EXPECT_EQ(o.gap(), 0.01);
  EXPECT_EQ(to_string(o.kind()), "elastic");
}

// R = max(0, k d + l dd/dt), dd/dt = -V: k = 100, l = 10, d = 0.02 gives
// 2 + 10 x 0.3 = 5 moving in at V = -0.3, and nothing (not 2 - 3) moving
// out at V = 0.3; none at all while not penetrating.
TEST(ObstacleLaw, ViscoelasticAddsItsDashpotAndNeverPulls) {
  const ObstacleLaw o = law(ObstacleKind::viscoelastic, 100.0, 0.0, 10.0);
  EXPECT_NEAR(o.reaction(-0.02, -0.3), 5.0, 1e-14);
  EXPECT_EQ(o.reaction(-0.02, 0.3), 0.0);
  EXPECT_EQ(o.reaction(0.001, -10.0), 0.0);
  EXPECT_NEAR(o.energy(-0.02), 0.02, 1e-16);  // the spring's alone
  EXPECT_EQ(o.viscosity(), 10.0);
  EXPECT_EQ(to_string(o.kind()), "viscoelastic");
}

// No obstacle: never a penetration, whatever U.
TEST(ObstacleLaw, NoneNeverTouches) {
  const ObstacleLaw o = law(ObstacleKind::none, 100.0, 0.0);
  EXPECT_EQ(o.penetration(-1.0), 0.0);
  EXPECT_EQ(o.reaction(-1.0, -1.0), 0.0);
  EXPECT_EQ(o.energy(-1.0), 0.0);
  EXPECT_EQ(to_string(ObstacleKind::none), "none");
  EXPECT_EQ(to_string(ObstacleKind::rigid), "rigid");
}

}  // namespace
}  // namespace barimpact
