// The history's columns beyond the budget (probe.hpp): their names in
// history.csv's order, and each one's value off a scheme's state through
// the line's numbering, against the formulas the header states (a diesel
// joint's gas pressure among them).
#include "barimpact/run/probe.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <span>
#include <string>
#include <vector>

#include "../support/diesel.hpp"
#include "../support/line_parts.hpp"
#include "../support/run_case.hpp"
#include "barimpact/case/line_builder.hpp"

namespace barimpact {
namespace {

using testing::bar;
using testing::law_joint;
using testing::mass;

// A scheme whose state is whatever the test puts in u, v and its bonds'
// plastic strain; its far-end force is not computed (NaN: read off the last bond).
class StateScheme final : public Scheme {
 public:
  explicit StateScheme(std::size_t nodes) : u(nodes, 0.0), v(nodes, 0.0) {}
  std::vector<double> u, v;
  double eps_p = 0.0;

  void start() override {}
  void advance() override {}
  [[nodiscard]] long long step() const override { return 0; }
  [[nodiscard]] double time() const override { return 0.0; }
  [[nodiscard]] std::size_t nodes() const override { return u.size(); }
  [[nodiscard]] double end_displacement() const override { return u[0]; }
  [[nodiscard]] double end_velocity() const override { return v[0]; }
  [[nodiscard]] double reaction() const override { return 0.0; }
  void displacement(std::span<double> out) const override { std::copy(u.begin(), u.end(), out.begin()); }
  void velocity(std::span<double> out) const override { std::copy(v.begin(), v.end(), out.begin()); }
  [[nodiscard]] Energies energies() const override { return {}; }
  [[nodiscard]] double displacement_at(std::size_t j) const override { return u[j]; }
  [[nodiscard]] double velocity_at(std::size_t j) const override { return v[j]; }
  [[nodiscard]] double link_opening(std::size_t /*i*/) const override { return 0.0; }
  [[nodiscard]] double plastic_strain(std::size_t /*bond*/) const override { return eps_p; }
  [[nodiscard]] bool finite() const override { return true; }
};

// Bar "a" (length 1, 10 elements, E = 4, A = 0.5, eta = 0.2) under a mass
// "m" on a spring of k = 50, a force on the far end, gauge "G" at x = 0.35.
Case bar_spring_mass() {
  Case c;
  BodyData a = bar("a", 1.0, 10);
  a.modulus = 4.0;
  a.area = 0.5;
  a.viscosity = 0.2;
  c.bodies = {a, mass("m", 2.0, 0.0)};
  c.joints = {law_joint("a", "m", JointLaw::spring, 50.0)};
  c.far_end.law = JointLaw::force;
  c.far_end.value = std::string("1");
  GaugeData g;
  g.name = "G";
  g.body = "a";
  g.at = 0.35;
  c.gauges = {g};
  return c;
}

TEST(Probes, ColumnsAreJointsThenTheFarEndThenMassesThenGauges) {
  const Case c = bar_spring_mass();
  const Line line = build_line(c);
  const Probes probes(c, line);
  const std::vector<std::string> expected{"joint.a-m.force", "joint.a-m.opening", "far_end.force",
                                          "far_end.opening", "body.m.u",          "body.m.v",
                                          "gauge.G.strain",  "gauge.G.velocity",  "gauge.G.force"};
  EXPECT_EQ(probes.names(), expected);
  EXPECT_EQ(probes.size(), expected.size());
  // A free far end has no columns.
  Case free = c;
  free.far_end.law = JointLaw::free;
  const Line free_line = build_line(free);
  EXPECT_EQ(Probes(free, free_line).size(), expected.size() - 2);
}

// A uniform strain eps = 0.01 and strain rate 0.3 along the bar (u_j = eps
// x_j, v_j = 0.3 x_j), the mass at u = 0.2, v = -1. By the header's
// formulas: the spring stretched by 0.2 - 0.01 = 0.19 carries a tension of
// 50 x 0.19 = 9.5 (its force column, compression > 0, -9.5); the far end's
// force read off the last bond is the same; the gauge reads eps, the
// velocity 0.3 x 0.35 and the axial force E A eps + eta A rate = 0.02 +
// 0.03 = 0.05, less E A eps_p = 2 x 0.002 once the bonds carry a plastic
// strain. Tolerance 1e-12: the round-off of differences of u over h = 0.1.
TEST(Probes, EachColumnIsItsFormulaOnTheState) {
  const Case c = bar_spring_mass();
  const Line line = build_line(c);
  ASSERT_EQ(line.nodes(), 12u);  // the bar's 11 nodes, then the mass
  StateScheme s(line.nodes());
  for (std::size_t j = 0; j <= 10; ++j) {
    s.u[j] = 0.01 * 0.1 * static_cast<double>(j);
    s.v[j] = 0.3 * 0.1 * static_cast<double>(j);
  }
  s.u[11] = 0.2;
  s.v[11] = -1.0;
  const Probes probes(c, line);
  std::vector<double> out(probes.size(), std::numeric_limits<double>::quiet_NaN());
  probes.read(s, out.data());
  const double expected[] = {-9.5, 0.19, -9.5, -0.2, 0.2, -1.0, 0.01, 0.105, 0.05};
  for (std::size_t k = 0; k < out.size(); ++k) EXPECT_NEAR(out[k], expected[k], 1e-12) << probes.names()[k];

  ASSERT_EQ(line.gauges.size(), 1u);
  EXPECT_NEAR(bond_tension(line, s, 3), 0.05, 1e-12);
  EXPECT_NEAR(gauge_velocity(s, line.gauges[0]), 0.105, 1e-12);
  s.eps_p = 0.002;
  EXPECT_NEAR(bond_tension(line, s, 3), 0.05 - 4.0 * 0.5 * 0.002, 1e-12);
  EXPECT_NEAR(gauge_force(line, s, line.gauges[0]), 0.046, 1e-12);
}

// Joints listed out of line order still give their columns in line order.
TEST(LineCase, JointColumnsFollowTheLine) {
  const Case c = testing::case_from(R"toml(
[[body]]
name = "a"
[[body]]
name = "b"
[[body]]
name = "c"
[[joint]]
between = ["b", "c"]
law = "spring"
[[joint]]
between = ["a", "b"]
law = "rigid"
[time]
scheme = "central-difference"
step = 0.002
end = 0.01
)toml");
  const RunResult r = run(c);
  ASSERT_GE(r.columns.size(), 4u);
  EXPECT_EQ(r.columns[0], "joint.a-b.force");
  EXPECT_EQ(r.columns[2], "joint.b-c.force");
}

// A diesel joint adds its gas's pressure after its force and opening: at
// the state's opening 0 (the ram at impact) with no compression kept (not
// yet struck), the compression polytrope's p_atm (0.6 / 0.1)^1.35.
TEST(Probes, ADieselJointAddsItsGasPressure) {
  const Case c = testing::diesel_drop();
  const Line line = build_line(c);
  const Probes probes(c, line);
  ASSERT_GE(probes.size(), 3u);
  EXPECT_EQ(probes.names()[0], "joint.gas.force");
  EXPECT_EQ(probes.names()[1], "joint.gas.opening");
  EXPECT_EQ(probes.names()[2], "joint.gas.pressure");
  const StateScheme s(line.nodes());
  std::vector<double> out(probes.size());
  probes.read(s, out.data());
  EXPECT_NEAR(out[2], 101325.0 * std::pow(6.0, 1.35), 1e-9 * out[2]);
}

}  // namespace
}  // namespace barimpact
