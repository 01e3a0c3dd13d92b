// Signal matching (study/match.hpp): its forward model against d'Alembert's
// solution, its static load test against the closed form of s_C, and the
// fit on records made by barimpact's own forward blow (a pile of known soil),
// clean and with noise.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <cmath>
#include <fstream>
#include <numbers>
#include <random>

#include "../support/line_runs.hpp"
#include "../support/run_case.hpp"
#include "../support/scratch_directory.hpp"
#include "barimpact/run/simulate.hpp"
#include "barimpact/study/match.hpp"

namespace barimpact {
namespace {

using testing::column;

// A uniform pile (c = 5000 m/s, Z = 4e5 N s/m, 2L/c = 8 ms) with a free toe,
// driven at the gauges by a smooth velocity pulse v = V sin^2 of `width` s: the
// force there is d'Alembert's, F(t) = Z (v(t) + 2 sum_k (-1)^k v(t - 2kL/c)).
struct FreePile {
  double length = 20.0, area = 0.01, modulus = 200e9, density = 8000.0;
  double peak = 4.0, start = 0.002, width = 0.002, dt = 2e-5, end = 0.03;
  [[nodiscard]] double c() const { return std::sqrt(modulus / density); }
  [[nodiscard]] double z() const { return modulus * area / c(); }
  [[nodiscard]] double v(double t) const {
    const double s = (t - start) / width;
    return s > 0.0 && s < 1.0 ? peak * std::pow(std::sin(std::numbers::pi * s), 2) : 0.0;
  }
  [[nodiscard]] double force(double t) const {
    double f = v(t);
    for (int k = 1; k * 2.0 * length / c() < t; ++k) f += 2.0 * (k % 2 ? -1.0 : 1.0) * v(t - k * 2.0 * length / c());
    return z() * f;
  }
  [[nodiscard]] PileRecord record(const std::filesystem::path& dir) const {
    std::ofstream csv(dir / "blow.csv");
    csv << "t,F,V\n";
    for (int k = 0; k * dt <= end; ++k) csv << fmt::format("{},{},{}\n", k * dt, force(k * dt), v(k * dt));
    csv.close();
    return PileRecord::from_string(
        fmt::format("[pile]\nlength = {}\narea = {}\nmodulus = {}\ndensity = {}\n[record]\nfile = \"blow.csv\"\n"
                    "force = \"F\"\nvelocity = \"V\"\n",
                    length, area, modulus, density),
        dir, "record.toml");
  }
};

// The largest |F - F_exact| over the record, over Z v's peak, with no soil.
double free_pile_error(const FreePile& p) {
  testing::ScratchDirectory dir("match-free");
  const PileRecord rec = p.record(dir.path());
  const PileSignals sig = read_pile_signals(rec);
  const MatchModel model(rec, sig, 0.0, sig.t.back());
  MatchSoil none;
  none.shaft.assign(model.segments(), 0.0);
  std::vector<double> f(sig.t.size());
  EXPECT_TRUE(model.head_force(none, 0, f));
  double worst = 0.0;
  for (std::size_t k = 0; k < f.size(); ++k) worst = std::max(worst, std::abs(f[k] - p.force(sig.t[k])));
  return worst / (p.z() * p.peak);
}

// Central differences at 0.9 of the stable step on 0.2 m elements: the
// error is the mesh's dispersion, second order in h over the pulse's length
// (measured 2.2% of Z V for a 2 ms pulse, 10 m long, after three round
// trips of the wave, and 3.85 times less for 4 ms: order 1.94).
TEST(MatchModel, FreePileIsDAlembert) {
  FreePile p;
  const double coarse = free_pile_error(p);
  p.width = 0.004;
  const double fine = free_pile_error(p);
  EXPECT_LT(coarse, 0.03);
  const double order = std::log2(coarse / fine);
  EXPECT_NEAR(order, 2.0, 0.3) << coarse << " " << fine;
  RecordProperty("error_2ms", fmt::format("{}", coarse));
  RecordProperty("order", fmt::format("{}", order));
}

// The same pile written as two [[segment]]s of its properties is the same
// line (the elements no longer than L / 100 fall on the same nodes): the
// same force at the gauges under the same soil, to round-off (the joint's
// node is stepped by the general row, the others by the stretch's).
TEST(MatchModel, SegmentsOfOneSectionAreTheUniformPile) {
  testing::ScratchDirectory dir("match-segments");
  const FreePile p;
  const PileRecord uniform = p.record(dir.path());
  const PileRecord two = PileRecord::from_string(
      fmt::format("[[segment]]\nlength = 12.0\narea = {0}\nmodulus = {1}\ndensity = {2}\n[[segment]]\nlength = 8.0\n"
                  "area = {0}\nmodulus = {1}\ndensity = {2}\n[record]\nfile = \"blow.csv\"\nforce = \"F\"\n"
                  "velocity = \"V\"\n",
                  p.area, p.modulus, p.density),
      dir.path(), "record.toml");
  const PileSignals sig = read_pile_signals(uniform);
  const MatchModel a(uniform, sig, 0.0, sig.t.back()), b(two, sig, 0.0, sig.t.back());
  ASSERT_EQ(a.line().x.size(), b.line().x.size());
  MatchSoil s;
  s.shaft.assign(a.segments(), 30e3);
  s.toe = 500e3;
  std::vector<double> fa(sig.t.size()), fb(sig.t.size());
  ASSERT_TRUE(a.head_force(s, 0, fa));
  ASSERT_TRUE(b.head_force(s, 0, fb));
  for (std::size_t k = 0; k < fa.size(); ++k) ASSERT_NEAR(fa[k], fb[k], 1e-9 * p.z() * p.peak) << k;
}

// A pile whose area halves 12 m below the gauges (r = (Z2 - Z1) / (Z2 + Z1)
// = -1/3): until the step's second echo (2 T1 = 9.6 ms) and the toe's
// (T1 + 2 L2 / c = 8 ms), F(t) = Z1 (v(t) + 2 r v(t - T1)), T1 = 2 L1 / c.
// Measured: 0.31% of Z1 V (the mesh's dispersion, as above).
TEST(MatchModel, AnImpedanceStepReflectsAsDAlembertSays) {
  testing::ScratchDirectory dir("match-step");
  const FreePile p;
  (void)p.record(dir.path());  // blow.csv: the uniform pile's record; only its velocity drives this one
  const PileRecord stepped = PileRecord::from_string(
      fmt::format("[[segment]]\nlength = 12.0\narea = {0}\nmodulus = {1}\ndensity = {2}\n[[segment]]\nlength = 8.0\n"
                  "area = {3}\nmodulus = {1}\ndensity = {2}\n[record]\nfile = \"blow.csv\"\nforce = \"F\"\n"
                  "velocity = \"V\"\n",
                  p.area, p.modulus, p.density, 0.5 * p.area),
      dir.path(), "record.toml");
  const PileSignals sig = read_pile_signals(stepped);
  const MatchModel model(stepped, sig, 0.0, sig.t.back());
  MatchSoil none;
  none.shaft.assign(model.segments(), 0.0);
  std::vector<double> f(sig.t.size());
  ASSERT_TRUE(model.head_force(none, 0, f));
  const double t1 = 2.0 * 12.0 / p.c(), r = -1.0 / 3.0;
  double worst = 0.0;
  for (std::size_t k = 0; sig.t[k] < 0.0079; ++k)
    worst = std::max(worst, std::abs(f[k] - p.z() * (p.v(sig.t[k]) + 2.0 * r * p.v(sig.t[k] - t1))));
  EXPECT_LT(worst / (p.z() * p.peak), 0.01);
  RecordProperty("error", fmt::format("{}", worst / (p.z() * p.peak)));
}

// The static load test on a uniform pile: the load reaches the capacity at
// s_C = max(q_toe, q_shaft) + (R_toe L + sum R_i z_i) / (E A) exactly (the
// elements' nodal forces carry the segments' uniform loads exactly), stays
// below it just before and equals it beyond.
TEST(MatchModel, StaticLoadTestReachesTheCapacityAtSc) {
  testing::ScratchDirectory dir("match-static");
  FreePile p;
  const PileRecord rec = p.record(dir.path());
  const PileSignals sig = read_pile_signals(rec);
  const MatchModel model(rec, sig, 0.0, sig.t.back());
  MatchSoil s;
  s.shaft.assign(model.segments(), 0.0);
  double moment = 0.0;
  for (std::size_t i = 0; i < s.shaft.size(); ++i) {
    s.shaft[i] = 20e3 * static_cast<double>(i + 1);
    moment += s.shaft[i] * 0.5 * (model.segment_top(i) + model.segment_bottom(i));
  }
  s.toe = 700e3;
  s.shaft_quake = 0.003;
  s.toe_quake = 0.002;
  const StaticTest t = static_load_test(model, s);
  const double s_c = 0.003 + (s.toe * p.length + moment) / (p.modulus * p.area);
  EXPECT_NEAR(t.s_c, s_c, 1e-12 * s_c);
  ASSERT_EQ(t.settlement.size(), 151u);
  EXPECT_NEAR(t.settlement[100], s_c, 1e-12 * s_c);
  EXPECT_NEAR(t.load[100], s.capacity(), 1e-9 * s.capacity());
  EXPECT_LT(t.load[99], s.capacity() * (1 - 1e-6));
  EXPECT_NEAR(t.load.back(), s.capacity(), 1e-9 * s.capacity());
  for (std::size_t i = 1; i < t.load.size(); ++i) EXPECT_GE(t.load[i], t.load[i - 1]);
}

// The steel pipe in sand (examples/pile): 600 kN on the shaft, triangular
// over its 18 m in the sand, 900 kN at the toe, quakes 2.5 mm, dampings 0.16
// and 0.15 s/m, its gauge 19.2 m above the toe. Its blow's gauge written as
// a record (two force and two velocity channels, after 2 ms of baseline),
// each channel with white noise of `noise` times its peak and the velocity
// channels scaled by `velocity_scale`.
PileRecord steel_pipe_record(const std::filesystem::path& dir, double noise, double velocity_scale,
                             const std::vector<std::string>& sets = {}, const std::string& match = "embedded = 18.0",
                             std::size_t stride = 1) {
  std::vector<std::string> all{"near_end.damping=0.15", "time.end=0.04", "output.every=1"};
  all.insert(all.end(), sets.begin(), sets.end());
  const Case c = testing::example("pile/steel-pipe-sand.toml", all);
  const RunResult r = run(c);
  EXPECT_TRUE(r.summary.complete) << r.summary.message;
  std::vector<double> t, f, v;
  const double dt = r.history[1].t - r.history[0].t;
  for (int k = static_cast<int>(0.002 / dt); k > 0; --k) {
    t.push_back(r.history[0].t - k * dt);
    f.push_back(0.0);
    v.push_back(0.0);
  }
  double fmax = 0.0, vmax = 0.0;
  for (std::size_t i = 0; i < r.history.size(); ++i) {
    t.push_back(r.history[i].t);
    f.push_back(-column(r, "gauge.head.force", i));
    v.push_back(-column(r, "gauge.head.velocity", i));
    fmax = std::max(fmax, std::abs(f.back()));
    vmax = std::max(vmax, std::abs(v.back()));
  }
  std::mt19937_64 random(20261128);
  std::normal_distribution<double> gauss(0.0, 1.0);
  std::ofstream csv(dir / "blow.csv");
  csv << "t,F1,F2,V1,V2\n";
  for (std::size_t k = 0; k < t.size(); k += stride) {
    const double f1 = f[k] + noise * fmax * gauss(random), f2 = f[k] + noise * fmax * gauss(random);
    const double v1 = velocity_scale * (v[k] + noise * vmax * gauss(random));
    const double v2 = velocity_scale * (v[k] + noise * vmax * gauss(random));
    csv << fmt::format("{},{},{},{},{}\n", t[k], f1, f2, v1, v2);
  }
  csv.close();
  return PileRecord::from_string(
      "[pile]\nlength = 19.2\narea = 0.0105\nmodulus = 210e9\ndensity = 7850.0\n[record]\nfile = \"blow.csv\"\n"
      "force = [\"F1\", \"F2\"]\nvelocity = [\"V1\", \"V2\"]\n[match]\nsegments = 10\n" +
          match + "\n",
      dir, "record.toml");
}

void record_match(const MatchResult& m) {
  ::testing::Test::RecordProperty("capacity", fmt::format("{}", m.soil.capacity()));
  ::testing::Test::RecordProperty("shaft", fmt::format("{}", m.soil.shaft_total()));
  ::testing::Test::RecordProperty("toe", fmt::format("{}", m.soil.toe));
  ::testing::Test::RecordProperty("quality", fmt::format("{}", m.quality));
  ::testing::Test::RecordProperty("evaluations", fmt::format("{}", m.evaluations));
}

// The match of `record` against the pipe's soil: the capacity within
// `capacity` and the shaft and the toe within `split` (fractions).
MatchResult expect_pipe_soil(const PileRecord& record, double capacity, double split) {
  MatchResult m = match_pile(record);
  EXPECT_NEAR(m.soil.capacity(), 1.5e6, capacity * 1.5e6);
  EXPECT_NEAR(m.soil.shaft_total(), 600e3, split * 600e3);
  EXPECT_NEAR(m.soil.toe, 900e3, split * 900e3);
  record_match(m);
  return m;
}

// The bounds: capacity within 2%, shaft and toe within 5%, match
// quality below 1% (measured 1500 kN, 604 and 895 kN, 0.10%: the match's
// pile has 0.19 m elements and ten uniform segments where the blow's had 0.2
// m elements and a triangle). The starts agree on the capacity to 0.1%
// (measured 0.001%).
TEST(Match, RecoversTheForwardBlowsSoil) {
  testing::ScratchDirectory dir("match-clean");
  const MatchResult m = expect_pipe_soil(steel_pipe_record(dir.path(), 0.0, 1.0), 0.02, 0.05);
  EXPECT_LT(m.quality, 0.01);
  ASSERT_EQ(m.starts.size(), 4u);
  for (const auto& s : m.starts) EXPECT_NEAR(s.soil.capacity(), m.soil.capacity(), 1e-3 * m.soil.capacity());
}

// White noise of 2% of each channel's peak on each channel and the velocity
// 1% high: capacity within 5%, shaft and toe within 10% (the issue's
// bounds; measured 1499, 593 and 906 kN, quality 1.0%). Over ten noise
// seeds on examples/pda's record the capacity stayed within 0.5% and the
// shaft within 5.1% (bench/match_noise.py); without the smoothing penalty the shaft
// spread to -15%, trading the deepest segment for the toe.
TEST(Match, RecoversTheSoilThroughNoiseAndAVelocityCalibration) {
  testing::ScratchDirectory dir("match-noisy");
  const MatchResult m = expect_pipe_soil(steel_pipe_record(dir.path(), 0.02, 1.01), 0.05, 0.10);
  EXPECT_LT(m.quality, 0.02) << "the noise's own rms, about 1% after the low-pass";
}

// The same noise on a record sampled at about 11 kHz (every fifth sample of
// the blow's 55 kHz), as analysers record: fewer samples carry the same
// noise, low-passed at a quarter of the sampling rate (measured 1511, 592
// and 919 kN, quality 1.7%).
TEST(Match, RecoversTheSoilThroughNoiseAtAnAnalysersRate) {
  testing::ScratchDirectory dir("match-noisy-11k");
  const MatchResult m =
      expect_pipe_soil(steel_pipe_record(dir.path(), 0.02, 1.01, {}, "embedded = 18.0", 5), 0.05, 0.10);
  EXPECT_LT(m.quality, 0.03);
}

// A distribution with a kink: the pipe's 600 kN uniform over its lowest 9 m
// only, matched over all of the pile's 19.2 m below the gauges: the
// smoothing penalty, zero on straight stretches, bends the distribution
// at the ground line's segment and moves a little of the toe to the shaft
// (measured 624 and 878 kN, quality 0.51%; at the weight 3, 601 and 900 kN
// and 0.27%).
TEST(Match, FollowsADistributionWithAKink) {
  testing::ScratchDirectory dir("match-kink");
  const MatchResult m =
      expect_pipe_soil(steel_pipe_record(dir.path(), 0.0, 1.0,
                                         {"body.pile.shaft.embedded=9.0", "body.pile.shaft.distribution=uniform"}, ""),
                       0.02, 0.05);
  EXPECT_LT(m.quality, 0.01);
  for (std::size_t i = 0; i < 4; ++i)
    EXPECT_LT(m.soil.shaft[i], 0.05 * 600e3) << "segment " << i + 1 << ": above the soil";
}

}  // namespace
}  // namespace barimpact
