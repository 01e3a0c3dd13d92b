// barimpact check: the penalty time constants (Z/k, impedances in series,
// sqrt(m/k)), the stable steps it reports, and its timing run.
#include "barimpact/run/check.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "../support/run_case.hpp"
#include "barimpact/case/line_builder.hpp"
#include "barimpact/model/input_error.hpp"
#include "barimpact/schemes/line_scheme.hpp"
#include "barimpact/schemes/scheme.hpp"

namespace barimpact {
namespace {

using testing::case_from;

constexpr const char* two_bars = R"(
[[body]]
name = "left"
length = 1.0
elements = 10
modulus = 1.0
density = 1.0
[[body]]
name = "right"
length = 1.0
elements = 10
modulus = 4.0
density = 1.0
velocity = "-1"
[[joint]]
between = ["left", "right"]
law = "elastic"
stiffness = 10.0
gap = 0.01
[time]
end = 1.0
step = 0.01
scheme = "central-difference"
)";

TEST(Check, SingleBarPenaltyIsImpedanceOverStiffness) {
  // Z = sqrt(rho a) = sqrt(2 * 8) = 4, k = 100: tau = 0.04.
  const Case c = case_from("[bar]\ndensity = 2.0\nstiffness = 8.0\n[obstacle]\nstiffness = 100.0\n");
  const auto p = penalty_time_constants(c);
  ASSERT_EQ(p.size(), 1U);
  EXPECT_NEAR(p[0].tau, 0.04, 1e-15);  // one division: round-off only
  EXPECT_EQ(p[0].basis, "Z/k");
}

TEST(Check, JointBetweenBarsTakesImpedancesInSeries) {
  // Z1 = A sqrt(E rho) = 1, Z2 = sqrt(4) = 2: Z1 Z2/(Z1 + Z2) = 2/3, tau = 2/30.
  const auto p = penalty_time_constants(case_from(two_bars));
  ASSERT_EQ(p.size(), 1U);
  EXPECT_NEAR(p[0].tau, 2.0 / 30.0, 1e-15);
  EXPECT_EQ(p[0].link, "joint.left-right");
}

TEST(Check, MassesTakeTheirReducedMass) {
  const Case c = case_from(R"(
[[body]]
name = "anvil"
kind = "mass"
mass = 3.0
[[body]]
name = "hammer"
kind = "mass"
mass = 6.0
velocity = -1
[[joint]]
between = ["anvil", "hammer"]
law = "elastic"
stiffness = 50.0
[near_end]
law = "elastic"
stiffness = 12.0
[time]
end = 1.0
step = 0.01
scheme = "central-difference"
)");
  const auto p = penalty_time_constants(c);
  ASSERT_EQ(p.size(), 2U);
  EXPECT_NEAR(p[0].tau, std::sqrt(3.0 / 12.0), 1e-15);              // the near end: the anvil alone
  EXPECT_NEAR(p[1].tau, std::sqrt(3.0 * 6.0 / 9.0 / 50.0), 1e-15);  // m1 m2/(m1 + m2) = 2
}

TEST(Check, ALightMassOnABarTakesTheSmallerTimeConstant) {
  // Bar Z = 1; mass m against it through k = 100: Z/k = 0.01, sqrt(m/k) =
  // 0.001 for m = 1e-4 (the mass rings faster than the bar answers).
  const std::string line = R"(
[[body]]
name = "bar"
length = 1.0
elements = 10
[[body]]
name = "tip"
kind = "mass"
mass = MASS
velocity = -1
[[joint]]
between = ["bar", "tip"]
law = "elastic"
stiffness = 100.0
[time]
end = 1.0
step = 1e-4
scheme = "central-difference"
)";
  auto with_mass = [&](const char* m) {
    std::string text = line;
    text.replace(text.find("MASS"), 4, m);
    return penalty_time_constants(case_from(text));
  };
  const auto light = with_mass("1e-4");
  ASSERT_EQ(light.size(), 1U);
  EXPECT_NEAR(light[0].tau, 1e-3, 1e-15);
  EXPECT_EQ(light[0].basis, "sqrt(m/k)");
  const auto heavy = with_mass("10.0");  // sqrt(m/k) = 0.32 > Z/k = 0.01
  ASSERT_EQ(heavy.size(), 1U);
  EXPECT_NEAR(heavy[0].tau, 0.01, 1e-15);
  EXPECT_EQ(heavy[0].basis, "Z/k");
}

TEST(Check, ReportsTheExplicitSchemesStableStepWithItsMass) {
  const Case lumped = case_from("[time]\nscheme = \"central-difference\"\nstep = 0.005\n");
  const auto k = check_case(lumped);
  ASSERT_TRUE(k.stable_step);
  EXPECT_EQ(*k.stable_step, line_stable_step(build_line(lumped), false));
  EXPECT_EQ(k.mass, "lumped");
  const Case consistent =
      case_from("[time]\nscheme = \"paoli-schatzman\"\nstep = 0.001\n[obstacle]\nkind = \"rigid\"\n");
  const auto kc = check_case(consistent);
  ASSERT_TRUE(kc.stable_step);
  EXPECT_EQ(*kc.stable_step, line_stable_step(build_line(consistent), true));
  EXPECT_EQ(kc.mass, "consistent");
  // The paper's scheme at alpha = 1/4 is unconditionally stable: no limit.
  EXPECT_FALSE(check_case(case_from("")).stable_step);
  EXPECT_TRUE(check_case(case_from("[time]\nalpha = 0.1\n")).stable_step);
}

TEST(Check, TimesAShortStretchAndScalesItToTheRun) {
  const Case c = case_from("[bar]\nelements = 1000\n[time]\nend = 10.0\nstep = 0.001\n");  // 10^4 steps
  const auto k = check_case(c, 1e5);                                                       // 100 steps of 1001 nodes
  EXPECT_EQ(k.steps, 10000);
  EXPECT_EQ(k.timed_steps, 99);
  EXPECT_GT(k.timed_seconds, 0.0);
  EXPECT_DOUBLE_EQ(k.estimate_seconds, k.timed_seconds * 10000.0 / 99.0);
  EXPECT_TRUE(k.trouble.empty());
  const std::string text = check_text(c, k);
  EXPECT_NE(text.find("steps: 10000"), std::string::npos) << text;
  EXPECT_NE(text.find("time estimate: "), std::string::npos) << text;
}

TEST(Check, SaysWhenTheStepDoesNotResolveThePenalty) {
  const Case c = case_from("[obstacle]\nstiffness = 1e4\n[time]\nstep = 0.001\n");
  const std::string text = check_text(c, check_case(c));
  EXPECT_NE(text.find("penalty: tau = 0.0001, dt/tau = 10 not resolved"), std::string::npos) << text;
  const Case resolved = case_from("[obstacle]\nstiffness = 1e4\n[time]\nstep = 5e-5\n");
  EXPECT_EQ(check_text(resolved, check_case(resolved)).find("not resolved"), std::string::npos);
}

TEST(Resources, CountTheNodesSnapshotsAndRowsOfTheRun) {
  // 1000 elements: 1001 nodes; 3 times, two on one step: 2 snapshots; 100 steps, every 10: 10 + 2 rows.
  const Case c = case_from(
      "[bar]\nelements = 1000\n[time]\nstep = 0.01\nend = 1.0\n[output]\nevery = 10\nfields_at = [0.0, 0.5, 0.501]\n");
  const ResourceEstimate held = estimate_resources(c, false), streamed = estimate_resources(c, true);
  EXPECT_EQ(held.nodes, 1001u);
  EXPECT_EQ(held.snapshots, 2u);
  EXPECT_EQ(held.history_rows, 12);
  // Streamed, the run holds one snapshot of 4 doubles a node, not two.
  EXPECT_DOUBLE_EQ(held.memory_bytes - streamed.memory_bytes, 32.0 * 1001);
  EXPECT_EQ(held.output_bytes, streamed.output_bytes);
}

TEST(Resources, RefusesWhatExceedsTheMemoryNamingTheKeys) {
  const Case c = case_from("[bar]\nelements = 100000\n[time]\nstep = 0.01\nend = 1.0\n");
  const ResourceEstimate e = estimate_resources(c, true);
  EXPECT_NO_THROW(refuse_beyond_memory(c, e, 2 * e.memory_bytes));
  try {
    refuse_beyond_memory(c, e, e.memory_bytes / 2);
    FAIL() << "not refused";
  } catch (const InputError& err) {
    const std::string what = err.what();
    for (const char* key : {"bar.elements", "output.fields_at", "output.every", "time.end"})
      EXPECT_NE(what.find(key), std::string::npos) << what;
  }
  EXPECT_GT(available_memory(), 0.0);
}

TEST(Resources, ALineNamesItsLargestBody) {
  Case c = case_from(two_bars);
  c.bodies[1].elements = 1000;
  try {
    refuse_beyond_memory(c, estimate_resources(c, true), 0.0);
    FAIL() << "not refused";
  } catch (const InputError& err) {
    EXPECT_NE(std::string(err.what()).find("body.right.elements"), std::string::npos) << err.what();
  }
}

TEST(Resources, WarnsOfOutputsAboveAGigabyte) {
  Case c = case_from("[bar]\nelements = 100\n[time]\nstep = 0.01\nend = 1.0\n[output]\nfields_at = [0.5]\n");
  EXPECT_EQ(output_size_warning(c, estimate_resources(c, true)), "");
  c.bodies[0].elements = 100'000'000;
  const std::string w = output_size_warning(c, estimate_resources(c, true));
  EXPECT_NE(w.find("GB on disk"), std::string::npos) << w;
  // HDF5: 8 bytes a value, snapshots of u, v, sigma, eps_p.
  c.bodies[0].elements = 999;
  c.output.format = OutputFormat::hdf5;
  const auto e = estimate_resources(c, true);
  EXPECT_DOUBLE_EQ(e.output_bytes, 8.0 * (102.0 * 11 + 4.0 * 1000 + 1000));
}

TEST(Resources, ResultsH5IsNotHeldInMemory) {
  // 101 snapshots of 10^5 nodes: results.h5 is written as the run goes, so
  // it costs HDF5's chunk caches beside the CSV's held snapshot, not the file.
  Case c = case_from("[bar]\nelements = 100000\n[time]\nstep = 0.01\nend = 1.0\n[output]\nfields_at = [0.5]\n");
  for (int s = 0; s <= 100; ++s) c.output.fields_at.push_back(0.01 * s);
  const double csv = estimate_resources(c, true).memory_bytes;
  c.output.format = OutputFormat::hdf5;
  EXPECT_LT(estimate_resources(c, true).memory_bytes, csv + 5e6);
}

}  // namespace
}  // namespace barimpact
