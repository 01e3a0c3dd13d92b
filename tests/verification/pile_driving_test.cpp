// Pile driving across the schemes: a quasi-static push reaches the static
// capacity of Smith's soil, a blow's budget closes, a capblock's loops are
// its law's hysteresis, and the head force is Deeks and Randolph's closed form.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <cmath>
#include <numeric>

#include "../support/line_runs.hpp"
#include "../support/pile.hpp"
#include "../support/run_case.hpp"
#include "barimpact/case/line_builder.hpp"
#include "barimpact/run/output.hpp"
#include "barimpact/run/simulate.hpp"
#include "barimpact/schemes/line_scheme.hpp"
#include "barimpact/schemes/registry.hpp"

namespace barimpact {
namespace {

using testing::case_from;
using testing::column;
using testing::pile_toml;

// The pile pushed down at 0.01 m/s (ramped over 0.1 s, 50 transit times, so
// that it rings by under 1e-3 of the load), pulled back 11 mm and pushed
// again: once every spring has yielded the head carries the static capacity
// R_toe + R_shaft; pulled back, the toe leaves its slipped position (no
// force) and the shaft holds the pile down with its whole capacity.
TEST(SmithPile, QuasiStaticPushReachesTheStaticCapacityThroughUnloadingAndReloading) {
  for (const char* scheme : {"central-difference", "newmark", "paper"}) {
    const std::string step = scheme == std::string("central-difference") ? "time.step=auto" : "time.step=1e-4";
    const Case c = case_from(std::string(pile_toml) + R"toml(
[far_end]
law = "velocity"
value = "0.01*(-min(1,max(0,t/0.1)) + 2*min(1,max(0,(t-1.5)/0.1)) - 2*min(1,max(0,(t-2.6)/0.1)))"
[output]
every = 100
)toml",
                             {"time.end=4.6", "body.pile.viscosity=2e7", fmt::format("time.scheme={}", scheme), step});
    const RunResult r = run(c);
    ASSERT_TRUE(r.summary.complete) << r.summary.message;
    auto row_at = [&](double t) {
      std::size_t best = 0;
      for (std::size_t i = 0; i < r.history.size(); ++i)
        if (std::abs(r.history[i].t - t) < std::abs(r.history[best].t - t)) best = i;
      return best;
    };
    for (const double t : {1.0, 1.4, 4.2, 4.6}) {
      const std::size_t i = row_at(t);
      EXPECT_NEAR(r.history[i].R, 200e3, 1e-12 * 200e3) << "the toe at its capacity, t = " << t;
      EXPECT_NEAR(column(r, "far_end.force", i), 500e3, 1e-3 * 500e3) << "t = " << t;  // the ringing: 1e-3
    }
    const std::size_t back = row_at(2.6);
    EXPECT_EQ(r.history[back].R, 0.0);
    EXPECT_NEAR(column(r, "far_end.force", back), -300e3, 1e-3 * 300e3);
    // The budget: the soil's slip work and stored energy against the head's
    // work, to 1e-7 (the paper's scheme 1e-6: measured 2e-7, its
    // alpha-averaged springs across their kinks at dt = 1e-4).
    const double scale = r.history.back().D_contact;
    EXPECT_GT(scale, 0.0);
    const double budget = scheme == std::string("paper") ? 1e-6 : 1e-7;
    for (const auto& h : r.history) EXPECT_NEAR(h.total(), 0.0, budget * scale) << scheme << " at " << h.t;
  }
}

}  // namespace
}  // namespace barimpact

namespace barimpact {
namespace {

// A blow of the example pile, both damping laws, toe and shaft, under
// central differences (its stable step), newmark and the paper's scheme
// (dt = 1e-5), to 0.12 s under the examples' gravity: the budget (soil spring energy in E_obstacle; slip, damping
// and cushion losses in D_contact) closes to the issue's 1e-3 of the
// hammer's energy at every row. Measured: central differences 5e-5 (steel
// pipe) and 4e-4 (concrete, soft pile cushion), the soil and cushion forces
// at t_n against the centred increments; newmark 1e-6 and 3e-6, the
// springs' kinks under the trapezoid; the paper's 2e-5, its cushions' split
// and the soil springs' alpha-average against their energies (O(dt^2):
// SmithBlow.PaperSchemeSolvesTheSoilAtItsLevels).
TEST(SmithPile, BlowBudgetCloses) {
  for (const char* scheme : {"central-difference", "newmark", "paper"})
    for (const char* example : {"pile/steel-pipe-sand.toml", "pile/concrete-clay.toml"})
      for (const char* law : {"smith", "viscous"}) {
        const bool implicit = scheme != std::string("central-difference");
        const double tolerance = scheme == std::string("newmark") ? 1e-5 : scheme == std::string("paper") ? 1e-4 : 1e-3;
        const Case c = testing::example(
            example,
            {fmt::format("near_end.damping_law={}", law), fmt::format("body.pile.shaft.damping_law={}", law),
             fmt::format("time.scheme={}", scheme), implicit ? "time.step=1e-5" : "time.step=auto", "time.end=0.12"});
        const RunResult r = run(c);
        ASSERT_TRUE(r.summary.complete) << r.summary.message;
        const double e0 = r.history.front().total();
        double worst = 0.0;
        for (const auto& h : r.history) worst = std::max(worst, std::abs(h.total() - e0));
        EXPECT_LT(worst, tolerance * e0) << scheme << " " << example << " " << law;
        EXPECT_GT(r.history.back().D_contact, 0.5 * e0) << "the soil and cushions take most of the blow";
        for (const auto& h : r.history) EXPECT_GE(h.R, 0.0) << "the toe never pulls";
      }
}

}  // namespace
}  // namespace barimpact

namespace barimpact {
namespace {}  // namespace
}  // namespace barimpact

namespace barimpact {
namespace {

// A capblock's loops under central differences, newmark and the paper's scheme:
// a ram on a cushion on a helmet on an elastic ground,
// pushed by growing pulses so that each contact compresses the cushion
// further than the last and the ram leaves it in between (and once
// bounces back within c_max: reloading along k / e^2, a loop of no area). Over each
// contact (force 0 at both ends, so nothing stored) the area of the loop,
// the trapezoid sum of p dc from the history, is what the cushion
// dissipated, D_contact's increase, and the law's k (1 - e^2) (c_max^2 -
// c_max0^2) / 2 with c_max from the history. Tolerances: the loop's area
// 1e-6 of the largest (the trapezoid's error at the loop's corners, O(dt^2)
// at 600 steps a contact; measured 5e-8), the booking 1e-12 (round-off: the
// scheme books the law's hysteresis at the new c_max; measured 1e-13).
TEST(SmithBlow, CushionHysteresisPerCycleIsTheAreaOfItsLoop) {
  for (const char* scheme : {"central-difference", "newmark", "paper"}) {
    const Case c = case_from(R"toml(
[[body]]
name = "helmet"
kind = "mass"
mass = 5.0
[[body]]
name = "ram"
kind = "mass"
mass = 1.0
[[joint]]
name = "capblock"
between = ["helmet", "ram"]
law = "cushion"
stiffness = 1e4
restitution = 0.7
[near_end]
law = "elastic"
stiffness = 5e4
[far_end]
law = "force"
value = "-20 * t * (1 - cos(8 * t))"
[time]
end = 4.0
step = 5e-5
scheme = "central-difference"
[output]
every = 1
)toml",
                             {fmt::format("time.scheme={}", scheme)});
    const RunResult r = run(c);
    ASSERT_TRUE(r.summary.complete) << r.summary.message;
    const double k = 1e4, e = 0.7;
    auto compression = [&](std::size_t i) { return column(r, "body.helmet.u", i) - column(r, "body.ram.u", i); };
    int loops = 0;
    double c_max = 0.0, area = 0.0, d0 = 0.0, c_max0 = 0.0, largest = 0.0;
    bool in_contact = false;
    for (std::size_t i = 1; i < r.history.size(); ++i) {
      const double p0 = column(r, "joint.capblock.force", i - 1), p1 = column(r, "joint.capblock.force", i);
      if (!in_contact && p1 > 0.0) {
        in_contact = true;
        area = 0.0;
        d0 = r.history[i - 1].D_contact;
        c_max0 = c_max;
      }
      c_max = std::max(c_max, compression(i));
      if (!in_contact) continue;
      area += 0.5 * (p0 + p1) * (compression(i) - compression(i - 1));
      if (p1 > 0.0) continue;
      in_contact = false;
      const double law = 0.5 * k * (1 - e * e) * (c_max * c_max - c_max0 * c_max0);
      const double booked = r.history[i].D_contact - d0;
      // A contact that stays within c_max loads and unloads along k / e^2: no loop.
      largest = std::max(largest, law);
      EXPECT_NEAR(area, law, 1e-6 * largest) << scheme << " contact at t = " << r.history[i].t;
      EXPECT_NEAR(booked, law, 1e-12 * largest) << scheme << " contact at t = " << r.history[i].t;
      if (law > 0.0) ++loops;
    }
    EXPECT_GE(loops, 4);
  }
}

}  // namespace
}  // namespace barimpact

namespace barimpact {
namespace {

// Deeks & Randolph (1993), "Analytical modelling of hammer impact for pile
// driving", Int. J. Numer. Anal. Methods Geomech. 17(5), 279-302: a ram m
// on a cushion k onto a pile that, until its toe's reflection returns, is a
// dashpot Z = E A / c (their model without the anvil mass and the cushion's
// damping). The head force obeys F'' + (k/Z) F' + (k/m) F = 0: from
// F = 0, F' = k v0 while the cushion loads, then with k / e^2 from the
// peak (F' = 0) while it unloads, until F = 0.
struct HammerImpact {
  double k, e, m, v0, z;
  // One phase of stiffness kk from (F0, F0') at its start, tau after it.
  [[nodiscard]] double phase(double kk, double tau, double f0, double df0) const {
    const double a = kk / (2.0 * z), d = a * a - kk / m;
    if (d > 0.0) {
      const double s = std::sqrt(d);
      return std::exp(-a * tau) *
             (f0 * (std::cosh(s * tau) + a / s * std::sinh(s * tau)) + df0 / s * std::sinh(s * tau));
    }
    const double s = std::sqrt(-d);  // d = 0 is not met by the cases below
    return std::exp(-a * tau) * (f0 * (std::cos(s * tau) + a / s * std::sin(s * tau)) + df0 / s * std::sin(s * tau));
  }
  [[nodiscard]] double peak_time() const {
    const double a = k / (2.0 * z), d = a * a - k / m;
    return d > 0.0 ? std::atanh(std::sqrt(d) / a) / std::sqrt(d) : std::atan2(std::sqrt(-d), a) / std::sqrt(-d);
  }
  [[nodiscard]] double force(double t) const {
    const double tp = peak_time();
    if (t <= tp) return phase(k, t, 0.0, k * v0);
    return std::max(0.0, phase(k / (e * e), t - tp, phase(k, tp, 0.0, k * v0), 0.0));
  }
};

// examples/pile/hammer-impact.toml's head force against the closed form at
// every step, before the toe's reflection returns, under central
// differences (its stable step), newmark and the paper's scheme (dt = h /
// (2 c)), at 200 and 400 elements. Measured, the largest error over the
// impact in units of the peak force, 200 then 400 elements: central
// differences 6.5e-3, 1.8e-3 (order 1.84); newmark 8.1e-3, 1.4e-3 (2.53);
// paper 9.0e-3, 1.6e-3 (2.54). Asserted: under 3e-3 at 400 elements and an
// order above 1.7 (second order: the cushion's kink at the peak is one in
// F'' only). The peak itself is met to 1e-4 at 400 elements (asserted 1e-3).
TEST(HammerImpact, HeadForceIsDeeksAndRandolphsClosedForm) {
  const Case base = testing::example("pile/hammer-impact.toml");
  const BodyData& pile = base.bodies[0];
  const double c0 = std::sqrt(pile.modulus / pile.density);
  const HammerImpact exact{1.5e9, 0.8, 4000.0, 4.43, pile.modulus * pile.area / c0};
  const double tp = exact.peak_time(), peak = exact.force(tp);
  for (const char* scheme : {"central-difference", "newmark", "paper"}) {
    double error[2] = {0.0, 0.0}, largest = 0.0;
    for (int level = 0; level < 2; ++level) {
      const int elements = 200 << level;
      const double h = pile.length / elements;
      const std::string step = scheme == std::string("central-difference") ? "auto" : fmt::format("{}", 0.5 * h / c0);
      const RunResult r = run(testing::example(
          "pile/hammer-impact.toml", {fmt::format("time.scheme={}", scheme), fmt::format("time.step={}", step),
                                      fmt::format("body.pile.elements={}", elements)}));
      ASSERT_TRUE(r.summary.complete) << r.summary.message;
      largest = 0.0;
      for (std::size_t i = 0; i < r.history.size(); ++i) {
        const double f = column(r, "joint.capblock.force", i);
        error[level] = std::max(error[level], std::abs(f - exact.force(r.history[i].t)));
        largest = std::max(largest, f);
      }
    }
    EXPECT_LT(error[1], 3e-3 * peak) << scheme;
    EXPECT_GT(std::log2(error[0] / error[1]), 1.7) << scheme << ": " << error[0] / peak << " then " << error[1] / peak;
    EXPECT_NEAR(largest, peak, 1e-3 * peak) << scheme;
  }
}

}  // namespace
}  // namespace barimpact

namespace barimpact {
namespace {}  // namespace
}  // namespace barimpact
