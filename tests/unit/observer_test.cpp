#include "barimpact/observer.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>

#include "../support/run_case.hpp"
#include "barimpact/simulate.hpp"

namespace barimpact {
namespace {

// A scheme whose end moves as U(t) = cos(t) on a rigid bar of 3 nodes.
class CosineScheme final : public Scheme {
 public:
  explicit CosineScheme(double dt) : dt_(dt) {}
  void start() override { n_ = 0; }
  void advance() override { ++n_; }
  long long step() const override { return n_; }
  double time() const override { return static_cast<double>(n_) * dt_; }
  std::size_t nodes() const override { return 3; }
  double end_displacement() const override { return std::cos(time()); }
  double end_velocity() const override { return -std::sin(time()); }
  double reaction() const override { return std::max(0.0, -10.0 * std::cos(time())); }
  void displacement(std::span<double> out) const override {
    for (auto& u : out) u = end_displacement();
  }
  void velocity(std::span<double> out) const override {
    for (auto& v : out) v = end_velocity();
  }
  Energies energies() const override { return {1.0, 2.0, 0.0, 0.5, 0.25}; }
  bool finite() const override { return true; }

 private:
  double dt_;
  long long n_ = 0;
};

TEST(HistoryRecorder, RecordsEveryNthStepAndAlwaysTheLast) {
  CosineScheme s(0.1);
  HistoryRecorder h(3);
  const std::array<Observer*, 1> obs{&h};
  simulate(s, 10, obs);
  std::vector<double> t;
  for (const auto& r : h.rows()) t.push_back(std::round(r.t * 10));
  EXPECT_EQ(t, (std::vector<double>{0, 3, 6, 9, 10}));
  EXPECT_EQ(h.rows()[1].E_strain, 2.0);
  EXPECT_EQ(h.rows()[1].D_visc, 0.25);
}

TEST(FieldRecorder, TakesTheNearestStepOncePerStep) {
  const Case c = testing::case_from("[bar]\nelements = 2\n[time]\nstep = 0.1\nend = 1");
  CosineScheme s(0.1);
  FieldRecorder f(c, {0.94, 0.26, 0.3, 0.0});
  const std::array<Observer*, 1> obs{&f};
  simulate(s, 10, obs);
  ASSERT_EQ(f.taken(), 3u);
  const Fields fields = f.take();
  ASSERT_EQ(fields.count(), 3u);
  EXPECT_NEAR(fields.t[0], 0.0, 1e-15);
  EXPECT_NEAR(fields.t[1], 0.3, 1e-15);
  EXPECT_NEAR(fields.t[2], 0.9, 1e-15);
  EXPECT_DOUBLE_EQ(fields.u[1 * 3 + 2], std::cos(0.30000000000000004));
  EXPECT_EQ(fields.sigma[1 * 3 + 1], 0.0);  // rigid: no strain
}

TEST(ContactMonitor, InterpolatesCrossingsAndReportsEachEpisode) {
  CosineScheme s(0.01);
  ContactMonitor m(ObstacleData{ObstacleKind::elastic, 10.0, 0.0});
  const std::array<Observer*, 1> obs{&m};
  simulate(s, 1000, obs);  // t up to 10: cos < 0 on (pi/2, 3pi/2) and (5pi/2, 7pi/2)
  ASSERT_EQ(m.intervals().size(), 2u);
  // Linear interpolation of cos over a step of 0.01: error below h^2/8 |cos''| ~ 1.3e-5.
  EXPECT_NEAR(m.intervals()[0].start, M_PI / 2, 2e-5);
  EXPECT_NEAR(m.intervals()[0].end, 3 * M_PI / 2, 2e-5);
  EXPECT_NEAR(m.intervals()[1].start, 5 * M_PI / 2, 2e-5);
  EXPECT_TRUE(m.intervals()[0].closed);
  EXPECT_NEAR(m.intervals()[0].rebound_velocity, 1.0, 1e-3);
  EXPECT_NEAR(m.max_reaction(), 10.0, 1e-3);
  EXPECT_NEAR(m.max_penetration(), 1.0, 1e-3);
}

}  // namespace
}  // namespace barimpact
