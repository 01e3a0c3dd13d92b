// The Case method and the analyser's quantities of a measured blow
// (Rausche, Goble & Likins 1985; Rausche & Goble 1979; ASTM D4945).
#include "barimpact/pda/case_method.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace barimpact {

namespace {

constexpr double case_window = 0.030;   // s: rmx is sought within 30 ms of t1
constexpr double bta_threshold = 0.01;  // dWu below 1% of Wd(t1): no defect

double interpolate(const std::vector<double>& t, const std::vector<double>& y, double at) {
  if (at <= t.front()) return y.front();
  if (at >= t.back()) return y.back();
  const auto k = static_cast<std::size_t>(std::upper_bound(t.begin(), t.end(), at) - t.begin());
  const double w = (at - t[k - 1]) / (t[k] - t[k - 1]);
  return (1.0 - w) * y[k - 1] + w * y[k];
}

// rmx: the largest Case resistance at the samples t1 <= t <= min(t1 + 30 ms, t_end - 2L/c).
void find_rmx(CaseMethodResult& r) {
  const auto& t = r.waves.t;
  const double T = r.record.travel_time();
  const double last = std::min(r.t1 + case_window, t.back() - T);
  r.rmx = -std::numeric_limits<double>::infinity();
  for (std::size_t k = r.signals.impact; k < t.size() && t[k] <= last; ++k) {
    const double rk = case_resistance(r.waves, t[k], T, r.record.damping);
    if (rk > r.rmx) {
      r.rmx = rk;
      r.rmx_time = t[k];
    }
  }
  r.rsp = case_resistance(r.waves, r.t1, T, r.record.damping);
}

// tsx: the largest -(Wd(t) + Wu(t + 2x/c)) / A(x) over the samples t in
// [t1, t2] and the depths whose two-way time ends on a sample, at a joint
// between segments (either side's area) or at the toe.
void find_tsx(CaseMethodResult& r) {
  const auto& rec = r.record;
  const auto& t = r.waves.t;
  const double T = rec.travel_time();
  std::vector<double> joints{0.0};
  for (const auto& s : rec.segments) joints.push_back(joints.back() + s.length);
  r.tsx = 0.0;
  for (std::size_t k = r.signals.impact; k < t.size() && t[k] <= r.t2; ++k) {
    auto consider = [&](double tau, double up, double area) {
      const double stress = -(r.waves.down[k] + up) / area;
      if (stress > r.tsx) {
        r.tsx = stress;
        r.tsx_time = t[k];
        r.tsx_depth = rec.depth_at(tau);
      }
    };
    // Only the uniform pile's area is known without a depth (the common case).
    const bool uniform = rec.segments.size() == 1;
    for (std::size_t j = k; j < t.size() && t[j] - t[k] <= T; ++j)
      consider(t[j] - t[k], r.waves.up[j], uniform ? rec.area() : rec.segment_at(rec.depth_at(t[j] - t[k])).area);
    for (std::size_t i = 0; i < joints.size(); ++i) {
      const double tau = rec.two_way_time(joints[i]);
      if (t[k] + tau > t.back()) continue;
      const double up = r.waves.up_at(t[k] + tau);
      if (i > 0) consider(tau, up, rec.segments[i - 1].area);
      if (i < rec.segments.size()) consider(tau, up, rec.segments[i].area);
    }
  }
}

// Rausche and Goble's beta: the wave up's drop dWu below Wu(t1) before the
// toe's reflection (t2 less the rise time) against the wave down at t1.
void find_bta(CaseMethodResult& r) {
  const auto& t = r.waves.t;
  const std::size_t i1 = r.signals.impact;
  const double end = r.t2 - (r.t1 - r.t_foot);
  std::size_t least = i1;
  for (std::size_t k = i1 + 1; k < t.size() && t[k] < end; ++k)
    if (least == i1 || r.waves.up[k] < r.waves.up[least]) least = k;
  const double wd = r.waves.down[i1];
  const double drop = least == i1 ? 0.0 : r.waves.up[i1] - r.waves.up[least];
  if (drop <= bta_threshold * wd) return;  // beta = 1, no depth
  r.bta = (wd - drop) / (wd + drop);
  r.bta_depth = r.record.depth_at(t[least] - r.t1);
}

}  // namespace

double PileWaves::down_at(double at) const {
  return interpolate(t, down, at);
}

double PileWaves::up_at(double at) const {
  return interpolate(t, up, at);
}

PileWaves pile_waves(const PileRecord& record, const PileSignals& s) {
  PileWaves w;
  w.t = s.t;
  const double z = record.impedance();
  for (std::size_t k = 0; k < s.t.size(); ++k) {
    w.velocity_z.push_back(z * s.velocity[k]);
    w.down.push_back(0.5 * (s.force[k] + w.velocity_z[k]));
    w.up.push_back(0.5 * (s.force[k] - w.velocity_z[k]));
  }
  return w;
}

double case_resistance(const PileWaves& w, double t, double travel_time, double damping) {
  return (1.0 - damping) * w.down_at(t) + (1.0 + damping) * w.up_at(t + travel_time);
}

CaseMethodResult analyse_pda(const PileRecord& record, PileSignals signals) {
  CaseMethodResult r;
  r.record = record;
  r.signals = std::move(signals);
  const auto& s = r.signals;
  r.waves = pile_waves(record, s);
  r.t_foot = s.t_foot();
  r.t1 = s.t1();
  r.t2 = r.t1 + record.travel_time();
  r.fmx = *std::max_element(s.force.begin(), s.force.end());
  r.vmx = *std::max_element(s.velocity.begin(), s.velocity.end());
  r.emx = *std::max_element(s.energy.begin(), s.energy.end());
  r.dmx = *std::max_element(s.displacement.begin(), s.displacement.end());
  r.csx = r.fmx / record.area();
  r.ratio_at_impact = s.force[s.impact] / r.waves.velocity_z[s.impact];
  find_rmx(r);
  find_tsx(r);
  find_bta(r);
  return r;
}

CaseMethodResult analyse_pda(const PileRecord& record) {
  return analyse_pda(record, read_pile_signals(record));
}

}  // namespace barimpact
