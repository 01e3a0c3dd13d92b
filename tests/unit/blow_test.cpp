// A pile-driving blow's results (blow.hpp): the blow counts and transfer
// ratio by their definitions, which runs report a blow, and a blow's
// summary against its own history, at refusal, cut short, without impact,
// ENTHRU against the closed form of a rigid ram on a long pile, and a
// diesel ram's rebound against energy.
#include "barimpact/run/blow.hpp"

#include <gtest/gtest.h>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "../support/diesel.hpp"
#include "../support/line_runs.hpp"
#include "../support/run_case.hpp"
#include "barimpact/case/line_builder.hpp"
#include "barimpact/run/output.hpp"
#include "barimpact/run/simulate.hpp"

namespace barimpact {
namespace {

using testing::case_from;
using testing::column;

// Blows per metre are 1 / set: a set of 4 mm is 250 blows a metre, 62.5
// per 250 mm; a set of 0 after an impact is refusal (infinite), and
// without an impact there is no count (NaN). The transfer ratio is ENTHRU
// over the hammer's energy, NaN when the ram brought none.
TEST(BlowSummary, BlowCountsAndTransferRatioFollowTheirDefinitions) {
  BlowSummary b;
  b.set = 0.004;
  EXPECT_TRUE(std::isnan(b.blows_per_m()));
  EXPECT_TRUE(std::isnan(b.blows_per_250mm()));
  b.impact = true;
  EXPECT_DOUBLE_EQ(b.blows_per_m(), 250.0);
  EXPECT_DOUBLE_EQ(b.blows_per_250mm(), 62.5);
  b.set = 0.0;
  EXPECT_TRUE(std::isinf(b.blows_per_m()));
  EXPECT_GT(b.blows_per_m(), 0.0);
  EXPECT_TRUE(std::isnan(b.transfer_ratio()));
  b.enthru = 3.0;
  EXPECT_TRUE(std::isnan(b.transfer_ratio()));
  b.hammer_energy = 4.0;
  EXPECT_EQ(b.transfer_ratio(), 0.75);
}

// A run reports a blow when its line has Smith's soil or the case a [blow]
// section; the paper's bar on its obstacle does not.
TEST(BlowSummary, ReportedForSmithsSoilOrABlowSection) {
  const Case pile = testing::example("pile/steel-pipe-sand.toml");
  EXPECT_TRUE(reports_blow(pile, build_line(pile)));
  const Case bar = testing::example("paper-example1.toml");
  EXPECT_FALSE(reports_blow(bar, build_line(bar)));
  const Case hammer = case_from(R"toml([[body]]
name = "pile"
[[body]]
name = "ram"
kind = "mass"
mass = 1.0
velocity = -1.0
[[gauge]]
name = "G"
body = "pile"
at = 0.5
[blow]
gauge = "G"
[time]
scheme = "central-difference"
step = 0.001
)toml");
  EXPECT_TRUE(reports_blow(hammer, build_line(hammer)));
}

// The blow's results against what the history says, row by row (every step).
TEST(SmithBlow, ResultsAgreeWithTheHistory) {
  // The example under gravity: the ram rebounds, falls back and strikes
  // again at 0.39 s, where the blow ends; the pile is at rest just before.
  const Case c = testing::example("pile/steel-pipe-sand.toml", {"output.every=1", "time.end=0.45"});
  const RunResult r = run(c);
  ASSERT_TRUE(r.summary.blow);
  const BlowSummary& b = *r.summary.blow;
  ASSERT_NEAR(b.restrike_time, 0.39, 0.01);
  std::size_t rows = 0;  // the blow's rows: before the re-strike
  while (rows < r.history.size() && r.history[rows].t < b.restrike_time) ++rows;
  ASSERT_LT(rows, r.history.size());
  EXPECT_EQ(b.pile, "pile");
  EXPECT_EQ(b.ram, "ram");
  EXPECT_EQ(b.gauge, "head");
  EXPECT_DOUBLE_EQ(b.hammer_energy, 0.5 * 4000.0 * 4.43 * 4.43);  // in contact from t = 0
  // ENTHRU: the largest running trapezoid sum of N v at the gauge.
  double e = 0.0, most = 0.0;
  for (std::size_t i = 1; i < rows; ++i) {
    auto p = [&](std::size_t k) { return column(r, "gauge.head.force", k) * column(r, "gauge.head.velocity", k); };
    e += 0.5 * (p(i - 1) + p(i)) * (r.history[i].t - r.history[i - 1].t);
    most = std::max(most, e);
  }
  EXPECT_NEAR(b.enthru, most, 1e-12 * most);
  EXPECT_GT(b.enthru, 0.5 * b.hammer_energy) << "energy flowing down is positive";
  EXPECT_LT(b.enthru, b.hammer_energy);
  EXPECT_DOUBLE_EQ(b.transfer_ratio(), b.enthru / b.hammer_energy);
  // The set: the toe's largest penetration less its quake.
  double deepest = 0.0;
  for (std::size_t i = 0; i < rows; ++i) deepest = std::max(deepest, -r.history[i].U);
  EXPECT_DOUBLE_EQ(b.toe_penetration, deepest);
  EXPECT_DOUBLE_EQ(b.set, deepest - 0.0025);
  EXPECT_DOUBLE_EQ(b.blows_per_250mm(), 0.25 / b.set);
  // The stress extremes bound the gauge's, and sit in the pile.
  for (std::size_t i = 0; i < rows; ++i) {
    const double sigma = column(r, "gauge.head.force", i) / 0.0105;
    EXPECT_LE(-sigma, b.max_compression.value * (1 + 1e-12));
    EXPECT_LE(sigma, b.max_tension.value * (1 + 1e-12));
  }
  EXPECT_GT(b.max_tension.value, 0.0);
  EXPECT_LE(b.max_compression.x, 20.0);
  // The envelopes: one entry per pile element, their largest the extremes,
  // and the gauge's element's at least the gauge's stress at every row.
  ASSERT_EQ(b.envelope.x.size(), 100u);
  EXPECT_EQ(*std::max_element(b.envelope.compression.begin(), b.envelope.compression.end()), b.max_compression.value);
  EXPECT_EQ(*std::max_element(b.envelope.tension.begin(), b.envelope.tension.end()), b.max_tension.value);
  const std::size_t at_gauge = 96;  // x = 19.2 is node 96, between elements 95 and 96: its force their mean
  EXPECT_NEAR(b.envelope.x[at_gauge], 19.3, 1e-12);
  for (std::size_t i = 0; i < rows; ++i) {
    const double sigma = column(r, "gauge.head.force", i) / 0.0105;
    EXPECT_LE(-sigma, std::max(b.envelope.compression[95], b.envelope.compression[96]) * (1 + 1e-12));
  }
  EXPECT_NEAR(b.impedance, 0.0105 * std::sqrt(210e9 * 7850.0), 1e-9 * b.impedance);  // E A / c
  EXPECT_TRUE(b.finished);
  EXPECT_LT(b.rest_time, b.restrike_time);
  EXPECT_LT(b.last_slip_time, 0.05) << "the first strike's slip";
}

// Under gravity the example's ram rebounds off the capblock, rises in free
// flight and falls back onto it: a second strike, which a hammer in service
// (caught and lifted) would not give. The blow ends there: its numbers are
// those of a run stopped just before the ram lands again (before, the
// example's "blow" to 0.45 s read 10.22 mm, both strikes together). The ram
// lands when a ballistic flight from where it left says (its velocity then
// v: back after 2 v / g, less the capblock's travel). Without gravity the
// ram never comes back.
TEST(SmithBlow, TheBlowEndsWhereTheRamFallsBackAndStrikesAgain) {
  const RunResult r = run(testing::example("pile/steel-pipe-sand.toml", {"output.every=1", "time.end=0.45"}));
  const BlowSummary& b = *r.summary.blow;
  ASSERT_FALSE(std::isnan(b.restrike_time));
  std::size_t left = 0;  // the last row the capblock pushed before its flight
  for (std::size_t i = 0; i < r.history.size() && r.history[i].t < b.restrike_time; ++i)
    if (column(r, "joint.capblock.force", i) > 0.0) left = i;
  const double v = column(r, "body.ram.v", left), flight = 2.0 * v / 9.81;
  EXPECT_GT(v, 1.0) << "the ram rebounds";
  EXPECT_NEAR(b.restrike_time, r.history[left].t + flight, 0.05 * flight) << "the helmet lands first, a little early";
  const Case cut = testing::example("pile/steel-pipe-sand.toml",
                                    {"output.every=1", fmt::format("time.end={}", b.restrike_time - 2e-3)});
  const BlowSummary first = *run(cut).summary.blow;
  EXPECT_DOUBLE_EQ(b.set, first.set);
  EXPECT_DOUBLE_EQ(b.toe_penetration, first.toe_penetration);
  EXPECT_DOUBLE_EQ(b.max_compression.value, first.max_compression.value);
  EXPECT_DOUBLE_EQ(b.max_tension.value, first.max_tension.value);
  EXPECT_NEAR(b.enthru, first.enthru, 1e-12 * first.enthru);
  EXPECT_TRUE(b.finished);
  EXPECT_LT(b.set, 0.0096) << "the first strike's set, not both strikes'";
  const RunResult none =
      run(testing::example("pile/steel-pipe-sand.toml", {"load.gravity=0", "time.end=0.45", "output.fields_at=[]"}));
  EXPECT_TRUE(std::isnan(none.summary.blow->restrike_time));
  EXPECT_EQ(b.strikes, 1);
}

// On a softer soil the concrete pile is still moving when the rebounding
// ram lands again (twice): those strikes are part of the blow, which ends
// only once the pile has settled.
TEST(SmithBlow, ARamFallingBackOnAPileStillDrivenIsPartOfTheBlow) {
  const BlowSummary b =
      *run(testing::example("pile/concrete-clay.toml",
                            {"near_end.ultimate=181.5e3", "body.pile.shaft.ultimate=544.5e3", "output.fields_at=[]"}))
           .summary.blow;
  EXPECT_GE(b.strikes, 2);
  EXPECT_TRUE(b.finished);
  EXPECT_TRUE(std::isnan(b.restrike_time) || b.restrike_time > b.rest_time);
}

// A hammer the soil does not let through: the toe stays within its quake,
// set 0, blow counts infinite; a run too short to see the pile at rest warns.
// At rest is below the rule from then on, not one instant where every node
// passes through zero while the pile rings (the example's pile read "at
// rest from 0.0786 s" and then moved at 0.66 m/s).
TEST(SmithBlow, APileAtRestStaysBelowTheRuleToTheEnd) {
  // Without gravity: the ram flies off, and the pile rings to the run's end.
  const RunResult ringing =
      run(testing::example("pile/steel-pipe-sand.toml", {"output.every=1", "load.gravity=0", "time.end=0.12"}));
  ASSERT_TRUE(ringing.summary.blow);
  EXPECT_FALSE(ringing.summary.blow->finished) << "still ringing at 0.12 s";
  const RunResult r =
      run(testing::example("pile/steel-pipe-sand.toml", {"output.every=1", "load.gravity=0", "time.end=0.45"}));
  const BlowSummary& b = *r.summary.blow;
  ASSERT_TRUE(b.finished);
  const double limit = 0.01 * std::abs(b.impact_velocity);
  for (std::size_t i = 0; i < r.history.size(); ++i)
    if (r.history[i].t >= b.rest_time) {
      ASSERT_LT(std::abs(column(r, "gauge.head.velocity", i)), limit) << "t = " << r.history[i].t;
    }
  // With a rest window, at rest once below the rule that long.
  const RunResult w =
      run(testing::example("pile/steel-pipe-sand.toml", {"load.gravity=0", "time.end=0.45", "blow.rest_window=0.02"}));
  EXPECT_TRUE(w.summary.blow->finished);
  EXPECT_EQ(w.summary.blow->rest_window, 0.02);
  EXPECT_NEAR(w.summary.blow->rest_time, b.rest_time, 1e-12);
}

// Issue 33's reproduction: a 100 m steel pipe, a steep front (a stiff
// capblock) and a viscous toe. The true tension is 0 until the front
// reaches the toe; newmark reports tension at the toe before it can arrive.
constexpr const char* long_pipe = R"(
[[body]]
name = "pile"
length = 100.0
elements = 2000
area = 0.0105
modulus = 210e9
density = 7850.0
[[body]]
name = "ram"
kind = "mass"
mass = 4000.0
velocity = -4.43
[[joint]]
between = ["pile", "ram"]
law = "cushion"
stiffness = 1.5e9
restitution = 0.8
[near_end]
law = "smith"
ultimate = 1.5e6
quake = 0.0025
damping = 0.5
damping_law = "viscous"
[time]
end = 0.03828
step = 4.834e-6
scheme = "newmark"
[output]
every = 1000
)";

TEST(SmithBlow, TensionAheadOfTheFrontWarnsOfSpuriousOscillation) {
  auto has = [](const RunResult& r) {
    return std::any_of(r.summary.warnings.begin(), r.summary.warnings.end(),
                       [](const std::string& w) { return w.rfind("spurious-oscillation", 0) == 0; });
  };
  const RunResult nm = run(testing::case_from(long_pipe));
  ASSERT_TRUE(nm.summary.blow);
  EXPECT_GT(nm.summary.blow->max_tension.value, 1e6) << "newmark's oscillation behind the front";
  EXPECT_GT(nm.summary.blow->precursor.value, 0.1 * nm.summary.blow->max_tension.value);
  EXPECT_TRUE(has(nm)) << "newmark's max_tension is its oscillation";
  const auto it = std::find_if(nm.summary.warnings.begin(), nm.summary.warnings.end(),
                               [](const std::string& w) { return w.rfind("spurious-oscillation", 0) == 0; });
  ASSERT_NE(it, nm.summary.warnings.end());
  EXPECT_NE(it->find("central-difference"), std::string::npos) << *it;
  // Central differences at their stable step keep the front sharp: no tension, no warning.
  const RunResult cd = run(testing::case_from(long_pipe, {"time.scheme=central-difference", "time.step=auto"}));
  EXPECT_LT(cd.summary.blow->max_tension.value, 0.5e6);
  EXPECT_FALSE(has(cd));
}

// Issue 33: a pile line under gravity starts from static equilibrium (the
// pile's weight on the soil, the helmet on the pile; the ram takes no
// part). With the ram held 0.5 m above its capblock, nothing moves until it
// lands: the toe carries, with the shaft, the weight of pile and helmet.
TEST(SmithBlow, UnderGravityThePileStartsAtRestOnItsSoil) {
  const Case c = testing::example("pile/steel-pipe-sand.toml",
                                  {"load.gravity=9.81", "body.ram.velocity=0.0", "joint.capblock.gap=0.5",
                                   "time.end=0.05", "output.every=1", "output.fields_at=[]"});
  const RunResult r = run(c);
  double fastest = 0.0;
  for (std::size_t i = 0; i < r.history.size(); ++i)
    fastest = std::max({fastest, std::abs(r.history[i].V), std::abs(column(r, "gauge.head.velocity", i))});
  EXPECT_LT(fastest, 1e-6) << "m/s: at rest (started where the case puts it, newmark swings at 0.04 m/s)";
  EXPECT_NEAR(r.history.back().R, r.history.front().R, 1e-6 * r.history.front().R);
  const double weight = (20.0 * 0.0105 * 7850.0 + 800.0) * 9.81;
  EXPECT_GT(r.history.front().R, 0.0);
  EXPECT_LT(r.history.front().R, weight) << "the shaft carries the rest";
  EXPECT_NEAR(column(r, "joint.pile-cushion.force", 0), 800.0 * 9.81, 1e-6 * 800.0 * 9.81) << "the helmet rests on it";
}

TEST(SmithBlow, RefusalAndAnUnfinishedBlow) {
  const RunResult r =
      run(testing::example("pile/steel-pipe-sand.toml", {"near_end.ultimate=2e8", "body.pile.shaft.ultimate=2e8"}));
  ASSERT_TRUE(r.summary.blow);
  EXPECT_EQ(r.summary.blow->set, 0.0);
  EXPECT_TRUE(std::isinf(r.summary.blow->blows_per_m()));
  const RunResult cut = run(testing::example("pile/steel-pipe-sand.toml", {"time.end=0.01", "output.fields_at=[0.0]"}));
  EXPECT_FALSE(cut.summary.blow->finished);
  bool warned = false;
  for (const auto& w : cut.summary.warnings) warned = warned || w.rfind("blow-unfinished:", 0) == 0;
  EXPECT_TRUE(warned);
}

// A blow cut short before the wave has reached the toe: the pile has not
// moved yet, so it is not "at rest" (it was, from the first step, before):
// not finished, warned, and its set of 0 is no refusal on the console.
TEST(SmithBlow, ABlowCutShortIsUnfinishedNotARefusal) {
  const Case c = testing::example("pile/steel-pipe-sand.toml", {"time.end=0.0015", "output.fields_at=[]"});
  const RunResult r = run(c);
  ASSERT_TRUE(r.summary.blow);
  const BlowSummary& b = *r.summary.blow;
  EXPECT_TRUE(b.impact);
  EXPECT_FALSE(b.finished);
  EXPECT_TRUE(std::isnan(b.rest_time));
  bool warned = false;
  for (const auto& w : r.summary.warnings) warned = warned || w.rfind("blow-unfinished:", 0) == 0;
  EXPECT_TRUE(warned);
  const std::string text = summary_text(c, r.summary);
  EXPECT_EQ(text.find("refusal"), std::string::npos) << text;
  EXPECT_NE(text.find("not finished"), std::string::npos) << text;
}

// The console follows [units]: mm, MPa and J under "SI", the case's own
// numbers without a unit under "none"; summary.json names the units.
TEST(SmithBlow, TheConsoleFollowsTheCasesUnits) {
  const std::vector<std::string> short_run{"time.end=0.01", "output.fields_at=[]"};
  const Case si = testing::example("pile/steel-pipe-sand.toml", short_run);
  auto sets = short_run;
  sets.push_back("units.system=none");
  const Case none = testing::example("pile/steel-pipe-sand.toml", sets);
  const RunResult r = run(si);
  const std::string with = summary_text(si, r.summary), without = summary_text(none, r.summary);
  for (const char* unit : {" mm", " MPa", " J ", "per 250 mm"}) {
    EXPECT_NE(with.find(unit), std::string::npos) << unit << with;
    EXPECT_EQ(without.find(unit), std::string::npos) << unit << without;
  }
  EXPECT_NE(summary_json(si, r.summary).find("\"stress\": \"Pa\""), std::string::npos);
  EXPECT_NE(summary_json(none, r.summary).find("\"system\": \"none\""), std::string::npos);
}

// A ram moving away from the pile never strikes it: no impact, said so; no
// refusal, no inf or nan on the console, no blow counts or transfer ratio.
TEST(SmithBlow, ARamMovingAwayIsNoImpact) {
  const Case c =
      testing::example("pile/steel-pipe-sand.toml", {"body.ram.velocity=4.43", "time.end=0.01", "output.fields_at=[]"});
  const RunResult r = run(c);
  ASSERT_TRUE(r.summary.blow);
  const BlowSummary& b = *r.summary.blow;
  EXPECT_FALSE(b.impact);
  EXPECT_FALSE(b.finished);
  EXPECT_TRUE(std::isnan(b.blows_per_m()));
  EXPECT_TRUE(std::isnan(b.transfer_ratio()));
  const std::string text = summary_text(c, r.summary);
  EXPECT_NE(text.find("no impact"), std::string::npos) << text;
  for (const char* word : {"refusal", "inf", "nan"}) EXPECT_EQ(text.find(word), std::string::npos) << word << text;
  // The ram's velocity is named before the run's outcome.
  ASSERT_EQ(r.summary.warnings.size(), 2u);
  EXPECT_EQ(
      r.summary.warnings[0],
      "ram-velocity: body.ram.velocity = 4.43 moves the ram away from the pile (+x runs up from the toe): -4.43?");
  EXPECT_EQ(r.summary.warnings[1].rfind("blow-no-impact:", 0), 0u) << r.summary.warnings[1];
}

// Capacities in kN (900 for 900e3 N), below the steel pipe's own weight of
// 16.2 kN, warn naming each key; the example's own capacities do not.
TEST(SmithBlow, ACapacityBelowThePilesWeightWarnsOfKilonewtons) {
  // The capacities' warnings of a short run (which also warns blow-unfinished).
  auto capacity_warnings = [](std::vector<std::string> sets) {
    sets.insert(sets.end(), {"time.end=0.002", "output.fields_at=[]"});
    std::vector<std::string> out;
    for (const auto& w : run(testing::example("pile/steel-pipe-sand.toml", sets)).summary.warnings)
      if (w.rfind("pile-capacity:", 0) == 0) out.push_back(w);
    return out;
  };
  EXPECT_TRUE(capacity_warnings({}).empty());
  // Without gravity a soil that light still runs, and warns; under gravity
  // (the example's) it cannot hold the pile up at all: refused.
  const auto warnings = capacity_warnings({"near_end.ultimate=900", "body.pile.shaft.ultimate=600", "load.gravity=0"});
  ASSERT_EQ(warnings.size(), 2u);
  EXPECT_EQ(
      warnings[0].rfind("pile-capacity: near_end.ultimate = 900: kN? below the pile's own weight (1.617e+04 N)", 0), 0u)
      << warnings[0];
  EXPECT_EQ(warnings[1].rfind("pile-capacity: body.pile.shaft.ultimate = 600: kN?", 0), 0u) << warnings[1];
  try {
    (void)capacity_warnings({"near_end.ultimate=900", "body.pile.shaft.ultimate=600"});
    ADD_FAILURE() << "a soil that cannot carry the pile's weight under gravity ran";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("near_end.ultimate"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("no static rest (capacities are in N: kN?)"), std::string::npos) << e.what();
  }
}

// A rigid ram of mass M at v0 welded onto a long elastic pile (impedance Z,
// no soil): the head force is Z v0 exp(-Z t / M), so the energy through the
// head gauge by time T (before the toe's reflection returns) is
// (1 - exp(-2 Z T / M)) M v0^2 / 2. Central differences converge to it at
// first order (the gauge's force is the mean of the elements beside it, the
// front a jump): 1% at h = L / 2000.
TEST(SmithBlow, EnthruOfARigidRamOnALongPileIsTheClosedForm) {
  const double length = 40.0, area = 0.01, e = 200e9, rho = 8000.0, m = 2000.0, v0 = 3.0;
  const double c0 = std::sqrt(e / rho), z = e * area / c0, gauge = 39.0, end = 0.9 * 2.0 * (length - 1.0) / c0;
  const Case c = case_from(fmt::format(R"toml(
[[body]]
name = "pile"
length = {}
elements = 2000
area = {}
modulus = {}
density = {}
[[body]]
name = "ram"
kind = "mass"
mass = {}
velocity = {}
[[gauge]]
name = "G"
body = "pile"
at = {}
[blow]
gauge = "G"
[time]
end = {}
step = "auto"
scheme = "central-difference"
)toml",
                                       length, area, e, rho, m, -v0, gauge, end));
  const RunResult r = run(c);
  ASSERT_TRUE(r.summary.blow);
  const double t_gauge = end - (length - gauge) / c0;  // the time the head's history has reached the gauge
  const double exact = (1.0 - std::exp(-2.0 * z * t_gauge / m)) * 0.5 * m * v0 * v0;
  EXPECT_NEAR(r.summary.blow->enthru, exact, 1e-2 * exact);
  EXPECT_DOUBLE_EQ(r.summary.blow->hammer_energy, 0.5 * m * v0 * v0);
}

// A diesel ram dropped from H = 2 m onto its anvil on a rigid stop
// (tests/support/diesel.hpp): the blow reports the gas's works in closed
// form and the rebound, the height the ram rises to above impact, against
// energy, e^2 (H - W_c / m g) + W_e / m g = 2.9011 m. The formula has the
// cushion give back e^2 of the ram's energy at impact; in the run the gas
// (1.45e5 N) and the ram's weight also push through the cushion's 1.2 mm,
// so that it loses about (1 - e^2)(F_gas + m g) c_max less: +2.3e-3 of the
// stroke. Measured +2.0e-3 at dt = 1e-5 s (+2.06e-3 at 2.5e-6 s): within
// 3e-3. A cushion 100 times stiffer (c_max 10 times smaller) brings the
// rebound to the formula: measured 1.5e-4 at dt = 1e-6 s, within 5e-4.
TEST(DieselBlow, RigidStopReboundFollowsFromEnergy) {
  using D = testing::DieselDrop;
  const RunResult r = run(testing::diesel_drop());
  ASSERT_TRUE(r.summary.blow);
  const BlowSummary& b = *r.summary.blow;
  ASSERT_TRUE(b.diesel);
  ASSERT_TRUE(b.impact);
  EXPECT_NEAR(b.compression_work, 5041.958, 1e-3);
  EXPECT_NEAR(b.expansion_work, 19130.289, 1e-3);
  const double expected = D::rebound(b.compression_work, b.expansion_work);
  EXPECT_NEAR(expected, 2.9011, 1e-4);
  EXPECT_NEAR(b.next_stroke, expected, 3e-3 * expected);
  const RunResult stiff =
      run(testing::diesel_drop({"joint.gas.impact_stiffness=2e12", "time.step=1e-6", "output.every=100"}));
  ASSERT_TRUE(stiff.summary.blow);
  EXPECT_NEAR(stiff.summary.blow->next_stroke, expected, 5e-4 * expected);
  // summary.json carries them.
  const std::string json = summary_json(testing::diesel_drop(), r.summary);
  for (const char* key : {"\"next_stroke\"", "\"compression_work\"", "\"expansion_work\""})
    EXPECT_NE(json.find(key), std::string::npos) << key;
}

// Cut short before the ram is back at its ports, the blow has no next stroke yet.
TEST(DieselBlow, NoNextStrokeBeforeTheRamPassesThePorts) {
  const RunResult r = run(testing::diesel_drop({"time.end=0.1"}));
  ASSERT_TRUE(r.summary.blow);
  EXPECT_TRUE(r.summary.blow->diesel);
  EXPECT_TRUE(std::isnan(r.summary.blow->next_stroke));
}

// The same hammer on the steel pipe in sand (examples/pile/diesel-pipe-sand.toml)
// at half, once and twice its capacity (toe and shaft scaled together): the
// harder the soil, the smaller the set and the higher the ram rebounds
// (measured 2.03, 2.22 and 2.33 m); the budget closes within 2e-3 of the
// ram's energy m g H through the blow (measured at most 21.5 J, 1.1e-3 of
// it, in the three runs since the line starts at rest on its soil under
// gravity, 10.1 J before: the cushions' and the soil's forces at t_n).
TEST(DieselBlow, StrokeRisesWithTheSoilsResistance) {
  double last_stroke = 0.0, last_set = 1.0;
  for (const double scale : {0.5, 1.0, 2.0}) {
    const Case c =
        testing::example("pile/diesel-pipe-sand.toml", {fmt::format("near_end.ultimate={}", 900e3 * scale),
                                                        fmt::format("body.pile.shaft.ultimate={}", 600e3 * scale)});
    const RunResult r = run(c);
    ASSERT_TRUE(r.summary.blow);
    const BlowSummary& b = *r.summary.blow;
    EXPECT_GT(b.next_stroke, last_stroke) << scale;
    EXPECT_LT(b.set, last_set) << scale;
    last_stroke = b.next_stroke;
    last_set = b.set;
    const double e0 = r.history.front().total();
    for (const auto& h : r.history) ASSERT_NEAR(h.total(), e0, 2e-3 * 1000.0 * 9.81 * 2.0) << scale << " " << h.t;
  }
}

}  // namespace
}  // namespace barimpact
