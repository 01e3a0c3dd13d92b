// From a case's bodies, joints and ends to the line the schemes step
// (line_builder.hpp): bodies become node ranges (a mass one node), a welded
// joint shares its node, a spring joint is a bond, a unilateral joint or an
// end's law a link; Smith's shaft spread over the embedded nodes; the
// restitution a rigid link takes.
#include "barimpact/case/line_builder.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <numeric>
#include <string>

#include "../support/line_parts.hpp"
#include "../support/pile.hpp"
#include "../support/run_case.hpp"

namespace barimpact {
namespace {

using testing::bar;
using testing::case_from;
using testing::joint;
using testing::law_joint;
using testing::mass;
using testing::pile_toml;

// Bar a (length 1, 4 elements) welded to bar b (length 2, 2 elements, E =
// 9, A = 0.5, rho = 2), a spring (k = 50) to a mass p of 3, a rigid joint
// with a gap of 0.01 to a mass m of 1.5, an elastic near end (k = 100). By
// the header: a's nodes 0..4, b's 4..6 (the welded joint shares node 4),
// p's 7 and m's 8; bonds a's elements (k = E A / h = 4, m = rho A h =
// 0.25), b's (k = 4.5, m = 1), the spring, and an open bond under the
// rigid link; links the near end's then the joint's. Tolerances: round-off.
TEST(BuildLine, BodiesAreNodeRangesAndJointsBondsOrLinks) {
  Case c;
  BodyData b = bar("b", 2.0, 2);
  b.modulus = 9.0;
  b.area = 0.5;
  b.density = 2.0;
  JointData gap = joint("p", "m", JointLaw::rigid, 0.01);
  c.bodies = {bar("a", 1.0, 4), b, mass("p", 3.0, 0.0), mass("m", 1.5, 0.0)};
  c.joints = {law_joint("b", "p", JointLaw::spring, 50.0), gap};
  c.near_end.law = JointLaw::elastic;
  c.near_end.stiffness = 100.0;
  const Line line = build_line(c);
  ASSERT_EQ(line.nodes(), 9u);
  ASSERT_EQ(line.bonds.size(), 8u);
  ASSERT_EQ(line.bodies.size(), 4u);
  const std::size_t first[] = {0, 4, 7, 8}, last[] = {4, 6, 7, 8};
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_EQ(line.bodies[i].name, c.bodies[i].name);
    EXPECT_EQ(line.bodies[i].first, first[i]) << i;
    EXPECT_EQ(line.bodies[i].last, last[i]) << i;
    EXPECT_EQ(line.bodies[i].is_mass, i >= 2) << i;
  }
  for (std::size_t j = 0; j < 4; ++j) {
    EXPECT_EQ(line.bonds[j].kind, BondKind::element);
    EXPECT_NEAR(line.bonds[j].stiffness, 4.0, 1e-15);
    EXPECT_NEAR(line.bonds[j].mass, 0.25, 1e-16);
    EXPECT_NEAR(line.x[j + 1] - line.x[j], 0.25, 1e-15);
  }
  for (std::size_t j = 4; j < 6; ++j) {
    EXPECT_EQ(line.bonds[j].kind, BondKind::element);
    EXPECT_NEAR(line.bonds[j].stiffness, 4.5, 1e-15);
    EXPECT_NEAR(line.bonds[j].mass, 1.0, 1e-15);
  }
  EXPECT_NEAR(line.x[6], 3.0, 1e-15);
  EXPECT_EQ(line.bonds[6].kind, BondKind::spring);
  EXPECT_EQ(line.bonds[6].stiffness, 50.0);
  EXPECT_EQ(line.bonds[6].mass, 0.0);
  EXPECT_EQ(line.bonds[7].kind, BondKind::open);
  // Each body's elements are one bond kept once; the spring and the open bond each.
  EXPECT_EQ(line.bonds.kept(), 4u);
  std::size_t walked = 0;
  for (const Bond& bond : line.bonds) EXPECT_EQ(&bond, &line.bonds[walked++]);
  EXPECT_EQ(walked, 8u);
  EXPECT_EQ(&line.bonds.back(), &line.bonds[7]);
  EXPECT_EQ(line.point_mass[7], 3.0);
  EXPECT_EQ(line.point_mass[8], 1.5);
  // The lumped mass is every body's: 1 (a) + 2 (b) + 3 + 1.5.
  const auto m = line.lumped_mass();
  EXPECT_NEAR(std::accumulate(m.begin(), m.end(), 0.0), 7.5, 1e-14);
  ASSERT_EQ(line.links.size(), 2u);
  EXPECT_EQ(line.links[0].name, "near_end");
  EXPECT_TRUE(line.links[0].is_end);
  EXPECT_EQ(line.links[0].a, Link::ground);
  EXPECT_EQ(line.links[0].b, 0u);
  EXPECT_EQ(line.links[0].law.kind, LawKind::elastic);
  EXPECT_EQ(line.links[0].law.stiffness, 100.0);
  EXPECT_EQ(line.links[1].name, "joint.p-m");
  EXPECT_EQ(line.links[1].a, 7u);
  EXPECT_EQ(line.links[1].b, 8u);
  EXPECT_EQ(line.links[1].gap, 0.01);
  EXPECT_TRUE(line.links[1].law.rigid());
  EXPECT_EQ(line.far.node, 8u);
  EXPECT_EQ(line.far.kind, EndKind::free);
}

// A rigid link's restitution is its own when the case gives one, else time.restitution.
TEST(BuildLine, ARigidLinkTakesItsOwnRestitutionElseTheSchemes) {
  const std::string text = R"toml([[body]]
name = "a"
[[body]]
name = "m"
kind = "mass"
mass = 1.0
[[joint]]
between = ["a", "m"]
law = "rigid"
{}
[time]
scheme = "moreau-jean"
restitution = 0.8
)toml";
  const Case own = case_from(fmt::format(fmt::runtime(text), "restitution = 0.3"));
  EXPECT_EQ(rigid_restitution(own, own.joints[0].law), 0.3);
  const Case schemes = case_from(fmt::format(fmt::runtime(text), ""));
  EXPECT_EQ(rigid_restitution(schemes, schemes.joints[0].law), 0.8);
}

TEST(SmithCase, ShaftIsSpreadOverTheEmbeddedNodesByTheElementLengths) {
  for (const char* dist : {"uniform", "triangular"}) {
    for (const double embedded : {10.0, 6.3}) {
      const Case c = case_from(pile_toml, {fmt::format("body.pile.shaft.distribution={}", dist),
                                           fmt::format("body.pile.shaft.embedded={}", embedded)});
      const Line line = build_line(c);
      const auto& r = line.shaft.ultimate;
      EXPECT_NEAR(std::accumulate(r.begin(), r.end(), 0.0), 300e3, 1e-9 * 300e3) << dist << " " << embedded;
      const auto ground = static_cast<std::size_t>(std::ceil(embedded / 0.2 - 1e-9));
      for (std::size_t j = ground + 1; j < r.size(); ++j) EXPECT_EQ(r[j], 0.0) << j;  // above the ground
      if (std::string(dist) == "uniform" && embedded == 10.0) {
        EXPECT_NEAR(r[0], 300e3 / 100, 1e-6);  // half an element's share at the toe
        EXPECT_NEAR(r[20], 300e3 / 50, 1e-6);
      }
      if (std::string(dist) == "triangular") {
        for (std::size_t j = 2; j < ground; ++j) EXPECT_LT(r[j], r[j - 1]) << "largest at the toe";
      }
      for (std::size_t j : line.shaft.nodes) EXPECT_DOUBLE_EQ(line.shaft.stiffness[j], r[j] / 0.0025);
    }
  }
}

}  // namespace
}  // namespace barimpact
