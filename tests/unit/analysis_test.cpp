// The Hopkinson bar analysis (analysis.hpp) on synthetic gauge records
// whose waves are known functions: every column against its formula, the
// alignment, the signal layouts a laboratory's files come in (signal.hpp),
// the fit, and every refusal of a setup (setup.hpp) or a record.
#include "barimpact/hopkinson/analysis.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <random>

#include "../support/scratch_directory.hpp"
#include "barimpact/model/input_error.hpp"

namespace barimpact {
namespace {

namespace fs = std::filesystem;

// Bars E = 200 GPa, rho = 8000: c0 = 5000 exactly. Gauges 1 m and 0.5 m from
// the specimen: the reflected pulse is read 400 us after the incident, the
// transmitted 300 us. Samples every 0.1 us: both shifts are whole samples.
constexpr double E = 200e9, rho = 8000.0, c0 = 5000.0, Ab = 3e-4, Ls = 0.005, As = 1e-4;
constexpr double dt = 1e-7, foot = 100e-6, shift_r = 400e-6, shift_t = 300e-6;
constexpr std::size_t samples = 12001;

// A pulse of unit height: a jump to 5% half a sample after 0, a ramp to 1 at
// 19 us, 1 to 100 us, down to 0 at 121 us (the jump and the 2% levels fall
// between samples: no sample's value hangs on the clock's rounding).
double shape(double tau) {
  if (tau <= 0.05e-6 || tau >= 121e-6) return 0.0;
  if (tau < 100e-6) return std::min(0.05 + tau / 20e-6, 1.0);
  return (121e-6 - tau) / 21e-6;
}

// The waves at the specimen's faces, tau from the incident foot's arrival.
double eps_i(double tau) {
  return -1e-3 * shape(tau);
}
double eps_r(double tau) {
  return 6e-4 * shape(tau - 3e-6);
}
double eps_t(double tau) {
  return -4e-4 * shape(tau - 1e-6);
}

struct Records {
  std::vector<double> t, incident, transmitted;
};

Records records(double offset_i = 0, double offset_t = 0, double clock = 0) {
  Records r;
  for (std::size_t k = 0; k < samples; ++k) {
    const double t = static_cast<double>(k) * dt;
    r.t.push_back(t + clock);
    r.incident.push_back(eps_i(t - foot) + eps_r(t - foot - shift_r) + offset_i);
    r.transmitted.push_back(eps_t(t - foot - shift_t) + offset_t);
  }
  return r;
}

class HopkinsonAnalysis : public ::testing::Test {
 protected:
  void write(const std::string& name, const std::string& text) const { std::ofstream(dir_ / name) << text; }

  void write_csv(const std::string& name, const std::vector<double>& t, const std::vector<double>& v,
                 const std::string& header = "t,strain\n") const {
    std::string text = header;
    for (std::size_t k = 0; k < t.size(); ++k) text += fmt::format("{},{}\n", t[k], v[k]);
    write(name, text);
  }

  void write_records(const Records& r) const {
    write_csv("incident.csv", r.t, r.incident);
    write_csv("transmitted.csv", r.t, r.transmitted);
  }

  static std::string setup_text(const std::string& extra = "", const std::string& incident = "",
                                const std::string& transmitted = "") {
    return fmt::format(R"toml(
[bar]
modulus = 200e9
density = 8000.0
area = 3e-4
[specimen]
length = 0.005
area = 1e-4
[incident]
{}gauge_to_specimen = 1.0
{}
[transmitted]
{}gauge_to_specimen = 0.5
{}
{}
)toml",
                       // A channel given its own signal does without the default one.
                       incident.find("signal =") == std::string::npos ? "signal = \"incident.csv\"\n" : "", incident,
                       transmitted.find("signal =") == std::string::npos ? "signal = \"transmitted.csv\"\n" : "",
                       transmitted, extra);
  }

  HopkinsonResult analyse(const std::string& setup) const {
    return analyse_hopkinson(HopkinsonSetup::from_string(setup, dir_, "setup.toml"));
  }

  // The one-line message of a refusal, or a failure.
  std::string refusal(const std::string& setup) const {
    try {
      (void)analyse(setup);
    } catch (const InputError& e) {
      const std::string what = e.what();
      EXPECT_EQ(what.find('\n'), std::string::npos) << what;
      return what;
    }
    ADD_FAILURE() << "accepted: " << setup;
    return "";
  }

  testing::ScratchDirectory scratch_{"barimpact-hopkinson"};
  const fs::path& dir_ = scratch_.path();
};

#define EXPECT_HAS(text, part) EXPECT_NE(std::string(text).find(part), std::string::npos) << (text)

double scale(const std::vector<double>& v) {
  double m = 0.0;
  for (double x : v)
    if (std::isfinite(x)) m = std::max(m, std::abs(x));
  return m;
}

// The setup's sizes and moduli may carry units (docs/hopkinson.md): a
// GPa/mm setup is its SI twin bit for bit; a unit of another quantity is
// refused naming the key and the units it takes.
TEST_F(HopkinsonAnalysis, ASetupInGigapascalsAndMillimetresIsItsSITwin) {
  write_records(records());
  std::string metric = setup_text();
  for (const auto& [si, with_unit] : {std::pair{"modulus = 200e9", "modulus = \"200 GPa\""},
                                      {"density = 8000.0", "density = \"8 t/m3\""},
                                      {"area = 3e-4", "area = \"300 mm2\""},
                                      {"length = 0.005", "length = \"5 mm\""},
                                      {"area = 1e-4", "area = \"1 cm2\""},
                                      {"gauge_to_specimen = 1.0", "gauge_to_specimen = \"1000 mm\""},
                                      {"gauge_to_specimen = 0.5", "gauge_to_specimen = \"50 cm\""}}) {
    const auto at = metric.find(si);
    ASSERT_NE(at, std::string::npos) << si;
    metric.replace(at, std::string(si).size(), with_unit);
  }
  const auto a = analyse(setup_text()), b = analyse(metric);
  ASSERT_EQ(a.columns.size(), b.columns.size());
  auto same = [](double x, double y) { return x == y || (std::isnan(x) && std::isnan(y)); };  // bit for bit, NaN too
  for (std::size_t i = 0; i < a.columns.size(); ++i)
    EXPECT_TRUE(std::equal(a.columns[i].values.begin(), a.columns[i].values.end(), b.columns[i].values.begin(),
                           b.columns[i].values.end(), same))
        << a.columns[i].name;
  std::string wrong = setup_text();
  wrong.replace(wrong.find("modulus = 200e9"), 15, "modulus = \"200 kN\"");
  EXPECT_HAS(refusal(wrong), "setup.toml:3: bar.modulus = \"200 kN\": kN is a force; a stress: Pa, kPa, MPa, GPa");
}

TEST_F(HopkinsonAnalysis, EveryColumnIsItsFormulaOnTheWavesAtTheFaces) {
  write_records(records());
  const auto r = analyse(setup_text());
  const auto& names = hopkinson_columns();
  ASSERT_GE(r.columns.size(), names.size());
  for (std::size_t i = 0; i < names.size(); ++i) EXPECT_EQ(r.columns[i].name, names[i]);
  // One row per incident sample from the foot (t = 100 us) to the window's
  // end: the first sample after the pulse falls back to 2% (120.6 us).
  const auto& t = r.column("t");
  ASSERT_EQ(t.size(), 1207u);
  EXPECT_DOUBLE_EQ(r.alignment.foot, foot);
  EXPECT_NEAR(r.alignment.incident.end, foot + 120.6e-6, 1e-12);
  EXPECT_NEAR(r.alignment.reflected_shift, shift_r, 1e-15);
  EXPECT_NEAR(r.alignment.transmitted_shift, shift_t, 1e-15);
  double strain_1w = 0.0, strain_3w = 0.0, peak_f = 0.0, peak_b = 0.0, peak_3w = 0.0;
  for (double tau : t) {
    peak_f = std::max(peak_f, -E * Ab * (eps_i(tau) + eps_r(tau)));
    peak_b = std::max(peak_b, -E * Ab * eps_t(tau));
    peak_3w = std::max(peak_3w, -E * Ab * (eps_i(tau) + eps_r(tau) + eps_t(tau)) / (2 * As));
  }
  for (std::size_t i = 0; i < t.size(); ++i) {
    const double tau = t[i], ei = eps_i(tau), er = eps_r(tau), et = eps_t(tau);
    // Strains are read at whole samples up to the clock's rounding (1e-18 s):
    // 1e-13 of a strain, 1e-9 relative on forces of 6e4.
    ASSERT_NEAR(r.column("incident")[i], ei, 1e-13) << tau;
    ASSERT_NEAR(r.column("reflected")[i], er, 1e-13) << tau;
    ASSERT_NEAR(r.column("transmitted")[i], et, 1e-13) << tau;
    const double ff = -E * Ab * (ei + er), fb = -E * Ab * et;
    EXPECT_NEAR(r.column("force_front")[i], ff, 1e-6);
    EXPECT_NEAR(r.column("force_back")[i], fb, 1e-6);
    EXPECT_NEAR(r.column("stress_1w")[i], fb / As, 1e-2);
    EXPECT_NEAR(r.column("stress_2w")[i], ff / As, 1e-2);
    EXPECT_NEAR(r.column("stress_3w")[i], (ff + fb) / (2 * As), 1e-2);
    EXPECT_NEAR(r.column("strain_rate_1w")[i], 2 * c0 * er / Ls, 1e-7);
    EXPECT_NEAR(r.column("strain_rate_3w")[i], c0 * (er + et - ei) / Ls, 1e-7);
    if (i > 0) {
      strain_1w += 0.5 * (t[i] - t[i - 1]) * (2 * c0 / Ls) * (er + eps_r(t[i - 1]));
      strain_3w +=
          0.5 * (t[i] - t[i - 1]) * (c0 / Ls) * (er + et - ei + eps_r(t[i - 1]) + eps_t(t[i - 1]) - eps_i(t[i - 1]));
    }
    EXPECT_NEAR(r.column("strain_1w")[i], strain_1w, 1e-12);
    EXPECT_NEAR(r.column("strain_3w")[i], strain_3w, 1e-12);
    // Equilibrium only where both forces pass 5% of their peaks (away from
    // the threshold by more than the forces' round-off).
    const double eq = r.column("equilibrium")[i];
    if (ff > 0.05 * peak_f * (1 + 1e-9) && fb > 0.05 * peak_b * (1 + 1e-9)) {
      EXPECT_NEAR(eq, 2 * (ff - fb) / (ff + fb), 1e-9) << tau;
    } else if (ff < 0.05 * peak_f * (1 - 1e-9) || fb < 0.05 * peak_b * (1 - 1e-9)) {
      EXPECT_TRUE(std::isnan(eq)) << tau;
    }
  }
  EXPECT_NEAR(r.peak_stress_3w.value, peak_3w, 1e-3);
  EXPECT_NEAR(r.peak_strain_rate_1w.value, 2 * c0 * 6e-4 / Ls, 1e-6);
}

TEST_F(HopkinsonAnalysis, BaselineOffsetsAndTheClockChangeNothingButTheAlignment) {
  write_records(records());
  const auto plain = analyse(setup_text());
  write_records(records(2.5e-5, -1.5e-5, 0.0123));
  const auto moved = analyse(setup_text());
  EXPECT_NEAR(moved.alignment.baseline_incident, 2.5e-5, 1e-18);
  EXPECT_NEAR(moved.alignment.baseline_transmitted, -1.5e-5, 1e-18);
  EXPECT_NEAR(moved.alignment.foot, foot + 0.0123, 1e-12);
  ASSERT_EQ(moved.column("t").size(), plain.column("t").size());
  for (const auto& name : hopkinson_columns())
    for (std::size_t i = 0; i < plain.column(name).size(); ++i) {
      const double a = plain.column(name)[i], b = moved.column(name)[i];
      if (std::isnan(a)) {
        EXPECT_TRUE(std::isnan(b)) << name << " " << i;
        continue;
      }
      // The offset's subtraction and the clock's shift round at 1e-16 of the
      // offset (strain) and 1e-16 of 0.0123 s: 1e-9 of each column's scale.
      EXPECT_NEAR(a, b, 1e-9 * scale(plain.column(name))) << name << " " << i;
    }
}

TEST_F(HopkinsonAnalysis, SummaryStatesTheAlignmentAndTheCsvHeaderIsTheContract) {
  write_records(records(1e-5, 0.0));
  const auto r = analyse(setup_text());
  const std::string csv = hopkinson_csv(r);
  EXPECT_EQ(csv.substr(0, csv.find('\n')),
            "t,strain_1w,strain_rate_1w,stress_1w,strain_3w,strain_rate_3w,stress_2w,stress_3w,force_front,"
            "force_back,equilibrium,incident,reflected,transmitted");
  EXPECT_HAS(csv, ",nan,");  // equilibrium where the forces are small
  const std::string json = hopkinson_summary_json(r);
  for (const char* key : {"\"alignment\"", "\"baseline\"", "\"shift\"", "\"windows\"", "\"peak_stress\"",
                          "\"peak_strain_rate\"", "\"equilibrium_from\""})
    EXPECT_HAS(json, key);
  EXPECT_EQ(json.find("\"fit\""), std::string::npos);  // no [fit], no fit
}

// A specimen with a bilinear law sigma(eps) strained at a rate that ramps up
// and holds, in equilibrium (eps_t = eps_i + eps_r): the records follow from
// it. The 3-wave curve is the law; the fit finds E, the 0.2% offset yield and
// the tangent modulus.
TEST_F(HopkinsonAnalysis, FitRecoversABilinearLawFromItsOwnRecords) {
  const double Es = 70e9, sy = 300e6, Et = 1e9, rate = 1000.0, ramp = 20e-6;
  auto strain = [&](double tau) {
    if (tau <= 0) return 0.0;
    return tau < ramp ? rate * tau * tau / (2 * ramp) : rate * (tau - ramp / 2);
  };
  auto stress = [&](double e) { return e <= sy / Es ? Es * e : sy + Et * (e - sy / Es); };
  auto er = [&](double tau) { return tau <= 0 ? 0.0 : Ls * rate * std::min(tau / ramp, 1.0) / (2 * c0); };
  auto et = [&](double tau) { return -stress(strain(tau)) * As / (E * Ab); };
  const double end = 150e-6;
  Records r;
  for (std::size_t k = 0; k < samples; ++k) {
    const double t = static_cast<double>(k) * dt;
    const double tau = t - foot, back = t - foot - shift_r;
    const double inc = tau > 0 && tau <= end ? et(tau) - er(tau) : 0.0;
    const double ref = back > 0 && back <= end ? er(back) : 0.0;
    r.t.push_back(t);
    r.incident.push_back(inc + ref);
    r.transmitted.push_back(t - foot - shift_t > 0 && t - foot - shift_t <= end ? et(t - foot - shift_t) : 0.0);
  }
  write_records(r);
  const auto a = analyse(setup_text("[fit]\nelastic = [50e6, 250e6]", "start = 100e-6\nend = 250e-6"));
  EXPECT_EQ(a.alignment.method, "windows");
  ASSERT_TRUE(a.fit.done);
  // The records hold the law exactly at the samples; the strain's trapezoid
  // rule is exact for the piecewise-linear rate: 1e-9 relative.
  EXPECT_NEAR(a.fit.modulus / Es, 1.0, 1e-9);
  const double yield = sy + Et * 0.002 * Es / (Es - Et);  // the bilinear law's 0.2% offset stress
  ASSERT_TRUE(a.fit.yield_stress);
  // Between samples the offset's crossing is interpolated: 1e-6 relative.
  EXPECT_NEAR(*a.fit.yield_stress / yield, 1.0, 1e-6);
  ASSERT_TRUE(a.fit.hardening_modulus);
  EXPECT_NEAR(*a.fit.hardening_modulus / Et, 1.0, 1e-6);
  EXPECT_HAS(hopkinson_summary_json(a), "\"yield_stress\"");
}

TEST_F(HopkinsonAnalysis, ReadsTheLayoutsALaboratoryRecordsIn) {
  const auto rec = records(1e-5, 0.0);
  write_records(rec);
  const auto reference = analyse(setup_text());
  // No header, tab-separated, three lines of scope preamble, no time column.
  std::string text = "scope X\nsample rate 10 MHz\n\n";
  for (std::size_t k = 0; k < samples; ++k) text += fmt::format("{}\t{}\n", -rec.incident[k], 0.0);
  write("raw.tsv", text);
  // Volts of a half bridge: eps = 2 V / (gain excitation GF).
  text = "time,ch1,ch2\n";
  for (std::size_t k = 0; k < samples; ++k)
    text += fmt::format("{},{},{}\n", rec.t[k], rec.transmitted[k] * 100 * 5 * 2.1 / 2, "x");
  write("volts.csv", text);
  const auto r = analyse(setup_text("",
                                    "signal = \"raw.tsv\"\nheader = false\nstrain = \"1\"\ndelimiter = \"\\t\"\n"
                                    "skip_rows = 3\nsample_interval = 1e-7\npolarity = -1",
                                    "signal = \"volts.csv\"\ntime = \"time\"\nvolts = \"ch1\"\nbridge = \"half\"\n"
                                    "gauge_factor = 2.1\nexcitation = 5.0\ngain = 100"));
  for (const auto& name : hopkinson_columns())
    for (std::size_t i = 0; i < reference.column(name).size(); i += 37) {
      if (std::isnan(reference.column(name)[i])) continue;
      // The volts' conversion and back rounds at 1e-16: 1e-8 of the column's scale.
      EXPECT_NEAR(r.column(name)[i], reference.column(name)[i], 1e-8 * scale(reference.column(name))) << name;
    }
}

TEST_F(HopkinsonAnalysis, AveragesAGaugePairInOneFileOrOnTwoChannels) {
  const auto rec = records();
  write_records(rec);
  const auto reference = analyse(setup_text());
  // Bending adds +b on one gauge and -b on the other: the mean is the axial strain.
  std::string pair = "t,a,b\n", one = "t,v\n", two = "t,v\n";
  for (std::size_t k = 0; k < samples; ++k) {
    const double bend = 3e-4 * std::sin(static_cast<double>(k) * 0.01);
    pair += fmt::format("{},{},{}\n", rec.t[k], rec.incident[k] + bend, rec.incident[k] - bend);
    one += fmt::format("{},{}\n", rec.t[k], rec.transmitted[k] + bend);
    two += fmt::format("{},{}\n", rec.t[k], rec.transmitted[k] - bend);
  }
  write("pair.csv", pair);
  write("one.csv", one);
  write("two.csv", two);
  const auto r = analyse(setup_text("", "signal = \"pair.csv\"\nstrain = [\"a\", \"b\"]",
                                    "signal = [\"one.csv\", \"two.csv\"]\nstrain = \"v\""));
  for (std::size_t i = 0; i < reference.column("stress_3w").size(); ++i)
    EXPECT_NEAR(r.column("stress_3w")[i], reference.column("stress_3w")[i], 1e-3) << i;  // of 1e8: round-off
}

// Issue 36: a spreadsheet's CSV starting with a UTF-8 byte order mark was
// refused with "no column \"t\" (columns: t, strain)": the mark is not text.
TEST_F(HopkinsonAnalysis, ReadsACsvFileStartingWithAByteOrderMark) {
  const auto rec = records();
  write_records(rec);
  const auto reference = analyse(setup_text());
  write_csv("incident.csv", rec.t, rec.incident, "\xEF\xBB\xBFt,strain\n");
  write_csv("transmitted.csv", rec.t, rec.transmitted, "\xEF\xBB\xBF\"t\",\"strain\"\n");
  const auto r = analyse(setup_text());
  EXPECT_EQ(r.column("stress_3w"), reference.column("stress_3w"));
  // Without a header the mark goes too: the first sample is a number.
  write_csv("incident.csv", rec.t, rec.incident, "\xEF\xBB\xBF");
  write_csv("transmitted.csv", rec.t, rec.transmitted, "\xEF\xBB\xBF");
  const auto bare = analyse(
      setup_text("", "header = false\ntime = \"1\"\nstrain = \"2\"", "header = false\ntime = \"1\"\nstrain = \"2\""));
  EXPECT_EQ(bare.column("stress_3w"), reference.column("stress_3w"));
}

// `text` with its first `from` replaced by `to`.
std::string with(std::string text, const std::string& from, const std::string& to) {
  return text.replace(text.find(from), from.size(), to);
}

TEST_F(HopkinsonAnalysis, RefusesWhatCannotBeAnalysedInOneLine) {
  write_records(records());
  EXPECT_HAS(refusal(with(setup_text(), "transmitted.csv", "missing.csv")), "missing.csv");
  EXPECT_HAS(refusal(setup_text("", "strain = \"eps\"")), "no column \"eps\"");
  EXPECT_HAS(refusal(setup_text("", "time = \"time\"")), "no column \"time\"");
  write("back.csv", "t,strain\n0,0\n1e-7,0\n0.5e-7,0\n");  // time that goes back
  EXPECT_HAS(refusal(with(setup_text(), "\"incident.csv\"", "\"back.csv\"")), "not increasing");
  // A silent transmitter bar: no pulse.
  auto silent = records();
  std::fill(silent.transmitted.begin(), silent.transmitted.end(), 0.0);
  write_records(silent);
  EXPECT_HAS(refusal(setup_text()), "[transmitted]");
  EXPECT_HAS(refusal(setup_text()), "no pulse");
  // Mains hum of amplitude 9e-5 (rms 6.4e-5): under the trigger level 1e-4,
  // above half of it.
  auto hum = records();
  for (std::size_t k = 0; k < samples; ++k) hum.incident[k] += 9e-5 * std::sin(2e5 * M_PI * hum.t[k]);
  write_records(hum);
  EXPECT_HAS(refusal(setup_text()), "baseline noise");
  // Clipping at full_scale (the plateau is at 1e-3).
  write_records(records());
  EXPECT_HAS(refusal(setup_text("", "full_scale = 9e-4")), "clips");
  // The gauge too near the specimen: a 121 us pulse against 2 x 0.2 / c0 = 80 us.
  EXPECT_HAS(refusal(with(setup_text(), "gauge_to_specimen = 1.0", "gauge_to_specimen = 0.2")), "pulses too close");
  // Compression recorded positive without polarity = -1.
  auto flipped = records();
  for (auto& v : flipped.incident) v = -v;
  write_records(flipped);
  EXPECT_HAS(refusal(setup_text()), "polarity");
}

// White noise on the incident record, of rms 2% and 8% of the incident peak
// (1e-3): noise once took the foot to the record's first samples (a window of
// 2 samples, a noise rms of 0, exit 0) or refused the pulse as starting
// there. The pulse is found on a moving average, the noise measured before
// the foot: 2% is analysed with the pulse's window, 8% refused (above half
// the trigger level, 5%); a record without 8 samples before the foot cannot
// measure it.
TEST_F(HopkinsonAnalysis, FindsThePulseUnderNoiseAndRefusesNoiseAboveTheContract) {
  for (const unsigned seed : {1u, 2u, 3u, 6u}) {
    std::mt19937 rng(seed);
    std::normal_distribution<double> normal(0.0, 1.0);
    const auto clean = records();
    auto noisy = [&](double rms) {
      auto r = clean;
      for (auto& v : r.incident) v += rms * normal(rng);
      return r;
    };
    write_records(noisy(8e-5));
    EXPECT_HAS(refusal(setup_text()), "baseline noise: the rms");
    write_records(noisy(2e-5));
    const auto r = analyse(setup_text());
    // The average (about 14 samples here) moves the foot up to half its
    // width early, and the end as late: 1 us (10 samples) either way.
    EXPECT_NEAR(r.alignment.foot, foot, 1e-6) << seed;
    EXPECT_NEAR(r.alignment.incident.end, foot + 120.6e-6, 1e-6) << seed;
    // The rms of 1000 samples: within 10% of the noise's.
    EXPECT_NEAR(r.alignment.noise_incident, 2e-5, 2e-6) << seed;
    EXPECT_NEAR(r.alignment.incident_peak, 1e-3, 2e-5) << seed;
  }
  write_records(records());
  EXPECT_HAS(refusal(setup_text("", "start = 0.5e-6\nend = 150e-6")), "only 5 samples before the incident foot");
}

// Each of these once exited 0 with every result nan (or a peak stress of -0):
// a result that is not finite is refused, naming the key that placed it.
TEST_F(HopkinsonAnalysis, RefusesASetupWhoseResultsWouldNotBeFinite) {
  write_records(records());
  for (const char* d : {"750", "1e300"})
    EXPECT_HAS(refusal(with(setup_text(), "gauge_to_specimen = 1.0", fmt::format("gauge_to_specimen = {}", d))),
               "incident.gauge_to_specimen");
  EXPECT_HAS(refusal(with(setup_text(), "gauge_to_specimen = 0.5", "gauge_to_specimen = 750")),
             "transmitted.gauge_to_specimen");
  // A transmitted window outside the record, as the incident's is refused.
  const std::string outside = refusal(setup_text("", "", "start = 2e-3\nend = 3e-3"));
  EXPECT_HAS(outside, "transmitted.start = 0.002, transmitted.end = 0.003");
  EXPECT_HAS(outside, "not inside the record");
  // A window between two samples (it read nothing: a peak stress of -0).
  EXPECT_HAS(refusal(setup_text("", "", "start = 400.01e-6\nend = 400.05e-6")), "holds 0 samples, fewer than two");
  EXPECT_HAS(refusal(setup_text("", "start = 100.01e-6\nend = 100.05e-6")), "incident.start");
  // Times 1e-320 apart: the pulses' travel times lie far beyond the record.
  std::string column = "strain\n", transmitted = "strain\n";
  const auto rec = records();
  for (std::size_t k = 0; k < samples; ++k) {
    column += fmt::format("{}\n", rec.incident[k]);
    transmitted += fmt::format("{}\n", rec.transmitted[k]);
  }
  write("i.csv", column);
  write("t.csv", transmitted);
  EXPECT_HAS(refusal(setup_text("", "signal = \"i.csv\"\nsample_interval = 1e-320",
                                "signal = \"t.csv\"\nsample_interval = 1e-320")),
             "incident.sample_interval = 1e-320: outside");
  // A reflected pulse larger than the incident one and a transmitted one in
  // tension: the specimen is never in compression.
  Records tension;
  for (std::size_t k = 0; k < samples; ++k) {
    const double t = static_cast<double>(k) * dt;
    tension.t.push_back(t);
    tension.incident.push_back(eps_i(t - foot) - 1.5 * eps_i(t - foot - shift_r));
    tension.transmitted.push_back(-eps_t(t - foot - shift_t));
  }
  write_records(tension);
  EXPECT_HAS(refusal(setup_text()), "never compression");
}

// A number given in another unit than SI's gave nan, or garbage with no
// word (a specimen 6 m long: a modulus of 6.6e13 Pa): refused, naming the key
// and the unit it was probably meant in.
TEST_F(HopkinsonAnalysis, RefusesAUnitSlipNamingTheKeyAndTheUnit) {
  write_records(records());
  const auto slip = [&](const std::string& from, const std::string& to) {
    return refusal(with(setup_text(), from, to));
  };
  EXPECT_HAS(slip("modulus = 200e9", "modulus = 200"), "bar.modulus = 200: GPa?");
  EXPECT_HAS(slip("modulus = 200e9", "modulus = 200000"), "bar.modulus = 200000: MPa?");
  EXPECT_HAS(slip("density = 8000.0", "density = 8.0"), "bar.density = 8: g/cm^3?");
  EXPECT_HAS(slip("density = 8000.0", "density = 8000.0\nwave_speed = 5"), "bar.wave_speed = 5: km/s?");
  EXPECT_HAS(slip("modulus = 200e9", "modulus = 2e8"), "c0 = sqrt(modulus / density) = 158.1 m/s");
  EXPECT_HAS(slip("area = 3e-4", "diameter = 20"), "bar.diameter = 20: mm?");
  EXPECT_HAS(slip("gauge_to_specimen = 1.0", "gauge_to_specimen = 750"), "incident.gauge_to_specimen = 750: mm?");
  // In the range of a bar, but placing the reflected pulse beyond the record.
  EXPECT_HAS(slip("gauge_to_specimen = 1.0", "gauge_to_specimen = 50"), "incident.gauge_to_specimen = 50: mm?");
  EXPECT_HAS(slip("length = 0.005", "length = 5"), "specimen.length = 5: mm? 443 diameters long");
  EXPECT_HAS(slip("area = 1e-4", "area = 100"), "specimen.area = 100: mm^2? the specimen");
  EXPECT_HAS(slip("area = 1e-4", "diameter = 11"), "specimen.diameter = 11: mm? the specimen");
  // A scope's time column in us (0.1 apart), or in ms (the pulse 0.12 long).
  for (const auto& [unit, factor, want] :
       {std::tuple{"us", 1e6, "incident.time: the samples are 0.1 apart on average: us?"},
        std::tuple{"ms", 1e3, "incident.time: the incident pulse lasts 0.1206: ms?"}}) {
    auto r = records();
    for (auto& t : r.t) t *= factor;
    write_records(r);
    EXPECT_HAS(refusal(setup_text()), want) << unit;
  }
  // A specimen 0.11 mm across: a stress of 2.6e12 Pa, beyond any bar test's.
  write_records(records());
  const auto r = analyse(with(with(setup_text(), "area = 1e-4", "area = 1e-8"), "length = 0.005", "length = 5e-4"));
  ASSERT_FALSE(r.warnings.empty());
  EXPECT_EQ(r.warnings.back().rfind("implausible-result: the 3-wave peak stress 2.61e+12", 0), 0u) << r.warnings.back();
}

TEST_F(HopkinsonAnalysis, RefusesABadSetupNamingTheKey) {
  write_records(records());
  EXPECT_HAS(refusal(setup_text("[window]\ntrigger = 0.01")), "window.trigger");
  EXPECT_HAS(refusal(setup_text("[window]\ntriger = 0.2")), "unknown key window.triger");
  EXPECT_HAS(refusal(setup_text("", "volts = \"ch1\"")), "incident.gauge_factor");
  EXPECT_HAS(refusal(setup_text("", "volts = \"ch1\"\ngauge_factor = 2\nexcitation = 5\nbridge = \"third\"")),
             "incident.bridge");
  EXPECT_HAS(refusal(setup_text("[fit]\nelastic = [3e8, 1e8]")), "fit.elastic");
  EXPECT_HAS(refusal(setup_text("", "start = 1e-4")), "incident.end");
  EXPECT_HAS(refusal(setup_text("[bar]\ndiameter = 0.02")), "not valid TOML");  // a second [bar]
  EXPECT_HAS(refusal(setup_text("[cushion]\nx = 1")), "unknown section [cushion]");
  EXPECT_HAS(refusal(setup_text("[fit]\nplastic = [0.01, 0.1]")), "fit.plastic needs fit.elastic");
}

}  // namespace
}  // namespace barimpact
