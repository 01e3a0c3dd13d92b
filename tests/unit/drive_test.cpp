// The soil profile ([drive], [[layer]]), the shaft as pieces ([body.shaft]
// profile) and the hammer ([hammer]): reading, the rules, and the line the
// profile gives the pile at one penetration.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>

#include "../support/pile.hpp"
#include "../support/run_case.hpp"
#include "barimpact/case/drive.hpp"
#include "barimpact/case/line_builder.hpp"
#include "barimpact/run/residual.hpp"
#include "barimpact/run/simulate.hpp"

namespace barimpact {
namespace {

using testing::case_from;

// Refused with --set `set`: the message names the --set and holds every part.
#define EXPECT_SET_REFUSED(toml, set, ...)                                           \
  do {                                                                               \
    const std::string msg_ = testing::refusal(toml, {set});                          \
    for (const std::string& part_ : std::initializer_list<std::string>{__VA_ARGS__}) \
      EXPECT_NE(msg_.find(part_), std::string::npos) << msg_;                        \
  } while (0)

// The 10 m pile, the 2 t ram dropped 0.8 m by hand, clay over sand.
const std::string pile =
    std::string(testing::driven_pile_toml) + testing::ram_toml + testing::blow_time_toml + testing::drop_toml;
const std::string profile =
    std::string("[drive]\nperimeter = 0.9\ndepths = \"3:9:4\"\n") + testing::clay_over_sand_toml;

double shaft_sum(const Line& line) {
  return std::accumulate(line.shaft.ultimate.begin(), line.shaft.ultimate.end(), 0.0);
}

TEST(DriveProfile, AtAPenetrationThePileHasTheProfilesShaftAndToe) {
  const Case c = case_from(pile + profile, {"drive.depth=7.0"});
  ASSERT_TRUE(c.drive);
  const ShaftData& s = *c.bodies[0].shaft;
  // x = 7 - z: the sand from the toe up to 3 m, then the clay from 4 m depth (x = 3) to the ground (x = 7).
  ASSERT_EQ(s.profile.size(), 2U);
  EXPECT_EQ(s.profile[0].from, 0.0);
  EXPECT_EQ(s.profile[0].to, 3.0);
  EXPECT_EQ(s.profile[0].resistance_from, 0.9 * 30e3);
  EXPECT_EQ(s.profile[1].from, 3.0);
  EXPECT_EQ(s.profile[1].to, 7.0);
  EXPECT_DOUBLE_EQ(s.profile[1].resistance_from, 0.9 * 20e3);  // the clay's bottom, 4 m deep
  EXPECT_DOUBLE_EQ(s.profile[1].resistance_to, 0.9 * 10e3);    // the ground
  EXPECT_EQ(c.near_end.law, JointLaw::smith);
  EXPECT_DOUBLE_EQ(c.near_end.soil.ultimate, 0.006 * 8e6);  // toe_area: the pile's area
  EXPECT_EQ(c.near_end.soil.quake, 0.004);
  EXPECT_EQ(c.near_end.soil.damping_law, DampingLaw::viscous);
  // The nodal shares add up to the profile's integral, exactly up to round-off.
  const double shaft = 0.9 * (3.0 * 30e3 + 4.0 * 15e3);
  EXPECT_NEAR(shaft_sum(build_line(c)), shaft, 1e-12 * shaft);
  const DriveSoil soil = soil_at(*c.drive, 7.0, 0.006);
  EXPECT_NEAR(soil.shaft_capacity, shaft, 1e-12 * shaft);
  EXPECT_NEAR(soil.long_term_capacity, 0.006 * 8e6 + 0.9 * (3.0 * 30e3 + 2.0 * 4.0 * 15e3), 1e-9);
}

TEST(DriveProfile, ANodeTakesTheSoilOfTheLayerItsDepthIsIn) {
  const Case c = case_from(pile + profile, {"drive.depth=7.0"});
  const Line line = build_line(c);
  for (std::size_t j : line.shaft.nodes) {
    const double z = 7.0 - line.x[j];  // the node's depth
    const LayerData& layer = c.drive->layer_at(z);
    EXPECT_EQ(line.shaft.quake[j], layer.shaft.quake) << "node at depth " << z;
    EXPECT_EQ(line.shaft.smith[j] > 0, layer.shaft.damping_law == DampingLaw::smith) << "node at depth " << z;
  }
  // A node on the boundary (4 m deep, x = 3) belongs to the layer below it.
  const auto on = static_cast<std::size_t>(std::lround(3.0 / 0.25));
  EXPECT_EQ(line.shaft.quake[on], 0.003);
  EXPECT_GT(line.shaft.viscous[on], 0.0);
  // Nodes above the ground have no soil.
  for (std::size_t j = 0; j < line.nodes(); ++j) {
    if (line.x[j] > 7.0 + 1e-12) {
      EXPECT_EQ(line.shaft.ultimate[j], 0.0) << "x = " << line.x[j];
    }
  }
}

TEST(DriveProfile, ATopOnTheToesDepthGivesTheToeTheLayerBelow) {
  const Case c = case_from(pile + profile, {"drive.depth=4.0"});
  EXPECT_DOUBLE_EQ(c.near_end.soil.ultimate, 0.006 * 8e6);
  const Line line = build_line(c);
  EXPECT_EQ(line.shaft.quake[0], 0.003);  // the toe's node, 4 m deep: the sand's
  const DriveData& d = *c.drive;
  EXPECT_EQ(&d.layer_at(4.0), &d.layers[1]);
  EXPECT_EQ(&d.layer_at(10.0), &d.layers[1]);  // the last layer includes its bottom
}

TEST(DriveProfile, AUniformLayerIsTodaysUniformShaft) {
  const std::string uniform = pile + R"(
[drive]
perimeter = 2.0
depths = [6.0]
[[layer]]
top = 0.0
bottom = 10.0
shaft = 25e3
toe = 5e6
shaft_quake = 0.002
shaft_damping = 0.2
)";
  std::string by_hand = pile + R"(
[near_end]
law = "smith"
ultimate = 30e3
)";
  by_hand.insert(by_hand.find("[[body]]\nname = \"ram\""),
                 "[body.shaft]\nultimate = 300e3\nembedded = 6.0\nquake = 0.002\ndamping = 0.2\n");
  const Line a = build_line(case_from(uniform));
  const Line b = build_line(case_from(by_hand));
  ASSERT_EQ(a.shaft.ultimate.size(), b.shaft.ultimate.size());
  for (std::size_t j = 0; j < a.shaft.ultimate.size(); ++j) {
    EXPECT_NEAR(a.shaft.ultimate[j], b.shaft.ultimate[j], 1e-9) << j;
    EXPECT_EQ(a.shaft.quake[j], b.shaft.quake[j]) << j;
    EXPECT_EQ(a.shaft.smith[j], b.shaft.smith[j]) << j;
  }
  EXPECT_EQ(a.shaft.nodes, b.shaft.nodes);
}

TEST(DriveProfile, TheResolvedCaseSpellsTheProfileAndRunsAlike) {
  const Case c = case_from(pile + profile, {"drive.depth=5.5"});
  const Case again = case_from(c.to_toml());
  EXPECT_FALSE(again.drive) << "case.toml holds the shaft and toe themselves";
  const RunResult a = run(c), b = run(again);
  ASSERT_TRUE(a.summary.blow && b.summary.blow);
  EXPECT_EQ(a.summary.blow->set, b.summary.blow->set);
  EXPECT_EQ(a.summary.blow->max_compression.value, b.summary.blow->max_compression.value);
}

TEST(DriveProfile, RefusesABrokenProfileNamingTheKey) {
  const std::string head = pile + "[drive]\nperimeter = 1.0\ndepths = \"2:8:4\"\n";
  auto layer = [](double top, double bottom) {
    return "[[layer]]\ntop = " + std::to_string(top) + "\nbottom = " + std::to_string(bottom) +
           "\nshaft = 1e4\ntoe = 1e6\n";
  };
  EXPECT_REFUSED(head + layer(1, 10), "layer[1].top", "must be 0");
  EXPECT_REFUSED(head + layer(0, 4) + layer(5, 10), "layer[2].top", "a gap");
  EXPECT_REFUSED(head + layer(0, 4) + layer(3, 10), "layer[2].top", "an overlap");
  EXPECT_REFUSED(head + layer(0, 4) + layer(4, 6), "layer[2].bottom", "deepest penetration analysed, 8");
  EXPECT_REFUSED(head + layer(0, 4) + layer(4, 3), "layer[2].bottom", "must be below top");
  EXPECT_REFUSED(pile + "[drive]\nperimeter = 1.0\ndepths = \"2:12:4\"\n" + layer(0, 12), "drive.depths",
                 "the pile's length");
  EXPECT_REFUSED(pile + "[drive]\nperimeter = 1.0\ndepths = \"2:8\"\n" + layer(0, 10), "drive.depths", "FROM:TO:COUNT");
  EXPECT_REFUSED(pile + "[drive]\nperimeter = 1.0\ndepths = [4.0, 3.0]\n" + layer(0, 10), "drive.depths", "ascend");
  EXPECT_REFUSED(pile + "[drive]\nperimeter = 0.0\ndepths = [4.0]\n" + layer(0, 10), "drive.perimeter", "> 0");
  EXPECT_REFUSED(head + "blows = 0\n" + layer(0, 10), "drive.blows", "[1, 1000]");
  EXPECT_REFUSED(head + layer(0, 10) + "shaft_quake = -1.0\n", "layer[1].shaft_quake", "> 0");
  EXPECT_REFUSED(head + layer(0, 10) + "toe_damping = -1.0\n", "layer[1].toe_damping", ">= 0");
  EXPECT_REFUSED(head + layer(0, 10) + "damping_law = \"linear\"\n", "layer[1].damping_law", "smith or viscous");
  EXPECT_REFUSED(head + "[[layer]]\ntop = 0.0\nbottom = 10.0\nshaft = -1e4\ntoe = 1e6\n", "layer[1].shaft", ">= 0");
  EXPECT_REFUSED(head + "[[layer]]\ntop = 0.0\nbottom = 10.0\nshaft = 1e4\ntoe = -1e6\n", "layer[1].toe", ">= 0");
  EXPECT_REFUSED(head, "[drive] needs the soil as [[layer]]");
  EXPECT_REFUSED(pile + layer(0, 10), "[[layer]] needs a [drive]");
}

TEST(DriveProfile, RefusesNumbersInAnotherUnitNamingTheUnit) {
  const std::string head = pile + "[drive]\nperimeter = 1.0\ndepths = \"2:8:4\"\n";
  const std::string layer = "[[layer]]\ntop = 0.0\nbottom = 10.0\n";
  EXPECT_REFUSED(pile + "[drive]\nperimeter = 1420.0\ndepths = [4.0]\n" + layer + "shaft = 1e4\ntoe = 1e6\n",
                 "drive.perimeter", "mm?");
  EXPECT_REFUSED(head + layer + "shaft = [25.0, 50.0]\ntoe = 1e6\n", "layer[1].shaft", "kPa?");
  EXPECT_REFUSED(head + layer + "shaft = 1e4\ntoe = 6000.0\n", "layer[1].toe", "kPa?");
  EXPECT_REFUSED(head + layer + "shaft = 1e4\ntoe = 1e6\nshaft_quake = 2.5\n", "layer[1].shaft_quake", "mm?");
  EXPECT_REFUSED(head + layer + "shaft = 1e4\ntoe = 1e6\ntoe_damping = 15.0\n", "layer[1].toe_damping", "s/ft?");
  EXPECT_REFUSED(head + "toe_area = 16800.0\n" + layer + "shaft = 1e4\ntoe = 1e6\n", "drive.toe_area", "mm2?");
  EXPECT_SET_REFUSED(pile, "hammer.stroke=1200.0", "hammer.stroke", "mm?");
  // A pile alone has nothing to drive it.
  EXPECT_REFUSED(std::string(testing::driven_pile_toml) + "[drive]\nperimeter = 1.0\ndepths = [4.0]\n" + layer +
                     "shaft = 1e4\ntoe = 1e6\n",
                 "[drive] needs a hammer");
}

TEST(DriveProfile, ADrivenPileWithoutTimeRunsOnThePilesSchemeAndStableStep) {
  const std::string no_time = std::string(testing::driven_pile_toml) + testing::ram_toml + testing::drop_toml + profile;
  const Case c = case_from(no_time);
  EXPECT_EQ(c.time.scheme, "central-difference");
  EXPECT_TRUE(c.time.step_auto);
  EXPECT_LT(c.time.step, 1e-4);  // the stable step of a 0.25 m steel element, not the paper's 0.01
}

TEST(Hammer, ByHandTheRamStartsAtImpactAtTheSpeedOfItsFall) {
  const Case c = case_from(pile);
  ASSERT_TRUE(c.hammer);
  EXPECT_EQ(c.hammer->kind, HammerKind::drop);
  EXPECT_EQ(c.hammer->efficiency, 0.67);  // the drop hammer's default
  EXPECT_DOUBLE_EQ(-std::stod(c.bodies[1].velocity), std::sqrt(2.0 * 9.81 * 0.8 * 0.67));
  // [load] gravity replaces 9.81.
  const Case moon = case_from(pile, {"load.gravity=1.62"});
  EXPECT_DOUBLE_EQ(-std::stod(moon.bodies[1].velocity), std::sqrt(2.0 * 1.62 * 0.8 * 0.67));
}

TEST(Hammer, EnergyGivesTheStrokeAndGravityIsTheCases) {
  std::string by_energy = pile;
  by_energy.replace(by_energy.find("stroke = 0.8"), 12, "energy = 15696.0");
  const Case c = case_from(by_energy, {"load.gravity=9.81", "hammer.kind=hydraulic"});
  EXPECT_DOUBLE_EQ(c.hammer->stroke, 15696.0 / (2000.0 * 9.81));
  EXPECT_EQ(c.hammer->efficiency, 0.95);
}

TEST(Hammer, AModelAddsTheHelmetCapblockAndRamFromTheTable) {
  const std::string line = std::string(testing::driven_pile_toml) + R"(
[near_end]
law = "smith"
ultimate = 500e3
[hammer]
model = "Vulcan 010"
[time]
end = 0.03
step = "auto"
scheme = "central-difference"
)";
  const Case c = case_from(line);
  ASSERT_EQ(c.bodies.size(), 3U);
  EXPECT_EQ(c.bodies[1].name, "helmet");
  EXPECT_EQ(c.bodies[2].name, "ram");
  const HammerModel* m = nullptr;
  for (const auto& h : shipped_hammers())
    if (h.name == "Vulcan 010") m = &h;
  ASSERT_NE(m, nullptr);
  EXPECT_EQ(c.bodies[2].mass, m->ram_mass);
  EXPECT_EQ(c.bodies[1].mass, m->helmet_mass);
  EXPECT_DOUBLE_EQ(-std::stod(c.bodies[2].velocity), std::sqrt(2.0 * 9.81 * m->stroke * m->efficiency));
  ASSERT_EQ(c.joints.size(), 2U);
  EXPECT_EQ(c.joints[1].law.law, JointLaw::cushion);
  EXPECT_EQ(c.joints[1].law.stiffness, m->cushion_stiffness);
  const RunResult r = run(c);
  ASSERT_TRUE(r.summary.blow);
  EXPECT_TRUE(r.summary.blow->impact);
  EXPECT_GT(r.summary.blow->set, 0.0);
  // A ram in the case as well is refused, and so is an unknown model, naming the nearest.
  EXPECT_REFUSED(line + "[[body]]\nname = \"ram\"\nkind = \"mass\"\nmass = 1.0\n", "hammer.model", "\"ram\"");
  std::string typo = line;
  typo.replace(typo.find("Vulcan 010"), 10, "Vulkan 010");
  EXPECT_REFUSED(typo, "hammer.model", "Vulkan 010", "nearest: \"Vulcan 010\"");
}

TEST(Hammer, RefusesBadKeysNamingThem) {
  EXPECT_SET_REFUSED(pile, "hammer.stroke=0.0", "hammer.stroke", "> 0");
  EXPECT_SET_REFUSED(pile, "hammer.stroke=-1.0", "hammer.stroke", "> 0");
  EXPECT_SET_REFUSED(pile, "hammer.kind=steam", "hammer.kind", "drop, hydraulic, air-steam or diesel");
  EXPECT_SET_REFUSED(pile, "hammer.energy=1e4", "hammer.energy", "cannot be given with stroke");
  EXPECT_SET_REFUSED(pile, "hammer.efficiency=1.5", "hammer.efficiency", "(0, 1]");
  EXPECT_SET_REFUSED(pile, "hammer.ram=anvil", "hammer.ram", "names no body");
  EXPECT_SET_REFUSED(pile, "body.ram.velocity=-3.0", "body.ram.velocity", "set by [hammer]");
  EXPECT_SET_REFUSED(pile, "hammer.stroke=11.0", "hammer.stroke", "plausible");
}

// A diesel hammer from the table on the 10 m pile, its toe in Smith's soil.
std::string diesel_case(double toe) {
  return std::string(testing::driven_pile_toml) + "[near_end]\nlaw = \"smith\"\nultimate = " + std::to_string(toe) +
         R"(
[hammer]
model = "Delmag D19-42"
[blow]
ram = "ram"
[time]
end = 0.5
step = "auto"
scheme = "central-difference"
[output]
every = 100
)";
}

TEST(DieselHammer, AModelAddsAnvilGasAndRamAndItsGasHasTheContractsColumns) {
  const Case c = case_from(diesel_case(1e6));
  ASSERT_EQ(c.bodies.size(), 4U);
  EXPECT_EQ(c.bodies[2].name, "anvil");
  EXPECT_EQ(c.load.gravity, 9.81);  // a diesel hammer runs under gravity
  const JointData& gas = c.joints.back();
  EXPECT_EQ(gas.law.law, JointLaw::diesel);
  EXPECT_EQ(gas.column_stem(), "hammer.gas");
  EXPECT_EQ(gas.law.gap, c.hammer->diesel.compression_length);  // the ram starts at the ports
  // ... moving down at sqrt(2 g (stroke - L_c)), the first blow from max_stroke.
  EXPECT_DOUBLE_EQ(-std::stod(c.bodies[3].velocity),
                   std::sqrt(2.0 * 9.81 * (c.hammer->diesel.max_stroke - c.hammer->diesel.compression_length)));
  const RunResult r = run(c);
  for (const char* column : {"hammer.gas.pressure", "hammer.gas.force"})
    EXPECT_NE(std::find(r.columns.begin(), r.columns.end(), column), r.columns.end()) << column;
}

TEST(DieselHammer, TheStrokeSettlesOverBlowsAndRisesWithTheSoilsResistance) {
  double last = 0.0;
  for (const double toe : {0.3e6, 1.5e6}) {
    const RunResult r = run(case_from(diesel_case(toe)));
    ASSERT_TRUE(r.summary.blow);
    const BlowSummary& b = *r.summary.blow;
    EXPECT_TRUE(r.summary.warnings.empty() || r.summary.warnings[0].rfind("diesel-stroke", 0) != 0)
        << r.summary.warnings[0];
    EXPECT_GE(b.blows_run, 2);
    EXPECT_LE(b.blows_run, 20);
    const double max_stroke = case_from(diesel_case(toe)).hammer->diesel.max_stroke;
    EXPECT_LE(b.stroke, max_stroke);
    // Settled: the last blow's rebound (capped at max_stroke) is its own stroke within 1%.
    EXPECT_NEAR(std::min(b.next_stroke, max_stroke), b.stroke, 0.011 * b.stroke)
        << "toe " << toe << ": stroke " << b.stroke << ", next " << b.next_stroke;
    EXPECT_GT(b.stroke, last) << "a stiffer soil throws the ram higher";
    last = b.stroke;
  }
}

TEST(DieselHammer, ByHandItNeedsItsCylinder) {
  const std::string hand = std::string(testing::driven_pile_toml) + R"(
[time]
end = 0.5
step = "auto"
scheme = "central-difference"
[hammer]
kind = "diesel"
ram_mass = 1800.0
anvil_mass = 400.0
compression_length = 0.45
chamber_length = 0.09
combustion_pressure = 7e6
max_stroke = 3.0
)";
  EXPECT_REFUSED(hand, "hammer.cylinder_area", "required by a diesel hammer");
  EXPECT_REFUSED(hand + "cylinder_area = 0.08\nstroke = 0.3\n", "hammer.stroke", "not above the ports");
  EXPECT_REFUSED(hand + "cylinder_area = 0.08\n[[body]]\nname = \"anvil\"\nkind = \"mass\"\nmass = 1.0\n",
                 "hammer.kind", "\"anvil\"");
  const Case c = case_from(hand + "cylinder_area = 0.08\n");
  EXPECT_EQ(c.bodies.back().mass, 1800.0);
  EXPECT_EQ(c.hammer->stroke, 3.0);
}

// Residual stresses: the pile at static rest between blows, the forces it
// locks into the toe and the shaft in balance.
TEST(ResidualStress, TheLockedInForcesBalance) {
  const Case c = case_from(pile + profile, {"drive.depth=7.0"});
  const Line line = build_line(c);
  const std::size_t first = line.bodies[0].first, last = line.bodies[0].last;
  LineScheme::SoilRest rest;
  rest.u.assign(line.nodes(), 0.0);
  for (std::size_t j = first; j <= last; ++j) rest.u[j] = -0.004 - 0.002 * line.x[j] / 10.0;  // driven, compressed
  rest.shaft_slip.assign(line.nodes(), 0.0);
  for (std::size_t j = first; j <= last; ++j) rest.shaft_slip[j] = std::max(0.0, -rest.u[j] - 0.003);
  rest.c_max.assign(line.links.size(), 0.0);
  rest.c_max[0] = 0.0045;  // the toe slipped 1.5 mm past its quake's 3 mm... then 0.5 mm more
  const double capacity = c.near_end.soil.ultimate + c.bodies[0].shaft->soil.ultimate;
  const double toe = settle(line, last + 1, 0.0, rest, 1e-6 * capacity);
  EXPECT_GE(toe, 0.0);
  EXPECT_LE(toe, c.near_end.soil.ultimate);
  double shaft = 0.0;  // the shaft's forces on the pile at rest, up
  for (std::size_t j : line.shaft.nodes) {
    const double r = line.shaft.stiffness[j] * (-rest.u[j] - rest.shaft_slip[j]);
    EXPECT_LE(std::abs(r), line.shaft.ultimate[j] * (1 + 1e-12)) << j;
    shaft += r;
  }
  EXPECT_NEAR(toe + shaft, 0.0, 1e-5 * capacity) << "toe " << toe << ", shaft " << shaft;
}

TEST(ResidualStress, BlowsFromTheLastOnesRestSettle) {
  const Case one = case_from(pile + profile, {"drive.depth=7.0", "time.end=0.3"});
  const Case many = case_from(pile + profile, {"drive.depth=7.0", "time.end=0.3", "drive.blows=8"});
  const RunResult a = run(one), b = run(many);
  ASSERT_TRUE(a.summary.blow && b.summary.blow);
  const BlowSummary& r = *b.summary.blow;
  EXPECT_EQ(r.first_set, a.summary.blow->set) << "the first blow starts from rest";
  EXPECT_GE(r.blows_run, 2);
  EXPECT_LE(r.blows_run, 8);
  EXPECT_GT(r.set, 0.0);
  EXPECT_FALSE(std::isnan(r.residual_toe_force));
  EXPECT_NE(r.set, r.first_set) << "the locked-in forces change the blow";
  // A scheme that keeps no soil state is refused.
  EXPECT_THROW((void)run(case_from(pile + profile, {"drive.blows=3", "time.scheme=newmark", "time.step=1e-5"})),
               InputError);
}

TEST(HammerTable, ShipsAtLeastTwentyHammersEachWithItsSource) {
  const auto& table = shipped_hammers();
  EXPECT_GE(table.size(), 20U);
  for (const auto& h : table) {
    EXPECT_FALSE(h.source.empty()) << h.name;
    EXPECT_GT(h.ram_mass, 0.0) << h.name;
    if (h.kind == HammerKind::diesel) {
      EXPECT_GT(h.diesel.cylinder_area, 0.0) << h.name;
    }
  }
  for (auto kind : {HammerKind::drop, HammerKind::hydraulic, HammerKind::air_steam, HammerKind::diesel})
    EXPECT_TRUE(std::any_of(table.begin(), table.end(), [&](const HammerModel& h) { return h.kind == kind; }))
        << to_string(kind);
}

}  // namespace
}  // namespace barimpact
