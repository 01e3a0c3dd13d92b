// The record file's contract (record.hpp): [pile] or [[segment]], [record]'s
// channels, [case_method]; the signals made from the CSV file; and every
// refusal of a record that cannot be analysed, one line naming the file,
// column or key and the rule.
#include "barimpact/pda/record.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <vector>

#include "../support/pda_record.hpp"
#include "../support/scratch_directory.hpp"
#include "barimpact/model/input_error.hpp"

namespace barimpact {
namespace {

using testing::KnownWaves;

const char* const pile = "[pile]\nlength = 20.0\narea = 0.01\nmodulus = 200e9\ndensity = 8000.0\n";
const char* const channels = "[record]\nfile = \"blow.csv\"\nforce = [\"F1\", \"F2\"]\nvelocity = [\"V1\", \"V2\"]\n";

// The message of a record (TOML text, the known waves' CSV beside it,
// `appended` lines after its samples) that must be refused.
std::string refusal(const std::string& toml, const KnownWaves& w = {}, const std::string& appended = "") {
  testing::ScratchDirectory dir("pda-record");
  w.write(dir.path());
  std::ofstream(dir.path() / "blow.csv", std::ios::app) << appended;
  try {
    const auto rec = PileRecord::from_string(toml, dir.path(), "record.toml");
    (void)read_pile_signals(rec);
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;
    return what;
  }
  ADD_FAILURE() << "accepted: " << toml;
  return "";
}

#define EXPECT_RECORD_REFUSED(message, ...)                                          \
  do {                                                                               \
    const std::string msg_ = (message);                                              \
    for (const std::string& part_ : std::initializer_list<std::string>{__VA_ARGS__}) \
      EXPECT_NE(msg_.find(part_), std::string::npos) << msg_;                        \
  } while (0)

TEST(PileRecord, ReadsAUniformPileAndItsChannels) {
  const auto r = PileRecord::from_string(std::string(pile) + channels, "/data", "record.toml");
  ASSERT_EQ(r.segments.size(), 1u);
  EXPECT_DOUBLE_EQ(r.segments[0].wave_speed, 5000.0);
  EXPECT_DOUBLE_EQ(r.impedance(), 4e5);
  EXPECT_DOUBLE_EQ(r.travel_time(), 0.008);
  EXPECT_EQ(r.csv, std::filesystem::path("/data/blow.csv"));
  EXPECT_EQ(r.damping, 0.5);
  EXPECT_FALSE(r.strain);
  EXPECT_FALSE(r.acceleration);
}

// A given wave speed sets Z = E A / c and the density E / c^2.
TEST(PileRecord, WaveSpeedGivenSetsImpedance) {
  const auto r = PileRecord::from_string(std::string(pile) + "wave_speed = 4000.0\n" + channels, ".", "r");
  EXPECT_DOUBLE_EQ(r.impedance(), 200e9 * 0.01 / 4000.0);
  EXPECT_DOUBLE_EQ(r.segments[0].density, 200e9 / 16e6);
}

// [[segment]] from the gauges down: travel times add up, depths invert them.
TEST(PileRecord, SegmentsAddTravelTimes) {
  const auto r = PileRecord::from_string(std::string("[pile]\nlength = 30.0\n") +
                                             "[[segment]]\nlength = 10.0\narea = 0.02\nmodulus = 200e9\ndensity = "
                                             "8000.0\n[[segment]]\nlength = 20.0\narea = 0.01\nmodulus = 50e9\n"
                                             "density = 2000.0\n" +
                                             channels,
                                         ".", "r");
  ASSERT_EQ(r.segments.size(), 2u);
  EXPECT_DOUBLE_EQ(r.length(), 30.0);
  EXPECT_DOUBLE_EQ(r.travel_time(), 2.0 * 10.0 / 5000.0 + 2.0 * 20.0 / 5000.0);
  EXPECT_DOUBLE_EQ(r.impedance(), 200e9 * 0.02 / 5000.0);
  EXPECT_DOUBLE_EQ(r.depth_at(r.two_way_time(17.0)), 17.0);
  EXPECT_EQ(r.segment_at(10.0).area, 0.02);
  EXPECT_EQ(r.segment_at(10.5).area, 0.01);
}

// Strain times E A at the gauges makes the force; acceleration, its offset
// removed (the mean of the baseline), integrated by the trapezoid rule from
// the first sample makes the velocity (here exact to rounding against the
// same rule applied to the samples without offset).
TEST(PileRecord, StrainAndAccelerationMakeForceAndVelocity) {
  const KnownWaves w;
  testing::ScratchDirectory dir("pda-strain");
  std::vector<double> a(w.samples);
  const double ea = w.modulus * w.area, h = 1e-7;
  {
    std::ofstream csv(dir.path() / "blow.csv");
    csv << "t,S,A\n";
    for (int k = 0; k < w.samples; ++k) {
      const double t = w.t(k);
      a[k] = (w.velocity(t + h) - w.velocity(t - h)) / (2 * h);
      csv << fmt::format("{},{},{}\n", t, w.force(t) / ea, a[k] + 50.0);
    }
  }
  const auto rec = PileRecord::from_string(
      std::string(pile) + "[record]\nfile = \"blow.csv\"\nstrain = \"S\"\nacceleration = \"A\"\n", dir.path(), "r");
  const auto s = read_pile_signals(rec);
  double v = 0.0;
  for (int k = 0; k < w.samples; ++k) {
    if (k > 0) v += 0.5 * (a[k - 1] + a[k]) * w.dt;
    EXPECT_NEAR(s.force[k], w.force(w.t(k)), 1e-9 * w.peak) << k;
    EXPECT_NEAR(s.velocity[k], v, 1e-9 * w.peak / w.impedance()) << k;
  }
}

TEST(PileRecord, RefusesBadKeys) {
  EXPECT_RECORD_REFUSED(refusal(std::string(pile) + "colour = 1\n" + channels), "record.toml:6", "pile.colour");
  EXPECT_RECORD_REFUSED(refusal(channels), "[pile] is missing");
  EXPECT_RECORD_REFUSED(refusal("[pile]\nlength = 20.0\narea = 0.01\nmodulus = 200e9\n" + std::string(channels)),
                        "pile.density is missing");
  EXPECT_RECORD_REFUSED(
      refusal("[pile]\nlength = 20.0\narea = -0.01\nmodulus = 200e9\ndensity = 8000.0\n" + std::string(channels)),
      "record.toml:3", "pile.area must be > 0");
  EXPECT_RECORD_REFUSED(refusal(std::string(pile) + "[record]\nfile = \"blow.csv\"\nforce = \"F1\"\nstrain = \"F2\"\n"
                                                    "velocity = \"V1\"\n"),
                        "record.strain and force both given");
  EXPECT_RECORD_REFUSED(refusal(std::string(pile) + "[record]\nfile = \"blow.csv\"\nforce = \"F1\"\n"),
                        "record.velocity is missing");
  EXPECT_RECORD_REFUSED(refusal(std::string(pile) + "[record]\nfile = \"blow.csv\"\nforce = \"F1\"\nvelocity = "
                                                    "\"V1\"\nacceleration = \"V2\"\n"),
                        "record.acceleration and velocity both given");
  EXPECT_RECORD_REFUSED(refusal(std::string(pile) + channels + "[case_method]\ndamping = 1.5\n"),
                        "case_method.damping must be in [0, 1]");
  EXPECT_RECORD_REFUSED(refusal("[pile]\nlength = 25.0\n[[segment]]\nlength = 20.0\narea = 0.01\nmodulus = 200e9\n"
                                "density = 8000.0\n[[segment]]\nlength = 4.0\narea = 0.01\nmodulus = 200e9\n"
                                "wind = 3\n" +
                                std::string(channels)),
                        "record.toml:12", "segment[2].wind");
  EXPECT_RECORD_REFUSED(refusal("[pile]\nlength = 25.0\n[[segment]]\nlength = 20.0\narea = 0.01\nmodulus = 200e9\n"
                                "density = 8000.0\n" +
                                std::string(channels)),
                        "pile.length = 25 m, but the segments' lengths add up to 20 m");
}

// [match]: signal matching's keys, their defaults and rules.
TEST(PileRecord, ReadsMatchSettings) {
  testing::ScratchDirectory dir("pda-match");
  KnownWaves{}.write(dir.path());
  const auto defaults = PileRecord::from_string(std::string(pile) + channels, dir.path()).match;
  EXPECT_EQ(defaults.segments, 10);
  EXPECT_FALSE(defaults.embedded);
  EXPECT_FALSE(defaults.window);
  EXPECT_EQ(defaults.damping_law, DampingLaw::smith);
  EXPECT_EQ(defaults.unknowns, MatchSettings::all_unknowns());
  EXPECT_EQ(defaults.starts, 4);
  const auto m = PileRecord::from_string(std::string(pile) + channels +
                                             "[match]\nsegments = 6\nembedded = 18.0\nwindow = 0.01\n"
                                             "damping_law = \"viscous\"\nunknowns = [\"shaft\", \"toe\"]\n"
                                             "toe_quake = 0.004\nshaft_damping = 0.3\nstarts = 2\nlow_pass = 0\n"
                                             "smoothing = 0\n",
                                         dir.path())
                     .match;
  EXPECT_EQ(m.segments, 6);
  EXPECT_EQ(m.embedded, 18.0);
  EXPECT_EQ(m.window, 0.01);
  EXPECT_EQ(m.damping_law, DampingLaw::viscous);
  EXPECT_TRUE(m.fits("toe"));
  EXPECT_FALSE(m.fits("toe_quake"));
  EXPECT_EQ(m.toe_quake, 0.004);
  EXPECT_EQ(m.shaft_damping, 0.3);
  EXPECT_EQ(m.starts, 2);
  EXPECT_EQ(m.low_pass, 0.0);
  EXPECT_EQ(m.smoothing, 0.0);
}

// The match's low-pass: at the cutoff asked, or a quarter of the sampling
// rate when lower (the known waves' 10 kHz: 2.5 kHz), zero phase (the
// half-sine's peak stays at its time); none on an unevenly sampled record,
// which says why.
TEST(PileRecord, LowPassesAtAQuarterOfTheSamplingRateAtMost) {
  testing::ScratchDirectory dir("pda-filter");
  const KnownWaves w;
  w.write(dir.path());
  const auto rec = PileRecord::from_string(std::string(pile) + channels, dir.path());
  const PileSignals raw = read_pile_signals(rec);
  const PileSignals s = read_pile_signals(rec, 5000.0);
  EXPECT_FALSE(raw.filtered);
  EXPECT_TRUE(s.filtered);
  EXPECT_NEAR(s.cutoff, 2500.0, 1e-6);
  EXPECT_EQ(s.impact, raw.impact) << "zero phase: the force's first peak stays at its sample";
  EXPECT_TRUE(read_pile_signals(rec, 1000.0).cutoff == 1000.0);
  std::ofstream(dir.path() / "blow.csv", std::ios::app) << "0.04005,0,0,0,0\n";
  const PileSignals uneven = read_pile_signals(rec, 5000.0);
  EXPECT_FALSE(uneven.filtered);
  EXPECT_NE(uneven.filter_note.find("not evenly spaced"), std::string::npos) << uneven.filter_note;
}

TEST(PileRecord, RefusesBadMatchSettings) {
  const std::string base = std::string(pile) + channels + "[match]\n";
  EXPECT_RECORD_REFUSED(refusal(base + "segments = 0\n"), "match.segments must be a whole number in [1, 50]");
  EXPECT_RECORD_REFUSED(refusal(base + "segments = 2.5\n"), "match.segments");
  EXPECT_RECORD_REFUSED(refusal(base + "embedded = 21\n"), "match.embedded must be in (0, 20] m");
  EXPECT_RECORD_REFUSED(refusal(base + "window = -1\n"), "match.window must be > 0");
  EXPECT_RECORD_REFUSED(refusal(base + "damping_law = \"coulomb\"\n"), "match.damping_law", "coulomb");
  EXPECT_RECORD_REFUSED(refusal(base + "unknowns = [\"shaft\", \"skin\"]\n"), "match.unknowns names \"skin\"");
  EXPECT_RECORD_REFUSED(refusal(base + "unknowns = [\"toe\", \"toe\"]\n"), "names \"toe\" twice");
  EXPECT_RECORD_REFUSED(refusal(base + "toe_quake = 0.02\n"), "match.toe_quake must be in [0.0005, 0.015]");
  EXPECT_RECORD_REFUSED(refusal(base + "shaft_damping = 3\n"), "match.shaft_damping must be in [0, 2.5]");
  EXPECT_RECORD_REFUSED(refusal(base + "starts = 0\n"), "match.starts");
  EXPECT_RECORD_REFUSED(refusal(base + "low_pass = -5\n"), "match.low_pass must be >= 0");
  EXPECT_RECORD_REFUSED(refusal(base + "colour = 1\n"), "match.colour");
}

TEST(PileRecord, RefusesBadFiles) {
  EXPECT_RECORD_REFUSED(
      refusal(std::string(pile) + "[record]\nfile = \"none.csv\"\nforce = \"F1\"\nvelocity = \"V1\"\n"),
      "none.csv cannot be read");
  EXPECT_RECORD_REFUSED(
      refusal(std::string(pile) + "[record]\nfile = \"blow.csv\"\nforce = \"F3\"\nvelocity = \"V1\"\n"), "blow.csv:1",
      "force: no column \"F3\"");
  EXPECT_RECORD_REFUSED(refusal(std::string(pile) + channels, {}, "0.05,1,x,0,0\n"),
                        "blow.csv:402: record: column \"F2\" holds \"x\", not a finite number");
}

// Time not increasing, no impact, too short, too late, bending, F and Z v apart.
TEST(PileRecord, RefusesRecordsThatCannotBeAnalysed) {
  const std::string toml = std::string(pile) + channels;
  KnownWaves w;
  w.peak = -2e6;  // tension only, no reflections, no offsets
  w.drop = w.toe = w.late = w.force_offset = 0.0;
  EXPECT_RECORD_REFUSED(refusal(toml, w), "blow.csv: record: no impact");
  w = {};
  w.start = -0.0005;  // the blow under way at the first sample
  EXPECT_RECORD_REFUSED(refusal(toml, w), "record: no impact", "above 5% of its peak from the first sample");
  w = {};
  w.samples = 105;  // to 10.4 ms, t2 = 11 ms
  EXPECT_RECORD_REFUSED(refusal(toml, w), "record: ends at t = 0.0104", "before t2 = t1 + 2L/c = 0.011");
  w = {};
  w.start = 0.0003;  // the foot at 0.4 ms, the rise 0.9 ms
  EXPECT_RECORD_REFUSED(refusal(toml, w), "record: starts too late for the offsets: 0 samples");
  w = {};
  w.drop = 0.0;
  EXPECT_RECORD_REFUSED(refusal(std::string(pile) + "[record]\nfile = \"blow.csv\"\nforce = [\"F1\", \"V1\"]\n"
                                                    "velocity = \"V2\"\n",
                                w),
                        "force channels \"F1\" and \"V1\" differ at t1 = 0.003 s", "bending");
  EXPECT_RECORD_REFUSED(refusal(std::string("[pile]\nlength = 20.0\narea = 0.01\nmodulus = 200e9\ndensity = 8000.0\n"
                                            "wave_speed = 2500.0\n") +
                                channels),
                        "force and velocity disagree at impact: F / (Z v) = 0.5 at t1 = 0.003 s");
  EXPECT_RECORD_REFUSED(refusal(toml, {}, "0.0399,0,0,0,0\n"),
                        "blow.csv:402: record: time column \"t\" is not increasing");
}

TEST(PileRecord, InputsAreTheRecordAndItsFile) {
  const auto r = PileRecord::from_string(std::string(pile) + channels, "/data", "record.toml");
  const auto in = pda_inputs(r);
  ASSERT_EQ(in.files.size(), 1u);
  EXPECT_EQ(in.files[0], std::filesystem::path("/data/blow.csv"));
}

}  // namespace
}  // namespace barimpact
