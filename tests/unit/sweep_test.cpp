// Parameter sweeps (sweep.hpp): the plan read from a sweep file's text
// (lists, linear and log ranges, zips, ids), the line's keys in [set] and
// the axes, and sweep.csv's rows against the runs.
#include "barimpact/study/sweep.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "../support/run_case.hpp"
#include "../support/scratch_directory.hpp"

namespace {

// A sweep over the pile hammer (examples/lines), its plan given as text.
barimpact::SweepPlan pile_sweep(const std::string& rest) {
  return barimpact::SweepPlan::from_string("case = \"pile-hammer.toml\"\n" + rest, "sweep.toml",
                                           BARIMPACT_SOURCE_DIR "/examples/lines");
}

}  // namespace

namespace {

// A sweep of an example (`example` in examples/`folder`) with its [set] and one axis.
barimpact::SweepPlan example_sweep(const std::string& folder, const std::string& example, const std::string& set,
                                   const std::string& key, const std::string& values) {
  return barimpact::SweepPlan::from_string(
      fmt::format("case = \"{}\"\n[set]\n{}[[axis]]\nkey = \"{}\"\nvalues = [{}]\n", example, set, key, values),
      "sweep.toml", std::string(BARIMPACT_SOURCE_DIR "/examples/") + folder);
}

}  // namespace

namespace barimpact {
namespace {

// The value of `key` at a point, as TOML text; a failure (and "") when the point has none.
std::string value_at(const SweepPoint& p, const std::string& key) {
  for (const auto& [k, v] : p.values)
    if (k == key) return v;
  ADD_FAILURE() << "no " << key;
  return "";
}

// Issue 36: ranges whose points overflow (to - from, or to / from, beyond
// the largest double) gave inf and nan from finite ends. Every point is now
// finite, between the ends, the ends themselves exact.
TEST(SweepPlan, ARangeOfFiniteEndsHasFinitePointsBetweenThem) {
  for (const auto& [from, to, scale] :
       {std::tuple{"-1.7e308", "1.7e308", "linear"}, std::tuple{"1.7e308", "-1.7e308", "linear"},
        std::tuple{"1e-300", "1e300", "log"}, std::tuple{"1e300", "1e-300", "log"},
        std::tuple{"4.9e-324", "1.7e308", "log"}}) {
    const auto plan = SweepPlan::from_string(
        fmt::format("case = \"paper-example1.toml\"\n[[axis]]\nkey = \"obstacle.gap\"\nfrom = {}\nto = {}\n"
                    "count = 5\nscale = \"{}\"\n",
                    from, to, scale),
        "sweep.toml", BARIMPACT_EXAMPLES_DIR);
    ASSERT_EQ(plan.points().size(), 5u);
    const auto number = [](const std::string& text) { return std::strtod(text.c_str(), nullptr); };  // subnormals too
    const double a = number(from), b = number(to);
    std::vector<double> points;
    for (const auto& p : plan.points()) points.push_back(number(value_at(p, "obstacle.gap")));
    for (const double x : points) {
      EXPECT_TRUE(std::isfinite(x)) << from << " .. " << to << ": " << x;
      EXPECT_GE(x, std::min(a, b)) << from << " .. " << to;
      EXPECT_LE(x, std::max(a, b)) << from << " .. " << to;
    }
    EXPECT_TRUE(std::is_sorted(points.begin(), points.end()) || std::is_sorted(points.rbegin(), points.rend()));
    EXPECT_EQ(points.front(), a);
    EXPECT_EQ(points.back(), b);
  }
}

// Two axes make their product: a list of 2 and a log range of 3 from 0.01
// to 0.001 (ratio 10^(-1/2) a point: 0.01, sqrt(1e-5), 0.001), 6 points,
// each combination once, ids of 4 digits at least in order. Tolerance of
// the range's middle value 1e-12 relative: pow's rounding and the text.
TEST(SweepPlan, AxesMakeTheirProductAndARangeItsSpacing) {
  const auto plan = SweepPlan::from_string(
      "case = \"paper-example1.toml\"\n[[axis]]\nkey = \"obstacle.stiffness\"\nvalues = [100.0, 1000.0]\n"
      "[[axis]]\nkey = \"time.step\"\nfrom = 0.01\nto = 0.001\ncount = 3\nscale = \"log\"\n",
      "sweep.toml", BARIMPACT_EXAMPLES_DIR);
  EXPECT_EQ(plan.keys(), (std::vector<std::string>{"obstacle.stiffness", "time.step"}));
  ASSERT_EQ(plan.points().size(), 6u);
  std::set<std::pair<std::string, double>> seen;
  for (std::size_t i = 0; i < 6; ++i) {
    const SweepPoint& p = plan.points()[i];
    EXPECT_EQ(p.id, fmt::format("{:04}", i));
    const double step = std::stod(value_at(p, "time.step"));
    seen.insert({value_at(p, "obstacle.stiffness"), step});
    const Case c = plan.case_at(p);
    EXPECT_EQ(c.time.step, step);
    EXPECT_EQ(c.one_bar()->obstacle.stiffness, std::stod(value_at(p, "obstacle.stiffness")));
  }
  ASSERT_EQ(seen.size(), 6u);
  std::set<double> steps;
  for (const auto& [k, dt] : seen) steps.insert(dt);
  ASSERT_EQ(steps.size(), 3u);
  EXPECT_NEAR(*steps.begin(), 0.001, 1e-15);
  EXPECT_NEAR(*std::next(steps.begin()), std::sqrt(1e-5), 1e-12 * std::sqrt(1e-5));
  EXPECT_NEAR(*steps.rbegin(), 0.01, 1e-15);
}

// Zipped axes move together: two lists of 3 give 3 points, paired in
// order; a linear range of 3 from 10 to 30 is 10, 20, 30.
TEST(SweepPlan, ZippedAxesMoveTogether) {
  const auto plan = SweepPlan::from_string(
      "case = \"paper-example1.toml\"\nzip = [[\"obstacle.stiffness\", \"bar.elements\"]]\n"
      "[[axis]]\nkey = \"obstacle.stiffness\"\nfrom = 10.0\nto = 30.0\ncount = 3\n"
      "[[axis]]\nkey = \"bar.elements\"\nvalues = [10, 20, 40]\n",
      "sweep.toml", BARIMPACT_EXAMPLES_DIR);
  ASSERT_EQ(plan.points().size(), 3u);
  const double k[] = {10.0, 20.0, 30.0};
  const int m[] = {10, 20, 40};
  for (std::size_t i = 0; i < 3; ++i) {
    const Case c = plan.case_at(plan.points()[i]);
    EXPECT_EQ(c.one_bar()->obstacle.stiffness, k[i]) << i;
    EXPECT_EQ(c.one_bar()->bar.elements, m[i]) << i;
  }
}

// A refused plan names its file and the rule.
TEST(SweepPlan, RefusesABadAxisNamingTheFileAndTheRule) {
  auto refusal = [](const std::string& axis) {
    try {
      (void)SweepPlan::from_string("case = \"paper-example1.toml\"\n[[axis]]\n" + axis, "sweep.toml",
                                   BARIMPACT_EXAMPLES_DIR);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    ADD_FAILURE() << "accepted " << axis;
    return std::string();
  };
  const std::string scale = refusal("key = \"time.step\"\nfrom = 0.01\nto = 0.001\ncount = 3\nscale = \"cubic\"\n");
  EXPECT_NE(scale.find("sweep.toml"), std::string::npos) << scale;
  EXPECT_NE(scale.find("axis time.step: scale must be linear or log"), std::string::npos) << scale;
  const std::string log = refusal("key = \"obstacle.gap\"\nfrom = 0.0\nto = 0.1\ncount = 3\nscale = \"log\"\n");
  EXPECT_NE(log.find("axis obstacle.gap: a log range needs from, to > 0"), std::string::npos) << log;
}

TEST(SweepPlan, RefusesACaseFileThatIsNotARegularFile) {
  // A FIFO would block every point's read until a writer came.
  const testing::ScratchDirectory dir("sweep-fifo");
  ASSERT_EQ(::mkfifo((dir.path() / "case.fifo").c_str(), 0600), 0);
  try {
    (void)SweepPlan::from_string("case = \"case.fifo\"\n[[axis]]\nkey = \"bar.length\"\nvalues = [1]\n", "sweep.toml",
                                 dir.path());
    ADD_FAILURE() << "accepted a FIFO";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("case.fifo: the case file is a named pipe"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace barimpact

// [set] takes the line's keys as TOML writes them (a dotted key is nested
// tables): every point's case has them, beside the axes' values.
TEST(SweepLines, SetTakesTheLinesDottedKeys) {
  const auto plan = pile_sweep(
      "[set]\nbody.pile.elements = 50\njoint.capblock.restitution = 0.7\ntime.end = 0.02\noutput.fields_at = []\n"
      "[[axis]]\nkey = \"body.ram.velocity\"\nvalues = [-1.0, -2.0]\n");
  ASSERT_EQ(plan.points().size(), 2u);
  for (std::size_t i = 0; i < 2; ++i) {
    const barimpact::Case c = plan.case_at(plan.points()[i]);
    const auto pile = std::find_if(c.bodies.begin(), c.bodies.end(), [](const auto& b) { return b.name == "pile"; });
    const auto ram = std::find_if(c.bodies.begin(), c.bodies.end(), [](const auto& b) { return b.name == "ram"; });
    ASSERT_NE(pile, c.bodies.end());
    ASSERT_NE(ram, c.bodies.end());
    EXPECT_EQ(pile->elements, 50);
    EXPECT_EQ(c.joints.at(0).law.restitution, 0.7);
    EXPECT_EQ(c.time.end, 0.02);
    EXPECT_EQ(ram->velocity, i == 0 ? "-1" : "-2");
  }
}

// An axis naming a body, joint or gauge the case does not have is refused
// when the plan is read, naming the axis, as a misspelled key is (not run
// as a sweep of refused cases).
TEST(SweepLines, RefusesAnAxisNamingNoPartOfTheLine) {
  for (const char* key : {"body.nobody.velocity", "joint.nojoint.gap", "gauge.nogauge.at"}) {
    try {
      (void)pile_sweep(fmt::format("[[axis]]\nkey = \"{}\"\nvalues = [1.0, 2.0]\n", key));
      ADD_FAILURE() << "accepted " << key;
    } catch (const barimpact::InputError& e) {
      EXPECT_NE(std::string(e.what()).find(fmt::format("axis {}", key)), std::string::npos) << e.what();
    }
  }
}

// A penalty so stiff for its step that the contact chatters (hundreds of
// brief episodes): the sweep's lift-off and rebound come from one episode,
// the last (the bar leaves near t = 2), never the first brief touch's end
// beside the last episode's rebound.
TEST(SweepRows, LiftOffAndReboundComeFromTheSameEpisode) {
  const barimpact::testing::ScratchDirectory dir("sweep-episodes");
  const auto plan =
      example_sweep(".", "paper-example1.toml", "output.fields_at = []\ntime.step = 0.0025\nbar.elements = 800\n",
                    "obstacle.stiffness", "800.0");
  std::filesystem::create_directories(dir.path() / "runs");
  const auto rows = barimpact::run_sweep(plan, dir.path(), {0}, {});
  ASSERT_EQ(rows.size(), 1u);
  const auto& r = rows.front();
  ASSERT_GT(r.contacts, 10) << "the contact chatters";
  const barimpact::RunResult run = barimpact::run(plan.case_at(plan.points()[0]));
  const barimpact::ContactInterval& last = run.summary.contacts.back();
  ASSERT_TRUE(last.closed);
  EXPECT_EQ(r.lift_off, last.end);
  EXPECT_EQ(r.rebound_velocity, last.rebound_velocity);
  EXPECT_GT(r.lift_off, 1.9);
}

// A sweep of pile blows: sweep.csv adds the blow's columns after the
// contract's (set, blow counts, driving stresses, ENTHRU), the run's own
// numbers, and a resumed sweep reads them back from the runs.
TEST(SweepRows, APileSweepHasTheBlowsColumns) {
  const barimpact::testing::ScratchDirectory dir("sweep-blows");
  const auto plan = example_sweep("pile", "steel-pipe-sand.toml", "output.fields_at = []\nbody.pile.elements = 40\n",
                                  "near_end.ultimate", "1.0e6, 2.0e6");
  const auto out = dir.path() / "sweep";
  const auto first = barimpact::write_sweep(plan, out, {}, false);
  ASSERT_EQ(first.rows.size(), 2u);
  for (std::size_t i = 0; i < 2; ++i) {
    const auto& r = first.rows[i];
    ASSERT_TRUE(r.blow);
    const auto b = *barimpact::run(plan.case_at(plan.points()[i])).summary.blow;
    EXPECT_EQ(r.set, b.set);
    EXPECT_EQ(r.blows_per_250mm, b.blows_per_250mm());
    EXPECT_EQ(r.max_compression, b.max_compression.value);
    EXPECT_EQ(r.max_tension, b.max_tension.value);
    EXPECT_EQ(r.enthru, b.enthru);
  }
  std::ifstream csv(out / "sweep.csv");
  std::string header;
  std::getline(csv, header);
  EXPECT_NE(header.find(",message,warnings,set,blows_per_250mm,blows_per_m,max_compression,max_tension,enthru"),
            std::string::npos)
      << header;
  const auto again = barimpact::write_sweep(plan, out, {}, false);  // resumed: read back from the runs
  EXPECT_EQ(again.resumed, 2u);
  for (std::size_t i = 0; i < 2; ++i) {
    EXPECT_TRUE(again.rows[i].blow);
    EXPECT_EQ(again.rows[i].set, first.rows[i].set);
    EXPECT_EQ(again.rows[i].enthru, first.rows[i].enthru);
  }
}
