#include "barimpact/hopkinson/analysis.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "barimpact/hopkinson/dispersion.hpp"
#include "barimpact/model/input_error.hpp"
#include "plausible.hpp"

namespace barimpact {

namespace {

namespace hp = hopkinson_plausible;

constexpr double nan = std::numeric_limits<double>::quiet_NaN();
constexpr double foot_fraction = 0.02;               // the foot: at or below 2% of the incident peak
constexpr double pulse_rms_multiple = 5.0;           // a pulse stands 5 baseline rms above the noise ...
constexpr double pulse_peak_fraction = 0.01;         // ... and 1% of the incident peak
constexpr double equilibrium_force_fraction = 0.05;  // equilibrium is shown where both forces pass 5% of their peak
constexpr double equilibrium_tolerance = 0.05;
constexpr double offset_strain = 0.002;  // the 0.2% offset yield
constexpr int max_rounds = 50;           // of baseline and foot, and of the first pulse's peak
// Noise above 1% of the peak could carry a baseline sample past the foot's
// 2% level (at 2 rms) or the trigger's: the pulse is then found on a moving
// average that brings the noise to 0.5% of the peak (an average of m samples
// divides white noise's rms by sqrt(m)), of at most a twentieth of the record.
constexpr double smoothing_noise = 0.01, smoothed_noise = 0.005;
constexpr std::size_t min_baseline = 8;  // samples before the foot to measure the noise's rms on

[[noreturn]] void refuse(const GaugeSignal& s, const std::string& rule) {
  throw InputError(fmt::format("{}: {}", s.label, rule));
}

// The mean of v[0, n) and the rms about it.
std::pair<double, double> mean_rms(const std::vector<double>& v, std::size_t n) {
  if (n == 0) return {0.0, 0.0};
  const double mean = std::accumulate(v.begin(), v.begin() + static_cast<long>(n), 0.0) / static_cast<double>(n);
  double sq = 0.0;
  for (std::size_t k = 0; k < n; ++k) sq += (v[k] - mean) * (v[k] - mean);
  return {mean, std::sqrt(sq / static_cast<double>(n))};
}

double median(std::vector<double> v) {
  const auto mid = v.begin() + static_cast<long>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  return *mid;
}

// The rms of Gaussian noise from the median absolute deviation (x 1.4826),
// which the minority of samples in a pulse does not move.
double robust_rms(std::vector<double> v) {
  const double m = median(v);
  for (auto& x : v) x = std::abs(x - m);
  return 1.4826 * median(std::move(v));
}

// The noise's rms on a record: the larger of the spread of its first tenth
// (slow noise, hum) and that of its successive differences over sqrt(2)
// (fast noise, wherever the pulses are).
double noise_estimate(const std::vector<double>& c) {
  const std::vector<double> head(c.begin(), c.begin() + static_cast<long>(std::max<std::size_t>(c.size() / 10, 1)));
  std::vector<double> steps(c.size() - 1);
  for (std::size_t k = 0; k + 1 < c.size(); ++k) steps[k] = c[k + 1] - c[k];
  return std::max(robust_rms(head), robust_rms(std::move(steps)) / std::sqrt(2.0));
}

// The moving average's width that finds the pulse under the record's noise (1: none).
std::size_t smoothing_width(const std::vector<double>& c) {
  const double peak = *std::max_element(c.begin(), c.end()), noise = noise_estimate(c);
  if (!(peak > 0) || !(noise > smoothing_noise * peak)) return 1;
  const double m = std::ceil(std::pow(noise / (smoothed_noise * peak), 2));
  return static_cast<std::size_t>(std::min(m, static_cast<double>(std::max<std::size_t>(c.size() / 20, 1))));
}

// The centred moving average of m samples (fewer at the record's ends).
std::vector<double> moving_average(const std::vector<double>& v, std::size_t m) {
  std::vector<double> sum(v.size() + 1, 0.0), out(v.size());
  for (std::size_t k = 0; k < v.size(); ++k) sum[k + 1] = sum[k] + v[k];
  const std::size_t half = m / 2;
  for (std::size_t k = 0; k < v.size(); ++k) {
    const std::size_t lo = k > half ? k - half : 0, hi = std::min(v.size(), k + half + 1);
    out[k] = (sum[hi] - sum[lo]) / static_cast<double>(hi - lo);
  }
  return out;
}

std::size_t samples_before(const std::vector<double>& t, double time) {
  return static_cast<std::size_t>(std::lower_bound(t.begin(), t.end(), time) - t.begin());
}

// Strain at gauge time `time` by linear interpolation; nan outside [from, to]
// (the record, or a given window).
class Interpolant {
 public:
  Interpolant(const GaugeSignal& s, double from, double to) : s_(s), from_(from), to_(to) {}
  double operator()(double time) {
    const auto& t = s_.t;
    if (!(time >= from_ && time <= to_)) return nan;
    while (k_ + 1 < t.size() && t[k_ + 1] < time) ++k_;  // rows come in increasing time
    while (k_ > 0 && t[k_] > time) --k_;
    if (k_ + 1 == t.size()) return s_.strain[k_];
    const double f = (time - t[k_]) / (t[k_ + 1] - t[k_]);
    return s_.strain[k_] + f * (s_.strain[k_ + 1] - s_.strain[k_]);
  }

 private:
  const GaugeSignal& s_;
  double from_, to_;
  std::size_t k_ = 0;
};

// The least-squares line v = slope u + intercept through the points.
struct Line2 {
  double slope = nan, intercept = nan;
};
Line2 least_squares(const std::vector<double>& u, const std::vector<double>& v) {
  const double n = static_cast<double>(u.size());
  const double mu = std::accumulate(u.begin(), u.end(), 0.0) / n;
  const double mv = std::accumulate(v.begin(), v.end(), 0.0) / n;
  double suu = 0.0, suv = 0.0;
  for (std::size_t k = 0; k < u.size(); ++k) {
    suu += (u[k] - mu) * (u[k] - mu);
    suv += (u[k] - mu) * (v[k] - mv);
  }
  if (!(suu > 0)) return {};
  return {suv / suu, mv - suv / suu * mu};
}

// A given window ([incident] or [transmitted] start and end) lies inside its
// record and holds two samples or more: else no row could be read from it.
void check_given_window(const GaugeSignal& s, const ChannelSetup& ch) {
  const auto& t = s.t;
  if (*ch.start < t.front() || *ch.end > t.back())
    refuse(s, fmt::format("{0}.start = {1}, {0}.end = {2}: the window is not inside the record (t = {3} to {4})",
                          ch.section, *ch.start, *ch.end, t.front(), t.back()));
  const auto inside = std::upper_bound(t.begin(), t.end(), *ch.end) - std::lower_bound(t.begin(), t.end(), *ch.start);
  if (inside < 2)
    refuse(s, fmt::format("{0}.start = {1}, {0}.end = {2}: the window holds {3} sample{4}, fewer than two", ch.section,
                          *ch.start, *ch.end, inside, inside == 1 ? "" : "s"));
}

class Analysis {
 public:
  Analysis(const HopkinsonSetup& setup, GaugeSignal inc, GaugeSignal tr)
      : setup_(setup), inc_(std::move(inc)), tr_(std::move(tr)) {
    r_.setup = setup;
  }

  HopkinsonResult run() {
    check_clock(inc_, setup_.incident);
    check_clock(tr_, setup_.transmitted);
    find_incident_window();
    subtract_baselines();
    check_pulses();
    correct_dispersion();
    place_pulses();
    tabulate();
    measure_peaks();
    check_results();
    measure_equilibrium();
    if (setup_.fit_elastic) fit();
    check_bounds();
    return std::move(r_);
  }

 private:
  // In SI a record's times are seconds: its mean sample interval within
  // hopkinson_plausible::sample_interval, else they are in another unit.
  void check_clock(const GaugeSignal& s, const ChannelSetup& ch) const {
    if (!setup_.si || s.t.size() < 2) return;
    const double dt = (s.t.back() - s.t.front()) / static_cast<double>(s.t.size() - 1);
    const auto& b = hp::sample_interval;
    if (!b.holds(dt))
      refuse(s, fmt::format("{}.time: the samples are {:.4g} apart on average: {}outside [{:g}, {:g}] s (the "
                            "records' times are in seconds)",
                            ch.section, dt, hp::meant(dt, b, hp::time_units), b.lo, b.hi));
  }

  // c = -(strain - baseline): compression positive (its moving average under noise).
  void compression(double baseline) {
    c_.resize(inc_.t.size());
    for (std::size_t k = 0; k < c_.size(); ++k) c_[k] = -(inc_.strain[k] - baseline);
    if (smooth_ > 1) c_ = moving_average(c_, smooth_);
  }

  void find_incident_window() {
    auto& a = r_.alignment;
    const std::size_t n = inc_.t.size();
    if (n < 8) refuse(inc_, fmt::format("holds {} samples: too few to find a pulse", n));
    if (setup_.incident.start) {
      given_window();
    } else {
      a.method = "trigger";
      // A first baseline from the record's first tenth (its median: robust if
      // the pulse starts there), then the foot, the mean before it, and again
      // until the foot stays.
      std::vector<double> head(inc_.strain.begin(),
                               inc_.strain.begin() + static_cast<long>(std::max<std::size_t>(n / 10, 1)));
      std::nth_element(head.begin(), head.begin() + static_cast<long>(head.size() / 2), head.end());
      a.baseline_incident = head[head.size() / 2];
      compression(a.baseline_incident);
      smooth_ = smoothing_width(c_);
      std::size_t last_foot = n;
      for (a.iterations = 1; a.iterations <= max_rounds; ++a.iterations) {
        compression(a.baseline_incident);
        if (a.iterations == 1) check_polarity();
        trigger_window();
        if (foot_ == last_foot) break;
        last_foot = foot_;
        a.baseline_incident = mean_rms(inc_.strain, foot_).first;
      }
      if (a.iterations > max_rounds) {
        a.iterations = max_rounds;
        r_.warnings.push_back(fmt::format(
            "the incident foot did not settle in {} rounds of baseline and foot: check the window", max_rounds));
      }
    }
    if (foot_ < min_baseline)
      refuse(inc_, fmt::format("only {} samples before the incident foot (t = {:.6g}): too few to measure the "
                               "baseline noise ({} or more)",
                               foot_, inc_.t[foot_], min_baseline));
    a.noise_incident = mean_rms(inc_.strain, foot_).second;
    a.trigger_level = setup_.trigger * a.incident_peak;
    a.foot = inc_.t[foot_];
    a.incident = {inc_.t[foot_], inc_.t[end_]};
  }

  // [incident] start and end: the nearest sample to start is the foot.
  void given_window() {
    auto& a = r_.alignment;
    const auto& ch = setup_.incident;
    const auto& t = inc_.t;
    a.method = "windows";
    check_given_window(inc_, ch);
    foot_ = samples_before(t, *ch.start);
    if (foot_ > 0 && *ch.start - t[foot_ - 1] < t[foot_] - *ch.start) --foot_;
    end_ = samples_before(t, *ch.end);
    if (end_ == t.size() || t[end_] > *ch.end) --end_;
    if (foot_ == 0) refuse(inc_, "incident.start is the record's first sample: a baseline needs samples before it");
    a.baseline_incident = mean_rms(inc_.strain, foot_).first;
    compression(a.baseline_incident);
    a.incident_peak =
        *std::max_element(c_.begin() + static_cast<long>(foot_), c_.begin() + static_cast<long>(end_) + 1);
    if (!(a.incident_peak > 0))
      refuse(inc_, "holds no compression in the given window (the incident pulse is negative)");
  }

  // The first pulse must be compression (negative): else the polarity is
  // wrong. The first excursion past half the largest is the incident pulse
  // whatever the baseline's first guess and the noise.
  void check_polarity() const {
    double largest = 0.0;
    for (double v : c_) largest = std::max(largest, std::abs(v));
    for (double v : c_)
      if (std::abs(v) >= 0.5 * largest) {
        if (v < 0)
          refuse(inc_,
                 "its first pulse is tension: the incident pulse must be compression, negative (set polarity = "
                 "-1 if the bridge records compression positive)");
        return;
      }
  }

  // The foot: the last sample before the trigger crossing at or below 2% of
  // the peak; the end: the first such sample after the pulse falls back.
  void trigger_window() {
    const std::size_t n = c_.size();
    double peak = *std::max_element(c_.begin(), c_.end());
    if (!(peak > 0)) refuse(inc_, "holds no compression pulse (the incident pulse is negative: tension is positive)");
    std::size_t cross = 0, down = n;
    for (int round = 0; round < max_rounds; ++round) {  // the first pulse's peak, not a later pulse's
      const double level = setup_.trigger * peak;
      cross = static_cast<std::size_t>(std::find_if(c_.begin(), c_.end(), [&](double v) { return v >= level; }) -
                                       c_.begin());
      down = static_cast<std::size_t>(
          std::find_if(c_.begin() + static_cast<long>(cross), c_.end(), [&](double v) { return v < level; }) -
          c_.begin());
      const double first =
          *std::max_element(c_.begin() + static_cast<long>(cross), c_.begin() + static_cast<long>(down));
      if (first == peak) break;
      peak = first;
    }
    r_.alignment.incident_peak = peak;
    std::size_t k = cross;
    while (k > 0 && c_[k] > foot_fraction * peak) --k;
    if (k == 0)  // the pulse, or its foot, is the first sample
      refuse(inc_, "the incident pulse starts at the record's first sample: a baseline needs samples before it");
    foot_ = k;
    k = down;
    while (k < n && c_[k] > foot_fraction * peak) ++k;
    end_ = std::min(k, n - 1);
  }

  // Each signal loses its mean before the incident foot (the transmitted
  // record's own samples before that time).
  void subtract_baselines() {
    auto& a = r_.alignment;
    for (auto& v : inc_.strain) v -= a.baseline_incident;
    const std::size_t before = samples_before(tr_.t, a.foot);
    if (before == 0)
      refuse(tr_, fmt::format("the record starts at t = {}, after the incident foot (t = {}): no baseline before it",
                              tr_.t.front(), a.foot));
    if (before < min_baseline)
      refuse(tr_, fmt::format("only {} samples before the incident foot (t = {:.6g}): too few to measure the "
                              "baseline noise ({} or more)",
                              before, a.foot, min_baseline));
    std::tie(a.baseline_transmitted, a.noise_transmitted) = mean_rms(tr_.strain, before);
    for (auto& v : tr_.strain) v -= a.baseline_transmitted;
  }

  // A pulse on each channel, noise below half the trigger level, and an
  // incident window the reflected pulse does not overlap.
  void check_pulses() {
    const auto& a = r_.alignment;
    const double noise_limit = 0.5 * a.trigger_level;
    if (!(a.incident_peak > pulse_rms_multiple * a.noise_incident))
      refuse(inc_, fmt::format("no pulse: its largest compression {:.4g} is not beyond 5 times the baseline rms {:.4g}",
                               a.incident_peak, a.noise_incident));
    const double level = std::max(pulse_rms_multiple * a.noise_transmitted, pulse_peak_fraction * a.incident_peak);
    const std::size_t from = samples_before(tr_.t, a.foot);
    if (std::none_of(tr_.strain.begin() + static_cast<long>(from), tr_.strain.end(),
                     [&](double v) { return std::abs(v) > level; }))
      refuse(tr_, fmt::format("no pulse: no sample after the incident foot is beyond both 5 times the baseline rms "
                              "({:.4g}) and 1% of the incident peak ({:.4g})",
                              pulse_rms_multiple * a.noise_transmitted, pulse_peak_fraction * a.incident_peak));
    for (const auto& [s, noise] : {std::pair{&inc_, a.noise_incident}, std::pair{&tr_, a.noise_transmitted}})
      if (noise > noise_limit)
        refuse(*s, fmt::format("baseline noise: the rms {:.4g} before the incident pulse is above half the trigger "
                               "level ({} x the incident peak {:.4g} / 2 = {:.4g}); filter the signal or raise "
                               "window.trigger",
                               noise, setup_.trigger, a.incident_peak, noise_limit));
    const double d = setup_.incident.gauge_to_specimen, c0 = setup_.incident_bar.wave_speed;
    const double length = a.incident.end - a.incident.start;
    if (setup_.si && !hp::pulse_duration.holds(length))
      refuse(inc_, fmt::format("incident.time: the incident pulse lasts {:.4g}: {}longer than any striker's, 2 "
                               "L / c0 (at most {:g} s; the records' times are in seconds)",
                               length, hp::meant(length, hp::pulse_duration, hp::time_units), hp::pulse_duration.hi));
    if (length > 2.0 * d / c0)
      refuse(inc_,
             fmt::format("pulses too close to separate: the incident window ({:.6g} to {:.6g}, {:.4g} long) is "
                         "longer than 2 gauge_to_specimen / c0 = {:.4g}, so the reflected pulse reaches the gauge "
                         "before it ends (a gauge farther from the specimen, or a shorter striker)",
                         a.incident.start, a.incident.end, length, 2.0 * d / c0));
  }

  void correct_dispersion() {
    auto& a = r_.alignment;
    const auto& bar = setup_.incident_bar;
    if (!bar.dispersion) return;
    if (inc_.simulated && tr_.simulated) {
      a.dispersion_note = "not applied: a one-dimensional simulation has no dispersion to correct";
      return;
    }
    const double di = setup_.incident.gauge_to_specimen, dt = setup_.transmitted.gauge_to_specimen;
    // The incident pulse travels forward to the face, the reflected and the
    // transmitted back from the faces: each is moved by its own distance.
    inc_forward_ = inc_;
    inc_backward_ = inc_;
    if (!inc_.simulated) {  // a simulated record has no dispersion to undo
      const DispersionCorrection incident(bar);
      a.dispersion_terms = incident.apply(inc_forward_, di);
      incident.apply(inc_backward_, -di);
    }
    if (!tr_.simulated) a.dispersion_terms = DispersionCorrection(setup_.transmitter_bar).apply(tr_, -dt);
    a.dispersion_note = "Pochhammer-Chree phase velocity for the bars' diameter and Poisson's ratio";
    dispersed_ = true;
  }

  // Where the reflected and transmitted pulses are read, by travel times.
  void place_pulses() {
    auto& a = r_.alignment;
    const double ci = setup_.incident_bar.wave_speed, ct = setup_.transmitter_bar.wave_speed;
    const double di = setup_.incident.gauge_to_specimen, dt = setup_.transmitted.gauge_to_specimen;
    a.wave_speed_incident = ci;
    a.wave_speed_transmitted = ct;
    a.to_front_face = di / ci;
    a.reflected_shift = 2.0 * di / ci;
    a.transmitted_shift = di / ci + dt / ct;
    if (setup_.transmitted.start) {
      check_given_window(tr_, setup_.transmitted);
      a.transmitted_shift = *setup_.transmitted.start - a.foot;
    }
    const double length = a.incident.end - a.incident.start;
    a.reflected = {a.incident.start + a.reflected_shift, a.incident.end + a.reflected_shift};
    a.transmitted = setup_.transmitted.start
                        ? PulseWindow{*setup_.transmitted.start, *setup_.transmitted.end}
                        : PulseWindow{a.foot + a.transmitted_shift, a.foot + a.transmitted_shift + length};
    // A pulse whose window starts after its record ends gives no row at all.
    // (in mm: the distance that would place it in the record, in metres.)
    const auto in_mm = [](double d, double farthest) {
      return hp::meant(d, {0.0, farthest, 0.5 * farthest}, {{1e-3, "mm"}});
    };
    if (a.reflected.start > inc_.t.back())
      refuse(inc_, fmt::format("incident.gauge_to_specimen = {}: {}the reflected pulse reaches the gauge 2 "
                               "gauge_to_specimen / c0 = {:.4g} after the incident foot, at t = {:.6g}, after the "
                               "record ends (t = {:.6g})",
                               di, in_mm(di, 0.5 * (inc_.t.back() - a.foot) * ci), a.reflected_shift, a.reflected.start,
                               inc_.t.back()));
    if (!setup_.transmitted.start && a.transmitted.start > tr_.t.back())
      refuse(tr_, fmt::format("transmitted.gauge_to_specimen = {}: {}the transmitted pulse reaches its gauge "
                              "incident.gauge_to_specimen / c_i + transmitted.gauge_to_specimen / c_t = {:.4g} after "
                              "the incident foot, at t = {:.6g}, after the record ends (t = {:.6g})",
                              dt, in_mm(dt, (tr_.t.back() - a.foot - di / ci) * ct), a.transmitted_shift,
                              a.transmitted.start, tr_.t.back()));
    if (a.reflected.end > inc_.t.back())
      r_.warnings.push_back(
          fmt::format("the incident record ends at t = {:.6g}, before the reflected pulse's window "
                      "(to {:.6g}): later rows are nan",
                      inc_.t.back(), a.reflected.end));
    if (a.transmitted.end > tr_.t.back())
      r_.warnings.push_back(
          fmt::format("the transmitted record ends at t = {:.6g}, before its pulse's window (to "
                      "{:.6g}): later rows are nan",
                      tr_.t.back(), a.transmitted.end));
  }

  void add(const std::string& name) { r_.columns.push_back({name, std::vector<double>(rows_, nan)}); }
  std::vector<double>& column(const std::string& name) { return r_.column(name); }

  void tabulate();
  void measure_peaks();
  void check_results() const;
  void check_bounds();
  void measure_equilibrium();
  void fit();

  const HopkinsonSetup& setup_;
  GaugeSignal inc_, tr_;
  GaugeSignal inc_forward_, inc_backward_;  // dispersion-corrected copies
  bool dispersed_ = false;
  HopkinsonResult r_;
  std::vector<double> c_;
  std::size_t foot_ = 0, end_ = 0, rows_ = 0;
  std::size_t smooth_ = 1;  // the moving average's width the pulse is found on
};

// The table: one row per incident sample from the foot to the window's end.
void Analysis::tabulate() {
  const auto& a = r_.alignment;
  rows_ = end_ - foot_ + 1;
  for (const auto& name : hopkinson_columns()) add(name);
  for (const char* name : {"incident", "reflected", "transmitted"}) add(name);
  auto &t = column("t"), &ei = column("incident"), &er = column("reflected"), &et = column("transmitted");
  const GaugeSignal& front = dispersed_ ? inc_forward_ : inc_;
  const GaugeSignal& back = dispersed_ ? inc_backward_ : inc_;
  Interpolant reflected(back, back.t.front(), back.t.back());
  const bool window = setup_.transmitted.start.has_value();
  Interpolant transmitted(tr_, window ? std::max(*setup_.transmitted.start, tr_.t.front()) : tr_.t.front(),
                          window ? std::min(*setup_.transmitted.end, tr_.t.back()) : tr_.t.back());
  for (std::size_t i = 0; i < rows_; ++i) {
    const double tk = inc_.t[foot_ + i];
    t[i] = tk - a.foot;
    ei[i] = front.strain[foot_ + i];
    er[i] = reflected(tk + a.reflected_shift);
    et[i] = transmitted(tk + a.transmitted_shift);
  }
  const auto& bi = setup_.incident_bar;
  const auto& bt = setup_.transmitter_bar;
  const double ls = setup_.specimen.length, as = setup_.specimen.area;
  auto &ff = column("force_front"), &fb = column("force_back");
  auto &s1 = column("stress_1w"), &s2 = column("stress_2w"), &s3 = column("stress_3w");
  auto &r1 = column("strain_rate_1w"), &r3 = column("strain_rate_3w");
  for (std::size_t i = 0; i < rows_; ++i) {
    ff[i] = -bi.modulus * bi.area * (ei[i] + er[i]);
    fb[i] = -bt.modulus * bt.area * et[i];
    s1[i] = fb[i] / as;
    s2[i] = ff[i] / as;
    s3[i] = (ff[i] + fb[i]) / (2.0 * as);
    r1[i] = 2.0 * bi.wave_speed * er[i] / ls;
    // The faces' velocities: front c_i (eps_r - eps_i) inward, back -c_t eps_t outward.
    r3[i] = (bi.wave_speed * (er[i] - ei[i]) + bt.wave_speed * et[i]) / ls;
  }
  // Strains: the trapezoidal integrals of the rates from t = 0.
  for (const auto& [rate, strain] :
       {std::pair{"strain_rate_1w", "strain_1w"}, std::pair{"strain_rate_3w", "strain_3w"}}) {
    const auto& rv = column(rate);
    auto& sv = column(strain);
    sv[0] = 0.0;
    for (std::size_t i = 1; i < rows_; ++i) sv[i] = sv[i - 1] + 0.5 * (t[i] - t[i - 1]) * (rv[i] + rv[i - 1]);
  }
}

HopkinsonPeak largest(const std::vector<double>& v, const std::vector<double>& t) {
  HopkinsonPeak p{nan, nan};
  for (std::size_t i = 0; i < v.size(); ++i)
    if (std::isfinite(v[i]) && !(v[i] <= p.value)) p = {v[i], t[i]};
  return p;
}

void Analysis::measure_peaks() {
  const auto& t = r_.column("t");
  r_.peak_stress_1w = largest(r_.column("stress_1w"), t);
  r_.peak_stress_2w = largest(r_.column("stress_2w"), t);
  r_.peak_stress_3w = largest(r_.column("stress_3w"), t);
  r_.peak_strain_rate_1w = largest(r_.column("strain_rate_1w"), t);
  r_.peak_strain_rate_3w = largest(r_.column("strain_rate_3w"), t);
}

// A result that is not finite is never a success: every row nan (no reflected
// or transmitted sample read) or a specimen never in compression is refused.
void Analysis::check_results() const {
  const double stress = r_.peak_stress_3w.value, rate = r_.peak_strain_rate_3w.value;
  if (!std::isfinite(stress) || !std::isfinite(rate))
    throw InputError(fmt::format(
        "{}: no row has a finite 3-wave stress and strain rate: the reflected and transmitted pulses are not in "
        "their records (check incident.gauge_to_specimen, transmitted.gauge_to_specimen, transmitted.start and "
        "end, the bars' wave speed and the records' times)",
        setup_.origin.string()));
  if (!(stress > 0))
    throw InputError(fmt::format(
        "{}: the 3-wave stress is never compression (its peak is {:.4g}): the pulses are not where the setup places "
        "them (check transmitted.start and end, each gauge_to_specimen and polarity)",
        setup_.origin.string(), stress));
}

// In SI, results beyond what any bar test reaches (hopkinson_plausible) warn:
// a unit slip the setup's checks let through.
void Analysis::check_bounds() {
  if (!setup_.si) return;
  const auto warn = [&](std::string_view what, double value, double bound) {
    r_.warnings.push_back(fmt::format(
        "implausible-result: the {} {:.4g} is beyond {:g}, more than a bar test reaches: check the setup's units (m, "
        "s, Pa, kg/m^3)",
        what, value, bound));
  };
  if (r_.peak_strain_rate_3w.value > hp::highest_strain_rate)
    warn("3-wave peak strain rate", r_.peak_strain_rate_3w.value, hp::highest_strain_rate);
  if (r_.peak_stress_3w.value > hp::highest_stress)
    warn("3-wave peak stress", r_.peak_stress_3w.value, hp::highest_stress);
  if (r_.fit.modulus > hp::highest_modulus) warn("fitted modulus", r_.fit.modulus, hp::highest_modulus);
}

// equilibrium where both forces pass 5% of their peak; the time from which
// it stays within 5% up to the 3-wave peak stress.
void Analysis::measure_equilibrium() {
  const auto& t = r_.column("t");
  const auto& ff = r_.column("force_front");
  const auto& fb = r_.column("force_back");
  auto* eq = &column("equilibrium");
  const double pf = largest(ff, t).value, pb = largest(fb, t).value;
  for (std::size_t i = 0; i < rows_; ++i)
    if (ff[i] > equilibrium_force_fraction * pf && fb[i] > equilibrium_force_fraction * pb)
      (*eq)[i] = 2.0 * (ff[i] - fb[i]) / (ff[i] + fb[i]);
  for (std::size_t i = 0; i < rows_; ++i)
    if (std::abs((*eq)[i]) < equilibrium_tolerance) {
      r_.equilibrium_first = t[i];
      break;
    }
  if (!std::isfinite(r_.peak_stress_3w.t)) return;
  const auto peak = static_cast<std::size_t>(std::find(t.begin(), t.end(), r_.peak_stress_3w.t) - t.begin());
  std::size_t j = peak + 1;
  while (j > 0 && std::abs((*eq)[j - 1]) < equilibrium_tolerance) --j;  // nan ends it too
  if (j <= peak)
    r_.equilibrium_from = t[j];
  else
    r_.warnings.push_back(
        fmt::format("the specimen is not in equilibrium at the 3-wave peak stress (|equilibrium| >= "
                    "{} or the forces below 5% of their peak there)",
                    equilibrium_tolerance));
}

// The samples of the loading branch, from `from` up to the peak, whose `key`
// (their stress or their strain) lies in `range`; `first` is the earliest
// one's index (peak + 1 when there is none).
struct BranchPoints {
  std::vector<double> strain, stress;
  std::size_t first = 0;
};

BranchPoints branch_points(const std::vector<double>& strain, const std::vector<double>& stress,
                           const std::vector<double>& key, std::size_t from, std::size_t peak,
                           std::pair<double, double> range) {
  BranchPoints b;
  b.first = peak + 1;
  for (std::size_t i = from; i <= peak; ++i)
    if (std::isfinite(strain[i]) && key[i] >= range.first && key[i] <= range.second) {
      b.strain.push_back(strain[i]);
      b.stress.push_back(stress[i]);
      b.first = std::min(b.first, i);
    }
  return b;
}

// The stress against strain line through the points: none (nan) below 3 points.
Line2 line_through(const BranchPoints& b) {
  return b.strain.size() >= 3 ? least_squares(b.strain, b.stress) : Line2{};
}

struct YieldPoint {
  double stress, strain;
};

// Where the curve, from `first` to the peak, first passes below the 0.2%
// offset line sigma = E (eps - eps0 - 0.002), between two samples linearly.
std::optional<YieldPoint> offset_yield(const std::vector<double>& strain, const std::vector<double>& stress,
                                       std::size_t first, std::size_t peak, double modulus, double strain_intercept) {
  auto offset = [&](std::size_t i) { return stress[i] - modulus * (strain[i] - strain_intercept - offset_strain); };
  for (std::size_t i = first; i < peak; ++i) {
    const double g0 = offset(i), g1 = offset(i + 1);
    if (g0 >= 0 && g1 < 0) {
      const double w = g0 / (g0 - g1);
      return YieldPoint{stress[i] + w * (stress[i + 1] - stress[i]), strain[i] + w * (strain[i + 1] - strain[i])};
    }
  }
  return std::nullopt;
}

// [fit]: the modulus over the elastic stress range (least squares on the
// loading branch, up to the 3-wave peak stress), the 0.2% offset yield where
// the curve crosses sigma = E (eps - eps0 - 0.002), the hardening modulus
// over the plastic strain range (given, or 20% to 90% of the way from the
// yield strain to the strain at the peak stress).
void Analysis::fit() {
  auto& f = r_.fit;
  const auto& t = r_.column("t");
  const auto& strain = r_.column("strain_3w");
  const auto& stress = r_.column("stress_3w");
  f.done = true;
  f.elastic_range = *setup_.fit_elastic;
  if (!std::isfinite(r_.peak_stress_3w.t)) {
    f.message = "no 3-wave stress to fit";
    return;
  }
  const auto peak = static_cast<std::size_t>(std::find(t.begin(), t.end(), r_.peak_stress_3w.t) - t.begin());
  const BranchPoints loading = branch_points(strain, stress, stress, 0, peak, f.elastic_range);
  f.elastic_points = static_cast<int>(loading.strain.size());
  const Line2 elastic = line_through(loading);
  if (!(elastic.slope > 0)) {
    f.message = fmt::format(
        "fit.elastic: {} samples of the loading branch have a 3-wave stress in [{}, {}]: too few "
        "for a modulus (3 or more with a rising stress)",
        loading.strain.size(), f.elastic_range.first, f.elastic_range.second);
    r_.warnings.push_back(f.message);
    return;
  }
  f.modulus = elastic.slope;
  f.strain_intercept = -elastic.intercept / elastic.slope;
  if (const auto yield = offset_yield(strain, stress, loading.first, peak, f.modulus, f.strain_intercept)) {
    f.yield_stress = yield->stress;
    f.yield_strain = yield->strain;
  }
  if (!f.yield_stress) {
    f.message = "no yield: the 3-wave curve stays above the 0.2% offset line up to its peak stress";
    return;
  }
  const double span = strain[peak] - *f.yield_strain;
  f.plastic_range =
      setup_.fit_plastic ? *setup_.fit_plastic : std::pair{*f.yield_strain + 0.2 * span, *f.yield_strain + 0.9 * span};
  // The plastic range is looked for from the elastic range's first sample on.
  const BranchPoints hardening = branch_points(strain, stress, strain, loading.first, peak, f.plastic_range);
  f.plastic_points = static_cast<int>(hardening.strain.size());
  const Line2 plastic = line_through(hardening);
  if (std::isfinite(plastic.slope)) {
    f.hardening_modulus = plastic.slope;
  } else {
    f.message = fmt::format(
        "fit.plastic: {} samples of the loading branch in the strain range [{:.6g}, {:.6g}]: too "
        "few for a hardening modulus",
        hardening.strain.size(), f.plastic_range.first, f.plastic_range.second);
    r_.warnings.push_back(f.message);
  }
}

}  // namespace

std::vector<double>& HopkinsonResult::column(const std::string& name) {
  for (auto& c : columns)
    if (c.name == name) return c.values;
  throw std::out_of_range("hopkinson: no column " + name);
}

const std::vector<double>& HopkinsonResult::column(const std::string& name) const {
  return const_cast<HopkinsonResult&>(*this).column(name);  // the search only: nothing is written
}

const std::vector<std::string>& hopkinson_columns() {
  static const std::vector<std::string> names{"t",           "strain_1w",      "strain_rate_1w", "stress_1w",
                                              "strain_3w",   "strain_rate_3w", "stress_2w",      "stress_3w",
                                              "force_front", "force_back",     "equilibrium"};
  return names;
}

HopkinsonResult analyse_hopkinson(const HopkinsonSetup& setup, GaugeSignal incident, GaugeSignal transmitted) {
  return Analysis(setup, std::move(incident), std::move(transmitted)).run();
}

HopkinsonResult analyse_hopkinson(const std::filesystem::path& setup_file) {
  return analyse_hopkinson(HopkinsonSetup::from_file(setup_file));
}

HopkinsonResult analyse_hopkinson(const HopkinsonSetup& setup) {
  auto incident = read_gauge_signal(setup.incident);  // the incident's errors first
  auto transmitted = read_gauge_signal(setup.transmitted);
  return analyse_hopkinson(setup, std::move(incident), std::move(transmitted));
}

}  // namespace barimpact
