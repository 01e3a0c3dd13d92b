// barimpact pda on records made by barimpact's own forward model: a gauge's
// force and velocity written as a record, with a pre-trigger baseline as an
// analyser keeps, then analysed. An impedance drop with no resistance above
// it gives Rausche and Goble's beta = Z2 / Z1 at the drop's depth; a pile in
// Smith's soil gives a Case-method RMX near its static capacity.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <fstream>

#include "../support/line_runs.hpp"
#include "../support/run_case.hpp"
#include "../support/scratch_directory.hpp"
#include "barimpact/pda/case_method.hpp"

namespace barimpact {
namespace {

using testing::case_from;
using testing::column;

// The run's gauge as a record: compression and downward velocity positive
// (the line runs up from the toe: the head's force and velocity negated),
// after 2 ms of zero samples before t = 0.
void write_record(const RunResult& r, const std::string& gauge, const std::filesystem::path& csv) {
  std::ofstream out(csv);
  out << "t,F,V\n";
  const double dt = r.history[1].t - r.history[0].t;
  const int baseline = static_cast<int>(0.002 / dt);
  for (int k = baseline; k > 0; --k) out << fmt::format("{},0,0\n", r.history[0].t - k * dt);
  for (std::size_t i = 0; i < r.history.size(); ++i)
    out << fmt::format("{},{},{}\n", r.history[i].t, -column(r, "gauge." + gauge + ".force", i),
                       -column(r, "gauge." + gauge + ".velocity", i));
}

// The run's record analysed as a uniform pile below the gauges (`pile`: its [pile] keys).
CaseMethodResult analyse_run(const RunResult& r, const std::string& pile, const std::string& extra = "") {
  EXPECT_TRUE(r.summary.complete) << r.summary.message;
  testing::ScratchDirectory dir("pda-forward");
  write_record(r, "head", dir.path() / "blow.csv");
  return analyse_pda(PileRecord::from_string(
      fmt::format("[pile]\n{}\n[record]\nfile = \"blow.csv\"\nforce = \"F\"\nvelocity = \"V\"\n{}", pile, extra),
      dir.path(), "record.toml"));
}

const char* const steel_19m = "length = 19.0\narea = 0.01\nmodulus = 210e9\ndensity = 7850.0";

// Two welded steel bars, the lower of half the upper's area (Z2 / Z1 = 0.5),
// no soil, a 2 t ram through a cushion at 3 m/s; the gauge 1 m below the
// head, the drop 9 m below the gauge.
const char* const stepped_pile = R"toml(
[[body]]
name = "lower"
length = 10.0
elements = 200
area = 0.005
modulus = 210e9
density = 7850.0
[[body]]
name = "upper"
length = 10.0
elements = 200
area = 0.01
modulus = 210e9
density = 7850.0
[[body]]
name = "ram"
kind = "mass"
mass = 2000.0
velocity = -3.0
[[joint]]
between = ["upper", "ram"]
law = "cushion"
stiffness = 2e9
restitution = 0.8
[[gauge]]
name = "head"
body = "upper"
at = 9.0
[time]
end = 0.02
step = "auto"
scheme = "central-difference"
[units]
system = "SI"
)toml";

// beta within 0.005 of Z2 / Z1 (measured 0.50002: the wave down's peak at
// t1 meets the drop smoothed by the mesh, 0.05 m elements against a pulse
// some metres long, and the wave up's least value is sampled at the run's
// steps); the depth within 0.2 m of 9 m (measured 9.03: c (t_min - t1) / 2
// with the trough of the reflection a step or two off the force's peak).
TEST(PdaForward, ImpedanceDropGivesBetaZ2OverZ1) {
  const auto a = analyse_run(run(case_from(stepped_pile)), steel_19m);
  EXPECT_NEAR(a.ratio_at_impact, 1.0, 0.05);
  EXPECT_NEAR(a.bta, 0.5, 0.005);
  ASSERT_TRUE(a.bta_depth);
  EXPECT_NEAR(*a.bta_depth, 9.0, 0.2);
  RecordProperty("bta", fmt::format("{}", a.bta));
  RecordProperty("bta_depth", fmt::format("{}", *a.bta_depth));
}

// The uniform upper bar alone (no drop) on a fixed toe: beta = 1 and no
// depth. (A free toe's reflection is a tension whose foot, below 5% of the
// peak, arrives before t2 - (t1 - t_foot), within beta's window: on such a
// pile the definition finds a drop of some percent at the toe.)
TEST(PdaForward, UniformPileIsIntact) {
  const auto a = analyse_run(run(case_from(stepped_pile, {"body.lower.area=0.01", "near_end.law=clamped"})), steel_19m);
  EXPECT_EQ(a.bta, 1.0);
  EXPECT_FALSE(a.bta_depth);
}

// The steel pipe in sand (examples/pile): 1.5 MN static capacity, toe
// damping lowered to 0.15 s/m so that Smith's damping, J_toe R_toe +
// J_shaft R_shaft = 0.15 x 900 kN + 0.16 x 600 kN, is Z J_c with J_c = 0.54
// (Z = 426 kN s/m): with J_c = 0.5 the Case method's RMX is within 30% of
// the capacity (Smith's damping grows with the soil's own resistance, the
// Case method's with the pile's impedance: they agree only roughly;
// measured 1.556 MN, 3.7% above).
TEST(PdaForward, SmithSoilRmxIsNearTheCapacity) {
  const Case c = testing::example("pile/steel-pipe-sand.toml", {"near_end.damping=0.15", "output.every=2"});
  const auto a = analyse_run(run(c), "length = 19.2\narea = 0.0105\nmodulus = 210e9\ndensity = 7850.0",
                             "[case_method]\ndamping = 0.5\n");
  EXPECT_NEAR(a.rmx, 1.5e6, 0.3 * 1.5e6);
  EXPECT_EQ(a.bta, 1.0) << "a uniform pile";
  RecordProperty("rmx", fmt::format("{}", a.rmx));
}

}  // namespace
}  // namespace barimpact
