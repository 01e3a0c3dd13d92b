// A record's signals at the gauges: the channels read, the foot and the
// impact found on the averaged force, the offsets removed, acceleration
// integrated, and the record refused where it cannot be analysed.
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "barimpact/model/input_error.hpp"
#include "barimpact/pda/record.hpp"

namespace barimpact {

namespace {

constexpr double foot_fraction = 0.05;     // the foot: 5% of the force's peak
constexpr std::size_t least_baseline = 5;  // samples for the offsets
constexpr double impact_mismatch = 0.3;    // |F / (Z v) - 1| at t1
constexpr double channel_spread = 0.5;     // |X1 - X2| / max(|X1|, |X2|) at t1

[[noreturn]] void refuse(const PileRecord& rec, std::string_view rule) {
  throw InputError(fmt::format("{}: record: {}", rec.csv.string(), rule));
}

std::vector<double> average(const std::vector<std::vector<double>>& channels) {
  std::vector<double> out(channels.front().size(), 0.0);
  for (const auto& c : channels)
    for (std::size_t k = 0; k < c.size(); ++k) out[k] += c[k];
  for (auto& v : out) v /= static_cast<double>(channels.size());
  return out;
}

// The running trapezoid integral of y from the first sample.
std::vector<double> integral(const std::vector<double>& t, const std::vector<double>& y) {
  std::vector<double> out(y.size(), 0.0);
  for (std::size_t k = 1; k < y.size(); ++k) out[k] = out[k - 1] + 0.5 * (y[k - 1] + y[k]) * (t[k] - t[k - 1]);
  return out;
}

// The foot, t1 and the baseline on the averaged force as recorded; refuses
// a record without impact, ending before t2 or starting too late.
void find_impact(const PileRecord& rec, const std::vector<double>& t, const std::vector<double>& f, PileSignals& s) {
  const std::string columns = fmt::format("{}", fmt::join(rec.force_columns, ", "));
  const double peak = *std::max_element(f.begin(), f.end());
  if (!(peak > 0.0))
    refuse(rec, fmt::format("no impact: the averaged {} ({}) never rises above 0 (compression positive)",
                            rec.strain ? "strain" : "force", columns));
  s.foot = static_cast<std::size_t>(
      std::find_if(f.begin(), f.end(), [&](double v) { return v > foot_fraction * peak; }) - f.begin());
  if (s.foot == 0)
    refuse(rec, fmt::format("no impact: the averaged {} ({}) is above 5% of its peak from the first sample at t = {} "
                            "s (no baseline before a rise)",
                            rec.strain ? "strain" : "force", columns, t.front()));
  s.impact = s.foot;
  while (s.impact + 1 < f.size() && !(f[s.impact + 1] < f[s.impact])) ++s.impact;
  if (s.impact + 1 == f.size())
    refuse(rec, fmt::format("no impact: the averaged force ({}) rises from its foot at t = {} s to the record's end "
                            "(no first peak)",
                            columns, t[s.foot]));
  const double t2 = t[s.impact] + rec.travel_time();
  if (t.back() < t2)
    refuse(rec, fmt::format("ends at t = {} s, before t2 = t1 + 2L/c = {} s (t1 = {} s, 2L/c = {} s): a record "
                            "must last to t2 after impact",
                            t.back(), t2, t[s.impact], rec.travel_time()));
  const double rise = t[s.impact] - t[s.foot];
  while (s.baseline < s.foot && t[s.foot] - t[s.baseline] > rise) ++s.baseline;
  if (s.baseline < least_baseline)
    refuse(rec, fmt::format("starts too late for the offsets: {} samples more than one rise time ({} s) before the "
                            "foot at t = {} s, at least {} needed",
                            s.baseline, rise, t[s.foot], least_baseline));
}

void remove_offset(std::vector<double>& x, std::size_t baseline) {
  double mean = 0.0;
  for (std::size_t k = 0; k < baseline; ++k) mean += x[k];
  mean /= static_cast<double>(baseline);
  for (auto& v : x) v -= mean;
}

// Two channels of one quantity differing at t1 by more than half the larger: bending, or a faulty gauge.
void check_channels(const PileRecord& rec, const std::vector<std::vector<double>>& channels,
                    const std::vector<std::string>& names, std::string_view key, const PileSignals& s) {
  for (std::size_t i = 0; i < channels.size(); ++i)
    for (std::size_t j = i + 1; j < channels.size(); ++j) {
      const double a = channels[i][s.impact], b = channels[j][s.impact];
      if (std::abs(a - b) > channel_spread * std::max(std::abs(a), std::abs(b)))
        refuse(rec, fmt::format("{} channels \"{}\" and \"{}\" differ at t1 = {} s: {:.6g} and {:.6g} (|X1 - X2| > "
                                "0.5 max(|X1|, |X2|)): bending, or a faulty gauge",
                                key, names[i], names[j], s.t1(), a, b));
    }
}

void check_proportional(const PileRecord& rec, const PileSignals& s) {
  const double f = s.force[s.impact], zv = rec.impedance() * s.velocity[s.impact];
  const double ratio = f / zv;
  if (!(std::abs(ratio - 1.0) <= impact_mismatch))
    refuse(rec, fmt::format("force and velocity disagree at impact: F / (Z v) = {:.4g} at t1 = {} s (F = {:.6g} N, "
                            "Z v = {:.6g} N, Z = {:.6g} N s/m; |F / (Z v) - 1| must be <= 0.3): check the channels' "
                            "units, calibration and polarity",
                            ratio, s.t1(), f, zv, rec.impedance()));
}

// A zero-phase low-pass: Butterworth's second-order section (bilinear
// transform, prewarped to `cutoff`) run forward and then backward, so that
// the record is not delayed and the response is |H|^2, fourth order, -6 dB
// at the cutoff. Each pass starts at rest at its first sample's value.
void low_pass(std::vector<double>& x, double cutoff, double dt) {
  const double k = std::tan(std::numbers::pi * cutoff * dt), norm = 1.0 / (1.0 + std::numbers::sqrt2 * k + k * k);
  const double b0 = k * k * norm, b1 = 2.0 * b0, a1 = 2.0 * (k * k - 1.0) * norm;
  const double a2 = (1.0 - std::numbers::sqrt2 * k + k * k) * norm;
  auto pass = [&](auto first, auto last) {
    const double rest = *first;
    double x1 = 0.0, x2 = 0.0, y1 = 0.0, y2 = 0.0;
    for (auto it = first; it != last; ++it) {
      const double in = *it - rest, out = b0 * (in + x2) + b1 * x1 - a1 * y1 - a2 * y2;
      x2 = x1;
      x1 = in;
      y2 = y1;
      y1 = out;
      *it = out + rest;
    }
  };
  pass(x.begin(), x.end());
  pass(x.rbegin(), x.rend());
}

// Every channel low-passed at `cutoff`, or at a quarter of the sampling
// rate when that is lower (a record sampled at 10 kHz is filtered at 2.5
// kHz: its noise would otherwise fool the foot and t1). A record whose steps
// differ by more than 1% is not filtered; `note` says so. Returns the
// cutoff applied, 0 for none.
double filter_channels(const std::vector<double>& t, CsvColumns& columns, double cutoff, std::string& note) {
  if (cutoff <= 0.0 || t.size() < 3) return 0.0;
  const double dt = (t.back() - t.front()) / static_cast<double>(t.size() - 1);
  for (std::size_t k = 1; k < t.size(); ++k)
    if (std::abs(t[k] - t[k - 1] - dt) > 0.01 * dt) {
      note = fmt::format(
          "the samples are not evenly spaced (at t = {} s the step is {} s, the mean {} s): the record "
          "is matched unfiltered",
          t[k - 1], t[k] - t[k - 1], dt);
      return 0.0;
    }
  const double applied = std::min(cutoff, 0.25 / dt);
  for (auto& c : columns.data) low_pass(c, applied, dt);
  return applied;
}

}  // namespace

PileSignals read_pile_signals(const PileRecord& rec, double cutoff) {
  std::vector<std::string> names = rec.force_columns, keys(rec.force_columns.size(), rec.strain ? "strain" : "force");
  names.insert(names.end(), rec.velocity_columns.begin(), rec.velocity_columns.end());
  keys.resize(names.size(), rec.acceleration ? "acceleration" : "velocity");
  CsvColumns columns = read_csv_columns(rec.layout, rec.csv, names, keys);
  PileSignals s;
  s.cutoff = filter_channels(columns.t, columns, cutoff, s.filter_note);
  s.filtered = s.cutoff > 0.0;
  s.t = std::move(columns.t);
  const auto forces = static_cast<std::ptrdiff_t>(rec.force_columns.size());
  s.force_channels.assign(columns.data.begin(), columns.data.begin() + forces);
  s.velocity_channels.assign(columns.data.begin() + forces, columns.data.end());
  const double ea = rec.segments.front().modulus * rec.area();
  if (rec.strain)
    for (auto& c : s.force_channels)
      for (auto& v : c) v *= ea;  // ASTM D4945: F = E A strain at the gauges
  find_impact(rec, s.t, average(s.force_channels), s);
  for (auto& c : s.force_channels) remove_offset(c, s.baseline);
  for (auto& c : s.velocity_channels) {
    remove_offset(c, s.baseline);
    if (rec.acceleration) c = integral(s.t, c);
  }
  check_channels(rec, s.force_channels, rec.force_columns, rec.strain ? "strain" : "force", s);
  check_channels(rec, s.velocity_channels, rec.velocity_columns,
                 rec.acceleration ? "acceleration (integrated)" : "velocity", s);
  s.force = average(s.force_channels);
  s.velocity = average(s.velocity_channels);
  check_proportional(rec, s);
  s.displacement = integral(s.t, s.velocity);
  std::vector<double> power(s.t.size());
  for (std::size_t k = 0; k < power.size(); ++k) power[k] = s.force[k] * s.velocity[k];
  s.energy = integral(s.t, power);
  return s;
}

}  // namespace barimpact
