// Helpers shared by the line schemes' tests: a case of bodies and joints
// written in code, a history column by name, and the order at which a
// scheme's near end converges to a line's exact solution.
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "barimpact/case/case.hpp"
#include "barimpact/exact/lines.hpp"
#include "barimpact/run/simulate.hpp"
#include "line_parts.hpp"

namespace barimpact::testing {

// A case run through the line engine.
inline Case line_case(std::vector<BodyData> bodies, std::vector<JointData> joints, double dt, double end,
                      const std::string& scheme = "central-difference") {
  Case c;
  c.bodies = std::move(bodies);
  c.joints = std::move(joints);

  c.time.scheme = scheme;
  c.time.step = dt;
  c.time.end = end;
  return c;
}

// The welded junction of two bars (b four times as stiff) under a unit
// force step at the near end, on 50 + 50 elements to t = 2.5 at dt = 0.01.
inline Case welded_junction(const std::string& scheme) {
  BodyData stiff = bar("b", 1.0, 50);
  stiff.modulus = 4.0;
  Case c = line_case({bar("a", 1.0, 50), stiff}, {}, 0.01, 2.5, scheme);
  c.near_end.law = JointLaw::force;
  c.near_end.value = std::string("1");
  return c;
}

// Column `name` of a run's history (probe.hpp's) at `row`; a failure (and
// NaN) when the run has no such column.
inline double column(const RunResult& r, const std::string& name, std::size_t row) {
  for (std::size_t i = 0; i < r.columns.size(); ++i)
    if (r.columns[i] == name) return r.extra[row * r.columns.size() + i];
  ADD_FAILURE() << "no column " << name;
  return NAN;
}

// The near end's error against the line's exact solution over the
// solution's interval: its displacement's largest (`force` false) or its
// support force's L1 error (`force` true).
inline double end_error(const Case& c, bool force) {
  const auto solution = exact::line_end(c);
  EXPECT_TRUE(solution != nullptr);
  const RunResult r = run(c);
  double e = 0.0;
  for (const auto& h : r.history) {
    if (h.t > solution->valid_until()) break;
    if (force)
      e += std::abs(h.R - solution->R(h.t)) * c.time.step;
    else
      e = std::max(e, std::abs(h.U - solution->U(h.t)));
  }
  return e;
}

// The order of end_error from the second to the third of three meshes,
// each halving every body's element size and the step.
inline double measured_order(Case c, bool force) {
  std::vector<double> errors;
  for (int level = 0; level < 3; ++level) {
    errors.push_back(end_error(c, force));
    for (auto& b : c.bodies) b.elements *= 2;
    c.time.step /= 2;
  }
  return std::log2(errors[1] / errors[2]);
}

}  // namespace barimpact::testing
