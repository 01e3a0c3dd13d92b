// The event-capturing rigid-contact schemes on lines (moreau-jean,
// paoli-schatzman, mass-redistribution; schemes/line_rigid.hpp): the single
// bar's numbers on one bar, convergence orders against exact solutions run
// through the line engine, the budget with D_contact and momentum on lines of
// several bodies, and the refusals.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <cmath>
#include <functional>

#include "../support/run_case.hpp"
#include "barimpact/case/line_builder.hpp"
#include "barimpact/exact/exact.hpp"
#include "barimpact/run/simulate.hpp"
#include "barimpact/schemes/line_scheme.hpp"

namespace barimpact {
namespace {

BodyData bar(const std::string& name, double length, int elements, const std::string& velocity = "0") {
  BodyData b;
  b.name = name;
  b.length = length;
  b.elements = elements;
  b.velocity = velocity;
  return b;
}

BodyData mass(const std::string& name, double m, double v) {
  BodyData b;
  b.name = name;
  b.kind = BodyKind::mass;
  b.mass = m;
  b.velocity = fmt::format("{}", v);
  return b;
}

JointData joint(const std::string& lower, const std::string& upper, JointLaw law) {
  JointData j;
  j.name = lower + "-" + upper;
  j.lower = lower;
  j.upper = upper;
  j.law.law = law;
  return j;
}

Case line_case(std::vector<BodyData> bodies, std::vector<JointData> joints, const std::string& scheme, double dt,
               double end) {
  Case c;
  c.bodies = std::move(bodies);
  c.joints = std::move(joints);
  c.single_bar = false;
  c.time.scheme = scheme;
  c.time.step = dt;
  c.time.end = end;
  return c;
}

// Each scheme with the step its single-bar tests use (dt / h): explicit
// paoli-schatzman below h / (c sqrt 3).
struct SchemeStep {
  const char* scheme;
  double ratio;
};
constexpr SchemeStep rigid_schemes[] = {{"moreau-jean", 1.0}, {"paoli-schatzman", 0.5}, {"mass-redistribution", 1.0}};

// One bar through the line engine against the single-bar scheme: the same
// equations with per-bond coefficients and the links settled through the
// responses instead of between the sweeps, so the same numbers up to
// round-off: 1e-12 of the scale for U and the energies (a few hundred steps
// of it); V and R are differences of displacements over dt or h (a face's
// backward difference, mass redistribution's R = (a/h)(u_0 - u_1) - F_0), so
// their round-off is 1/h = 100 times larger: 1e-10. e = 1/4, not 1/2: with
// e = 1/2 moreau-jean's first bounce lands exactly on its activity rule's
// threshold U + (dt/2) V = 0, where round-off decides.
TEST(LineRigid, MatchesTheSingleBarSchemesOnOneBar) {
  for (const auto& [scheme, ratio] : rigid_schemes) {
    // Viscosity where the scheme runs it (paoli-schatzman's explicit step bounds it at dt = h/2).
    const std::string viscosity = std::string(scheme) == "moreau-jean"       ? "0.01"
                                  : std::string(scheme) == "paoli-schatzman" ? "0.0001"
                                                                             : "0";
    for (const char* kind : {"rigid", "none"})
      for (const char* far : {"free", "clamped"}) {
        // The single bar's mass redistribution empties node 0 with no obstacle
        // too; on a line only a rigid link's face gives its mass away.
        if (std::string(scheme) == "mass-redistribution" && std::string(kind) == "none") continue;
        std::vector<std::string> sets{std::string("time.scheme=") + scheme,
                                      fmt::format("time.step={}", 0.01 * ratio),
                                      "time.end=3",
                                      "output.fields_at=[]",
                                      std::string("obstacle.kind=") + kind,
                                      std::string("bar.far_end=") + far,
                                      "time.restitution=0.25",
                                      "bar.viscosity=" + viscosity};
        if (std::string(far) == "clamped") sets.push_back("initial.velocity=\"x - 1\"");
        const Case single = testing::example("paper-example1.toml", sets);
        Case line = single;
        line.single_bar = false;
        line.bodies = {bar("bar", 1.0, 100, single.initial.velocity)};
        line.bodies[0].viscosity = single.bar.viscosity;
        line.near_end.law = std::string(kind) == "rigid" ? JointLaw::rigid : JointLaw::free;
        line.far_end.law = std::string(far) == "clamped" ? JointLaw::clamped : JointLaw::free;
        const RunResult a = run(single), b = run(line);
        ASSERT_EQ(a.history.size(), b.history.size());
        for (std::size_t k = 0; k < a.history.size(); ++k) {
          const HistoryRow &x = a.history[k], &y = b.history[k];
          for (auto [p, q] : {std::pair{x.U, y.U}, std::pair{x.E_kin, y.E_kin}, std::pair{x.E_strain, y.E_strain},
                              std::pair{x.D_visc, y.D_visc}})
            ASSERT_NEAR(p, q, 1e-12 * (1.0 + std::abs(p))) << scheme << " " << kind << " " << far << " row " << k;
          for (auto [p, q] : {std::pair{x.V, y.V}, std::pair{x.R, y.R}})
            ASSERT_NEAR(p, q, 1e-10 * (1.0 + std::abs(p))) << scheme << " " << kind << " " << far << " row " << k;
        }
      }
  }
}

}  // namespace
}  // namespace barimpact
