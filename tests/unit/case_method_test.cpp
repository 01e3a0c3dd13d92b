// The Case method and the analyser's quantities (case_method.hpp) against
// hand computation on a record whose waves are known: a half-sine wave down
// of peak P over 2 ms, and a wave up of a reflection -0.2 Wd(t - 3 ms) (an
// impedance drop 7.5 m below the gauges), 0.3 Wd(t - 2L/c) and
// 0.4 Wd(t - 2L/c - 1 ms), sampled every 0.1 ms, each channel offset.
#include "barimpact/pda/case_method.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "../support/pda_record.hpp"
#include "../support/scratch_directory.hpp"

namespace barimpact {
namespace {

using testing::KnownWaves;

CaseMethodResult analyse(const KnownWaves& w, const std::string& extra = "") {
  testing::ScratchDirectory dir("pda");
  w.write(dir.path(), extra);
  return analyse_pda(PileRecord::from_file(dir.path() / "record.toml"));
}

// The foot is the first sample above 5% of P (t = 2.1 ms: sin(pi / 20) =
// 0.156), t1 the first peak (3 ms), t2 = t1 + 2L/c; the offsets are removed,
// so that the waves are the chosen ones to rounding (1e-9 of P: the CSV's
// shortest exact numbers, sums of a few terms).
TEST(CaseMethod, TimesAndWavesAreTheRecordsOwn) {
  const KnownWaves w;
  const auto r = analyse(w);
  EXPECT_DOUBLE_EQ(r.t_foot, w.t(21));
  EXPECT_DOUBLE_EQ(r.t1, w.t(30));
  EXPECT_NEAR(r.t2, 0.003 + 0.008, 1e-15);
  ASSERT_EQ(r.waves.t.size(), static_cast<std::size_t>(w.samples));
  for (int k = 0; k < w.samples; ++k) {
    EXPECT_NEAR(r.waves.down[k], w.down(w.t(k)), 1e-9 * w.peak) << k;
    EXPECT_NEAR(r.waves.up[k], w.up(w.t(k)), 1e-9 * w.peak) << k;
    EXPECT_NEAR(r.waves.velocity_z[k], w.impedance() * w.velocity(w.t(k)), 1e-9 * w.peak) << k;
  }
  EXPECT_NEAR(r.ratio_at_impact, 1.0, 1e-9);
}

// FMX = P and VMX = P / Z (the wave down alone at t1); EMX the trapezoid
// sum of (Wd^2 - Wu^2) / Z while the wave down passes, exactly P^2 tau / (2 Z)
// (sum of sin^2(pi k / 20) over k = 0..20 is 10); DMX the displacement
// when the reflection of the drop has passed, (1 + 0.2) P dt cot(pi / 40) / Z
// (sum of sin(pi k / 20) over k = 1..19 is cot(pi / 40)); CSX = P / A; TSX
// the drop's reflection alone, 0.2 P / A.
TEST(CaseMethod, MaximaAndStressesAgreeWithHandComputation) {
  const KnownWaves w;
  const auto r = analyse(w);
  const double P = w.peak, Z = w.impedance();
  EXPECT_NEAR(r.fmx, P, 1e-9 * P);
  EXPECT_NEAR(r.vmx, P / Z, 1e-9 * P / Z);
  EXPECT_NEAR(r.emx, P * P * w.width / (2.0 * Z), 1e-9 * P * P * w.width / Z);
  const double dmx = (1.0 + w.drop) * P * w.dt / std::tan(std::numbers::pi / 40.0) / Z;
  EXPECT_NEAR(r.dmx, dmx, 1e-9 * dmx);
  EXPECT_NEAR(r.csx, P / w.area, 1e-9 * P / w.area);
  EXPECT_NEAR(r.tsx, w.drop * P / w.area, 1e-9 * P / w.area);
}

// With [[segment]]s, tension is stress in the section it passes: the drop's
// reflection (0.2 P of tension at the gauges from 4 to 6 ms) meets depths
// 0 to 5 m; below 3 m the section is half the area, so TSX = 0.4 P / A
// there. Z, 2L/c and beta (its depth by the segments' travel times) are the
// uniform pile's.
TEST(CaseMethod, TensionStressUsesTheSectionAtItsDepth) {
  const KnownWaves w;
  testing::ScratchDirectory dir("pda-segments");
  w.write(dir.path());
  const auto r = analyse_pda(PileRecord::from_string(
      "[[segment]]\nlength = 3.0\narea = 0.01\nmodulus = 200e9\ndensity = 8000.0\n[[segment]]\nlength = 17.0\n"
      "area = 0.005\nmodulus = 200e9\ndensity = 8000.0\n[record]\nfile = \"blow.csv\"\nforce = [\"F1\", \"F2\"]\n"
      "velocity = [\"V1\", \"V2\"]\n",
      dir.path(), "record.toml"));
  EXPECT_NEAR(r.tsx, 2.0 * w.drop * w.peak / w.area, 1e-9 * w.peak / w.area);
  EXPECT_GE(r.tsx_depth, 3.0);
  EXPECT_LE(r.tsx_depth, 5.0 + 1e-9);
  EXPECT_NEAR(r.t2, 0.011, 1e-15);
  ASSERT_TRUE(r.bta_depth);
  EXPECT_NEAR(*r.bta_depth, 7.5, 1e-9);
}

// RSP at t1: (1 - J) P + (1 + J) 0.3 P; RMX the largest of
// (1 - J) Wd(t) + (1 + J) Wu(t + 2L/c) at the samples within 30 ms of t1,
// found here from the formulas, at 3.4 ms (the late reflection lifts it).
TEST(CaseMethod, CaseResistanceIsTheRecordsWavesCombined) {
  for (const double J : {0.0, 0.5, 1.0}) {
    const KnownWaves w;
    const auto r = analyse(w, fmt::format("[case_method]\ndamping = {}\n", J));
    const double P = w.peak;
    EXPECT_NEAR(r.rsp, (1.0 - J) * P + (1.0 + J) * w.toe * P, 1e-9 * P) << J;
    double rmx = -1e300, at = 0.0;
    for (int k = 30; w.t(k) <= std::min(0.003 + 0.030, w.t(w.samples - 1) - 0.008) + 1e-12; ++k) {
      const double rk = (1.0 - J) * w.down(w.t(k)) + (1.0 + J) * w.up(w.t(k) + 0.008);
      if (rk > rmx + 1e-9 * P) {
        rmx = rk;
        at = w.t(k);
      }
    }
    EXPECT_NEAR(r.rmx, rmx, 1e-9 * P) << J;
    EXPECT_NEAR(r.rmx_time, at, 1e-12) << J;
  }
}

// BTA: dWu = 0.2 P below Wu(t1) = 0 at 6 ms, so beta = (1 - 0.2) / (1 + 0.2)
// at c (6 - 3) ms / 2 = 7.5 m; without the drop beta = 1 and no depth.
TEST(CaseMethod, BetaIsRauscheAndGoblesIntegrityFactor) {
  KnownWaves w;
  auto r = analyse(w);
  EXPECT_NEAR(r.bta, 0.8 / 1.2, 1e-9);
  ASSERT_TRUE(r.bta_depth);
  EXPECT_NEAR(*r.bta_depth, 7.5, 1e-9);
  w.drop = 0.005;  // under 1% of Wd(t1)
  r = analyse(w);
  EXPECT_EQ(r.bta, 1.0);
  EXPECT_FALSE(r.bta_depth);
}

// The waves between samples by linear interpolation; the Case resistance by its formula.
TEST(CaseMethod, WavesInterpolateLinearly) {
  PileWaves w;
  w.t = {0.0, 1.0, 2.0};
  w.down = {0.0, 10.0, 20.0};
  w.up = {4.0, 2.0, 0.0};
  EXPECT_DOUBLE_EQ(w.down_at(0.25), 2.5);
  EXPECT_DOUBLE_EQ(w.up_at(1.5), 1.0);
  EXPECT_DOUBLE_EQ(case_resistance(w, 0.5, 1.0, 0.5), 0.5 * 5.0 + 1.5 * 1.0);
}

// pda.csv: the contract's columns first, one row a sample; summary.json's keys in the contract's order.
TEST(CaseMethod, OutputsFollowTheContract) {
  const KnownWaves w;
  const auto r = analyse(w);
  const std::string csv = pda_csv(r);
  EXPECT_EQ(csv.substr(0, csv.find('\n')), "t,force,velocity_z,wave_down,wave_up,displacement,velocity,energy");
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), w.samples + 1);
  const std::string json = pda_summary_json(r);
  std::size_t at = 0;
  for (const char* key : {"\"t1\"", "\"t2\"", "\"fmx\"", "\"vmx\"", "\"emx\"", "\"dmx\"", "\"csx\"", "\"tsx\"",
                          "\"rmx\"", "\"rmx_time\"", "\"rsp\"", "\"bta\"", "\"bta_depth\""}) {
    const auto found = json.find(key, at);
    ASSERT_NE(found, std::string::npos) << key;
    at = found;
  }
}

}  // namespace
}  // namespace barimpact
