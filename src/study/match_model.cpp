// Signal matching's forward model: the record's pile as a line, driven at
// the gauges by the measured velocity, with Smith's soil per run.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "barimpact/case/line_builder.hpp"
#include "barimpact/schemes/line_central_difference.hpp"
#include "barimpact/study/match.hpp"

namespace barimpact {

namespace {

// The pile below the gauges as a case: one bar per record segment, the toe's
// first (x = 0), welded, each with elements no longer than L / 100; Smith's
// toe at the near end (its soil set per run), the far end driven.
std::string pile_case(const PileRecord& record, double end, double step) {
  const double longest = record.length() / 100.0;
  std::string text;
  const auto& s = record.segments;
  for (std::size_t k = s.size(); k-- > 0;) {
    const auto elements = static_cast<int>(std::ceil(s[k].length / longest - 1e-9));
    text += fmt::format(
        "[[body]]\nname = \"segment{}\"\nlength = {:.17g}\nelements = {}\narea = {:.17g}\nmodulus = {:.17g}\n"
        "density = {:.17g}\n\n",
        k + 1, s[k].length, std::max(elements, 1), s[k].area, s[k].modulus, s[k].density);
  }
  for (std::size_t k = s.size() - 1; k-- > 0;)
    text += fmt::format("[[joint]]\nbetween = [\"segment{}\", \"segment{}\"]\nlaw = \"welded\"\n\n", k + 2, k + 1);
  text += "[near_end]\nlaw = \"smith\"\nultimate = 1.0\nquake = 0.00254\ndamping = 0.0\n\n";
  text += "[far_end]\nlaw = \"velocity\"\nvalue = \"0\"\n\n";
  text += fmt::format("[time]\nend = {:.17g}\nstep = {:.17g}\nscheme = \"central-difference\"\n", end, step);
  return text;
}

}  // namespace

double MatchSoil::shaft_total() const {
  double s = 0.0;
  for (double r : shaft) s += r;
  return s;
}

MatchModel::MatchModel(const PileRecord& record, const PileSignals& signals, double t_start, double t_end)
    : signals_(&signals), t_start_(t_start) {
  const double length = record.length();
  case_ = Case::from_string(pile_case(record, t_end - t_start, 1e-9));
  line_ = build_line(case_);
  // The far end's velocity along +x is the record's, downward positive:
  // v(t_start + s) for the run's time s.
  auto history = std::make_shared<SampledHistory>();
  for (std::size_t k = 0; k < signals.t.size(); ++k) {
    history->t.push_back(signals.t[k] - t_start);
    history->value.push_back(-signals.velocity[k]);
  }
  line_.far.history = history;
  segments_ = static_cast<std::size_t>(record.match.segments);
  const double embedded = record.match.embedded.value_or(length);
  length_ = length;
  top_ = length - embedded;
  segment_length_ = embedded / static_cast<double>(segments_);
  // Node j's share of segment i: the line builder's consistent shares of a
  // unit resistance spread over the segment (x - x0 = length - depth).
  const std::size_t n = line_.nodes();
  const BodyRange whole{"", false, 0, n - 1};
  shares_.assign(n, {});
  std::vector<double> share(n);
  for (std::size_t i = 0; i < segments_; ++i) {
    std::fill(share.begin(), share.end(), 0.0);
    add_shares(
        line_, whole, length - segment_bottom(i), length - segment_top(i),
        [&](double) { return 1.0 / segment_length_; }, share);
    for (std::size_t j = 0; j < n; ++j)
      if (share[j] > 0.0) shares_[j].emplace_back(i, share[j]);
  }
  for (auto* v :
       {&line_.shaft.ultimate, &line_.shaft.stiffness, &line_.shaft.quake, &line_.shaft.smith, &line_.shaft.viscous})
    v->assign(n, 0.0);
  line_.shaft.nodes.clear();
  bare_step_ = 0.9 * line_stable_step(line_, false);
}

double MatchModel::segment_top(std::size_t i) const {
  return top_ + static_cast<double>(i) * segment_length_;
}

double MatchModel::segment_bottom(std::size_t i) const {
  return i + 1 == segments_ ? length_ : segment_top(i + 1);
}

void MatchModel::apply(const MatchSoil& soil, Line& line) const {
  Shaft& s = line.shaft;
  s.nodes.clear();
  for (std::size_t j = 0; j < shares_.size(); ++j) {
    double r = 0.0;
    for (const auto& [i, w] : shares_[j]) r += w * soil.shaft[i];
    s.ultimate[j] = r;
    s.quake[j] = soil.shaft_quake;
    s.stiffness[j] = r / soil.shaft_quake;
    s.smith[j] = soil.law == DampingLaw::smith ? soil.shaft_damping : 0.0;
    s.viscous[j] = soil.law == DampingLaw::viscous ? soil.shaft_damping * r : 0.0;
    if (r > 0.0) s.nodes.push_back(j);
  }
  ContactLaw& toe = line.links.front().law;
  toe.soil = SoilSpring{soil.toe, soil.toe_quake, soil.toe_damping, soil.law};
  toe.stiffness = soil.toe / soil.toe_quake;
}

bool MatchModel::head_force(const MatchSoil& soil, std::size_t first, std::span<double> out) const {
  Line line = line_;
  apply(soil, line);
  // 0.9 of the bare pile's stable step, less where the soil's damping asks
  // for it: continuous in the soil, so that its finite differences are.
  Case c = case_;
  c.time.step = std::min(bare_step_, 0.95 * line_stable_step(line, false));
  const double dt = c.time.step;
  LineCentralDifference scheme(c, std::move(line));
  scheme.start();
  // The force at the samples, linear between the steps that bracket each.
  double before = scheme.far_force(), t_before = 0.0;
  scheme.advance();
  for (std::size_t k = 0; k < out.size(); ++k) {
    const double s = signals_->t[first + k] - t_start_;
    while (scheme.time() < s) {
      before = scheme.far_force();
      t_before = scheme.time();
      scheme.advance();
      if (!scheme.finite()) return false;
    }
    const double w = (s - t_before) / dt;
    out[k] = (1.0 - w) * before + w * scheme.far_force();
  }
  return true;
}

}  // namespace barimpact
