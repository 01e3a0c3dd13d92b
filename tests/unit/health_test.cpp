#include "barimpact/run/health.hpp"

#include <gtest/gtest.h>

#include <algorithm>

#include "../support/run_case.hpp"
#include "barimpact/case/line_builder.hpp"

namespace barimpact {
namespace {

bool has(const std::vector<std::string>& warnings, const std::string& kind) {
  return std::any_of(warnings.begin(), warnings.end(), [&](const auto& w) { return w.rfind(kind + ":", 0) == 0; });
}

TEST(Health, TheResolvedExampleIsHealthy) {
  const auto r = run(testing::example("paper-example1.toml"));
  EXPECT_TRUE(r.summary.warnings.empty()) << r.summary.warnings.front();
}

TEST(Health, AnUnresolvedPenaltyIsNamed) {
  // The README's stiff case: Z/k = 1e-4 below dt = 1e-3, a 64% budget error.
  const auto r = run(testing::example("paper-example1.toml", {"obstacle.stiffness=1e4", "time.step=0.001"}));
  EXPECT_TRUE(r.summary.complete);
  EXPECT_TRUE(has(r.summary.warnings, "penalty-unresolved"));
  EXPECT_TRUE(has(r.summary.warnings, "energy-balance"));
  EXPECT_TRUE(has(r.summary.warnings, "contact-chatter"));
}

TEST(Health, AConditionallyStableStepBeyondItsLimitIsNamed) {
  // alpha = 0: omega_max dt <= 2; Example 1 at h = 0.01 measures stable at dt = 0.0055 and blowing up at
  // 0.0057 (energy x 12 by t = 4); the estimate says 0.00556.
  const auto c = testing::example("paper-example1.toml",
                                  {"time.alpha=0", "time.end=0.05", "time.step=0.006", "output.fields_at=[]"});
  EXPECT_TRUE(has(check_health(c, build_line(c), run(c).summary, {}), "unstable-step"));
  const auto below = testing::example("paper-example1.toml",
                                      {"time.alpha=0", "time.end=0.05", "time.step=0.005", "output.fields_at=[]"});
  EXPECT_FALSE(has(check_health(below, build_line(below), run(below).summary, {}), "unstable-step"));
  const auto trapezoidal = testing::example("paper-example1.toml", {"time.step=0.1"});
  EXPECT_FALSE(has(check_health(trapezoidal, build_line(trapezoidal), run(trapezoidal).summary, {}), "unstable-step"));
}

TEST(Health, ChatterIsManyEpisodesOfAStepOrTwo) {
  const auto c = testing::example("paper-example1-rigid.toml");
  Summary s;
  s.method = "moreau-jean";
  for (int i = 0; i < 12; ++i) s.contacts.push_back({i * 0.1, i * 0.1 + c.time.step, true, 0, 0, 1});
  EXPECT_TRUE(has(check_health(c, build_line(c), s, {}), "contact-chatter"));
  s.contacts.resize(9);  // few episodes: a bounce or two is not chatter
  EXPECT_FALSE(has(check_health(c, build_line(c), s, {}), "contact-chatter"));
}

TEST(Health, TheEnergyScaleOfARunFromRestIsItsWork) {
  std::vector<HistoryRow> rows{{0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0}, {1, 0, 0, 0, 1.5, 0.5, 0, 2.0, 0, 0, 0}};
  EXPECT_EQ(energy_scale(rows), 2.0);
  rows[1].W_ext = 0.0;
  EXPECT_EQ(energy_scale(rows), 2.0);  // no work either: the largest stored energy
}

}  // namespace
}  // namespace barimpact
