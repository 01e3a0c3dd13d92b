// The drivability study: each depth's blow is the run of the case with the
// profile's resistances written by hand; drive.csv's columns and totals.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>

#include "../support/pile.hpp"
#include "../support/run_case.hpp"
#include "../support/scratch_directory.hpp"
#include "barimpact/study/drive.hpp"

namespace barimpact {
namespace {

// The 10 m pile, the 2 t ram dropped 0.8 m by hand, clay over sand.
const std::string drive_case =
    std::string(testing::driven_pile_toml) + testing::ram_toml + testing::blow_time_toml + testing::drop_toml +
    "[drive]\nperimeter = 0.9\ndepths = [3.0, 7.0]\nblow_rate = 30.0\n" + testing::clay_over_sand_toml;

// The blow at 7 m with the profile's resistances written by hand: the sand
// 0.9 x 30 kPa from the toe to x = 3, the clay 0.9 x (20 .. 10) kPa from
// x = 3 to the ground at x = 7, the toe 0.006 m2 x 8 MPa; the ram at
// sqrt(2 g 0.8 0.67).
const std::string by_hand = std::string(testing::driven_pile_toml) + R"(
[[body.shaft.profile]]
from = 0.0
to = 3.0
resistance = [27e3, 27e3]
quake = 0.003
damping = 0.164
damping_law = "viscous"
[[body.shaft.profile]]
from = 3.0
to = 7.0
resistance = [18e3, 9e3]
damping = 0.65
[near_end]
law = "smith"
ultimate = 48e3
quake = 0.004
damping = 0.492
damping_law = "viscous"
)" + testing::ram_toml + testing::blow_time_toml;

std::string text(const std::filesystem::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(Drive, EachDepthsBlowIsTheCaseWithTheProfileWrittenByHand) {
  testing::ScratchDirectory scratch("drive");
  const auto file = scratch.path() / "case.toml";
  std::ofstream(file) << drive_case;
  const DrivePlan plan(file, {});
  const auto rows = write_drive(plan, scratch.path() / "out", SweepOptions{1, false, nullptr}, false);
  ASSERT_EQ(rows.size(), 2U);
  EXPECT_DOUBLE_EQ(std::sqrt(2.0 * 9.81 * 0.8 * 0.67), 3.2428876021225284);
  const RunResult hand = run(testing::case_from(by_hand, {"body.ram.velocity=-3.2428876021225284"}));
  ASSERT_TRUE(hand.summary.blow);
  const DriveRow& r = rows[1];
  EXPECT_EQ(r.run.status, "complete") << r.run.message;
  EXPECT_NEAR(r.set, hand.summary.blow->set, 1e-12 * hand.summary.blow->set);
  EXPECT_NEAR(r.max_compression, hand.summary.blow->max_compression.value, 1e-12 * r.max_compression);
  EXPECT_NEAR(r.max_tension, hand.summary.blow->max_tension.value, 1e-12 * r.max_compression);
  EXPECT_NEAR(r.shaft, 0.9 * (3.0 * 30e3 + 4.0 * 15e3), 1e-9);
  EXPECT_DOUBLE_EQ(r.toe, 48e3);
  EXPECT_DOUBLE_EQ(r.capacity, r.shaft + r.toe);
  EXPECT_DOUBLE_EQ(r.stroke, 0.8);
  EXPECT_DOUBLE_EQ(r.blows_per_m, 1.0 / r.set);
  // The blows to get from 3 m to 7 m: trapezoidal in blows per metre.
  EXPECT_EQ(rows[0].cumulative_blows, 0.0);
  EXPECT_DOUBLE_EQ(r.cumulative_blows, 0.5 * (rows[0].blows_per_m + r.blows_per_m) * 4.0);
  const DriveTotals t = drive_totals(plan, rows);
  EXPECT_DOUBLE_EQ(t.total_blows, r.cumulative_blows);
  EXPECT_DOUBLE_EQ(t.driving_time, r.cumulative_blows / 30.0);
  EXPECT_FALSE(t.refusal_depth);
  const std::string csv = text(scratch.path() / "out" / "drive.csv");
  EXPECT_EQ(csv.substr(0, csv.find('\n')),
            "depth,shaft,toe,capacity,long_term_capacity,set,blows_per_250mm,blows_per_m,max_compression,"
            "max_tension,enthru,stroke,cumulative_blows,finished,first_set,blows_run,transfer_ratio,id,status,"
            "message,warnings");
  const std::string summary = text(scratch.path() / "out" / "summary.json");
  for (const char* key : {"\"total_blows\"", "\"driving_time\"", "\"refusal_depth\": null", "\"max_compression\""})
    EXPECT_NE(summary.find(key), std::string::npos) << key << " in " << summary;
}

TEST(Drive, TheFirstRefusedDepthEndsTheCount) {
  testing::ScratchDirectory scratch("drive-refusal");
  const auto file = scratch.path() / "case.toml";
  std::ofstream(file) << drive_case;
  const DrivePlan plan(file, {Case::Override{"drive.refusal=0.5"}});  // any blow count at all is refusal
  const auto rows = write_drive(plan, scratch.path() / "out", SweepOptions{1, false, nullptr}, false);
  const DriveTotals t = drive_totals(plan, rows);
  ASSERT_TRUE(t.refusal_depth);
  EXPECT_EQ(*t.refusal_depth, 3.0);
  EXPECT_EQ(t.total_blows, 0.0);
}

TEST(Drive, ACaseWithoutDriveIsRefused) {
  testing::ScratchDirectory scratch("drive-none");
  const auto file = scratch.path() / "case.toml";
  std::ofstream(file) << testing::pile_toml;
  EXPECT_THROW(DrivePlan(file, {}), InputError);
}

}  // namespace
}  // namespace barimpact
