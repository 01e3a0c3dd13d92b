// [units] system = "US" and values with units: a display system over SI
// numbers, and suffixes read into SI where the case is read.
#include <gtest/gtest.h>

#include <string>
#include <tuple>
#include <vector>

#include "../support/run_case.hpp"
#include "barimpact/case/case.hpp"
#include "barimpact/case/units.hpp"
#include "barimpact/run/output.hpp"

namespace barimpact {
namespace {

using testing::case_from;
using testing::example;

// A short blow of the steel pipe example (the stress wave's first passes).
const std::vector<std::string> short_blow{"time.end=0.02", "output.fields_at=[]"};

std::vector<std::string> with(std::vector<std::string> sets) {
  sets.insert(sets.end(), short_blow.begin(), short_blow.end());
  return sets;
}

// Metric suffixes shift the number's decimal exponent: "2.5 mm" is the same
// double as 0.0025, so the kN/mm/MPa case is the SI case bit for bit.
const std::vector<std::string> metric_twin{"body.pile.length=\"20 m\"",
                                           "body.pile.area=\"105 cm2\"",
                                           "body.pile.modulus=\"210 GPa\"",
                                           "body.pile.density=\"7.85 t/m3\"",
                                           "body.pile.shaft.ultimate=\"600 kN\"",
                                           "body.pile.shaft.embedded=\"18000 mm\"",
                                           "body.pile.shaft.quake=\"2.5 mm\"",
                                           "body.pile.shaft.damping=\"160 ms/m\"",
                                           "body.helmet.mass=\"0.8 t\"",
                                           "body.ram.mass=\"4 t\"",
                                           "body.ram.velocity=\"-4.43 m/s\"",
                                           "joint.pile-cushion.stiffness=\"5000 kN/mm\"",
                                           "joint.capblock.stiffness=\"1500 MN/m\"",
                                           "near_end.ultimate=\"900 kN\"",
                                           "near_end.quake=\"2.5 mm\"",
                                           "near_end.damping=\"0.5 s/m\"",
                                           "gauge.head.at=\"19200 mm\""};

TEST(Units, AKilonewtonMillimetreCaseIsItsSITwinBitForBit) {
  const Case si = example("pile/steel-pipe-sand.toml", short_blow);
  const Case metric = example("pile/steel-pipe-sand.toml", with(metric_twin));
  EXPECT_EQ(metric.to_toml(), si.to_toml());  // every number the same double
  const RunResult a = run(si), b = run(metric);
  ASSERT_TRUE(a.summary.blow && b.summary.blow);
  EXPECT_EQ(a.summary.blow->set, b.summary.blow->set);
  EXPECT_EQ(a.summary.blow->max_compression.value, b.summary.blow->max_compression.value);
  EXPECT_EQ(a.summary.blow->enthru, b.summary.blow->enthru);
}

// US customary units multiply by their exact factors (the international foot
// and pound): one rounding, so 1e-15 rather than bit for bit.
TEST(Units, USCustomaryUnitsAreReadWithTheirExactFactors) {
  const Case us =
      example("pile/steel-pipe-sand.toml",
              with({"body.pile.length=\"70 ft\"", "near_end.ultimate=\"200 kip\"", "near_end.quake=\"0.1 in\"",
                    "body.pile.modulus=\"29000 ksi\"", "near_end.damping=\"0.15 s/ft\"", "body.helmet.mass=\"2000 lb\"",
                    "body.pile.area=\"16 in2\"", "body.ram.velocity=\"-15 ft/s\"",
                    "joint.capblock.stiffness=\"10000 kip/in\"", "gauge.head.at=\"9 ft\""}));
  const BodyData& pile = us.bodies.front();
  EXPECT_DOUBLE_EQ(pile.length, 70 * 0.3048);
  EXPECT_DOUBLE_EQ(us.near_end.soil.ultimate, 200 * 4448.2216152605);
  EXPECT_DOUBLE_EQ(us.near_end.soil.quake, 0.00254);
  EXPECT_DOUBLE_EQ(pile.modulus, 29000 * 4448.2216152605 / (0.0254 * 0.0254));
  EXPECT_DOUBLE_EQ(us.near_end.soil.damping, 0.15 / 0.3048);
  EXPECT_DOUBLE_EQ(us.bodies[1].mass, 2000 * 0.45359237);
  EXPECT_DOUBLE_EQ(pile.area, 16 * 0.0254 * 0.0254);
  EXPECT_DOUBLE_EQ(std::stod(us.bodies[2].velocity), -15 * 0.3048);
  EXPECT_DOUBLE_EQ(us.joints[1].law.stiffness, 10000 * 4448.2216152605 / 0.0254);
  EXPECT_DOUBLE_EQ(us.gauges.front().at, 9 * 0.3048);
  // The resolved case holds the SI numbers, read back as they were.
  EXPECT_EQ(Case::from_string(us.to_toml(), {}, "again").to_toml(), us.to_toml());
}

// A velocity is an expression: only a number then a known unit is a suffix.
TEST(Units, AVelocityExpressionIsStillAnExpression) {
  for (const char* v : {"-4.43", "-4.43*(1 + 0*x)"}) {
    const Case c = example("pile/steel-pipe-sand.toml", with({fmt::format("body.pile.velocity=\"{}\"", v)}));
    EXPECT_EQ(c.bodies.front().velocity, v);
  }
  const Case bar = case_from("[[body]]\nname = \"b\"\nvelocity = \"2 ft/s\"\n");
  EXPECT_EQ(std::stod(bar.bodies.front().velocity), 2 * 0.3048);
}

TEST(Units, AUnitOfAnotherDimensionOrNoneKnownIsRefusedNamingTheKey) {
  const auto refused = [](const std::string& set) -> std::string {
    try {
      (void)example("pile/steel-pipe-sand.toml", with({set}));
    } catch (const InputError& e) {
      const std::string what = e.what();
      EXPECT_EQ(what.find('\n'), std::string::npos) << "one line: " << what;
      return what;
    }
    ADD_FAILURE() << "accepted: " << set;
    return "";
  };
  EXPECT_NE(refused("near_end.ultimate=\"900 kPa\"")
                .find("near_end.ultimate = \"900 kPa\": kPa is a stress; a force: N, kN, MN, lbf, kip"),
            std::string::npos);
  EXPECT_NE(refused("near_end.quake=\"2.5 furlong\"").find("\"furlong\" is no unit known; a length: m, cm, mm, in, ft"),
            std::string::npos);
  EXPECT_NE(refused("near_end.ultimate=\"900e3\"").find("near_end.ultimate = \"900e3\": no unit given; a force"),
            std::string::npos);
  EXPECT_NE(refused("body.ram.velocity=\"4 kN\"").find("body.ram.velocity = \"4 kN\": kN is a force; a velocity"),
            std::string::npos);
  EXPECT_NE(refused("body.pile.modulus=\"inf GPa\"").find("must be a finite number"), std::string::npos);
}

// "US" is a display: the case's numbers stay SI, the console converts them.
TEST(Units, TheConsoleUnderUSPrintsKipInchKsiAndBlowsPerFoot) {
  const Case si = example("pile/steel-pipe-sand.toml", {"time.end=0.1", "output.fields_at=[]"});
  const Case us = example("pile/steel-pipe-sand.toml", {"time.end=0.1", "output.fields_at=[]", "units.system=US"});
  EXPECT_EQ(us.units, "US");
  const RunResult r = run(si);
  const std::string text = summary_text(us, r.summary);
  for (const char* unit : {" in (", " blows/ft)", " ksi", " kip-ft", " kip\n"})
    EXPECT_NE(text.find(unit), std::string::npos) << unit << text;
  for (const char* unit : {" mm", " MPa", " J ", "250 mm"})
    EXPECT_EQ(text.find(unit), std::string::npos) << unit << text;
  const BlowSummary& b = *r.summary.blow;
  EXPECT_NE(text.find(fmt::format("set {:.4g} in ({:.3g} blows/ft)", b.set / 0.0254, b.blows_per_m() * 0.3048)),
            std::string::npos)
      << text;
  const std::string json = summary_json(us, r.summary);
  for (const char* part : {"\"system\": \"US\"", "\"numbers\": \"SI\"", "\"stress\": \"Pa\"", "\"stress\": \"ksi\"",
                           "\"blow_count\": \"blows/ft\""})
    EXPECT_NE(json.find(part), std::string::npos) << part << json;
}

// The US example is the SI example's case to 7 digits: its blow to about
// 1e-7, except what the head gauge measures (ENTHRU): 19.2 m is a node of
// the SI pile, where the gauge's element is a matter of the last bit, and
// 62.99213 ft lies 1.2 um above it (5e-5).
TEST(Units, TheUSExampleIsTheSIExampleTo7Digits) {
  const RunResult a = run(example("pile/steel-pipe-sand.toml")), b = run(example("pile/steel-pipe-sand-us.toml"));
  ASSERT_TRUE(a.summary.blow && b.summary.blow);
  const BlowSummary &si = *a.summary.blow, &us = *b.summary.blow;
  for (const auto& [what, x, y] : {std::tuple{"set", si.set, us.set},
                                   {"max compression", si.max_compression.value, us.max_compression.value},
                                   {"max tension", si.max_tension.value, us.max_tension.value},
                                   {"hammer energy", si.hammer_energy, us.hammer_energy},
                                   {"rest time", si.rest_time, us.rest_time}})
    EXPECT_NEAR(y / x, 1.0, 1e-6) << what;
  EXPECT_NEAR(us.enthru / si.enthru, 1.0, 1e-4);
}

}  // namespace
}  // namespace barimpact
