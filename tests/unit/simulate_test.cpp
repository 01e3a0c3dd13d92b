// The run loop (simulate.hpp): an interrupt ends a run after the step under
// way; lanes stepped together stop one by one, each for its own reason.
#include "barimpact/run/simulate.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <limits>
#include <vector>

#include "../support/run_case.hpp"
#include "barimpact/model/input_error.hpp"

namespace barimpact {
namespace {

TEST(Simulate, AnInterruptEndsTheRunAfterTheStepUnderWay) {
  const auto c = testing::example("paper-example1.toml", {"output.fields_at=[]"});
  std::atomic<bool> interrupt{false};
  RunOptions options;
  options.interrupt = &interrupt;
  options.loop_begins = [&interrupt] { interrupt = true; };
  const auto r = run(c, options);
  EXPECT_EQ(r.summary.status, RunStatus::interrupted);
  EXPECT_FALSE(r.summary.complete);
  EXPECT_EQ(r.summary.steps_done, 1);
  EXPECT_EQ(r.history.size(), 2u);
}

TEST(Simulate, AnInterruptEndsTheSetUpOfAStudysCase) {
  // A study's case polls its interrupt while its line and scheme are made:
  // it ends there, with no step taken (it took the first step, after a set-up of seconds at 10^7 elements).
  const auto c = testing::example("paper-example1.toml", {"output.fields_at=[]"});
  std::atomic<bool> interrupt{true};
  RunOptions options;
  options.interrupt = &interrupt;
  bool began = false;
  options.loop_begins = [&began] { began = true; };
  const auto r = run(c, options);
  EXPECT_FALSE(began);
  EXPECT_EQ(r.summary.status, RunStatus::interrupted);
  EXPECT_EQ(r.summary.steps_done, 0);
  EXPECT_EQ(r.summary.message, "interrupted during its set-up");
}

TEST(Simulate, LoopBeginsIsCalledOnceTheSetUpIsDone) {
  // The command ends set-up at once on a signal and polls from here on.
  const auto c = testing::example("paper-example1.toml", {"output.fields_at=[]", "time.end=0.1"});
  int calls = 0;
  RunOptions options;
  options.loop_begins = [&calls] { ++calls; };
  const auto r = run(c, options);
  EXPECT_EQ(calls, 1);
  EXPECT_TRUE(r.summary.complete);
}

TEST(Simulate, RefusesARunBeyondTheAvailableMemoryBeforeBuildingIt) {
  Case c = testing::example("paper-example1.toml", {"output.fields_at=[]"});
  c.bodies[0].elements = 1'000'000'000;  // about 190 GB: more than any test machine has
  EXPECT_THROW((void)run(c), InputError);
}

// A lane whose end moves as U = t and turns non-finite at step `bad` (never if 0).
class RampLane final : public Scheme {
 public:
  RampLane(double dt, long long bad) : dt_(dt), bad_(bad) {}
  void start() override { n_ = 0; }
  void advance() override { ++n_; }
  long long step() const override { return n_; }
  double time() const override { return static_cast<double>(n_) * dt_; }
  std::size_t nodes() const override { return 1; }
  double end_displacement() const override { return time(); }
  double end_velocity() const override { return 1.0; }
  double reaction() const override { return 0.0; }
  void displacement(std::span<double> out) const override { out[0] = time(); }
  void velocity(std::span<double> out) const override { out[0] = 1.0; }
  Energies energies() const override { return {}; }
  bool finite() const override { return bad_ == 0 || n_ < bad_; }
  double displacement_at(std::size_t) const override { return time(); }
  double velocity_at(std::size_t) const override { return 1.0; }
  double link_opening(std::size_t) const override { return time(); }

 private:
  double dt_;
  long long bad_, n_ = 0;
};

// Three lanes advanced together, as the batch steps them.
class ThreeLanes final : public LaneStepper {
 public:
  std::size_t lanes() const override { return 3; }
  Scheme& lane(std::size_t i) override { return lanes_[i]; }
  void start() override {
    for (auto& l : lanes_) l.start();
    ++starts;
  }
  void advance() override {
    for (auto& l : lanes_) l.advance();
    ++advances;
  }
  int starts = 0, advances = 0;

 private:
  std::vector<RampLane> lanes_{RampLane(0.1, 0), RampLane(0.1, 4), RampLane(0.1, 0)};
};

// Counts the steps it sees; content until step `stop` (never if 0).
class Counter final : public Observer {
 public:
  explicit Counter(long long stop = 0) : stop_(stop) {}
  void begin(const Scheme&, long long) override { seen = 0; }
  bool observe(const Scheme& s) override {
    ++seen;
    return stop_ == 0 || s.step() < stop_;
  }
  long long seen = 0;

 private:
  long long stop_;
};

TEST(Simulate, LanesSteppedTogetherStopEachForItsOwnReason) {
  ThreeLanes lanes;
  Counter all, broken, stopping(6);
  const std::vector<std::vector<Observer*>> observers{{&all}, {&broken}, {&stopping}};
  const auto r = simulate(lanes, 10, observers);
  ASSERT_EQ(r.size(), 3u);
  EXPECT_EQ(r[0].status, RunStatus::complete);
  EXPECT_EQ(r[0].steps_done, 10);
  EXPECT_EQ(all.seen, 11);  // steps 0..10
  EXPECT_EQ(r[1].status, RunStatus::non_finite);
  EXPECT_EQ(r[1].steps_done, 3);  // step 4 is not finite: observed up to 3
  EXPECT_EQ(broken.seen, 4);
  EXPECT_EQ(r[2].status, RunStatus::stopped);
  EXPECT_EQ(r[2].steps_done, 6);
  EXPECT_EQ(stopping.seen, 7);
  EXPECT_EQ(lanes.starts, 1);
  EXPECT_EQ(lanes.advances, 10);  // the lanes left run on together
}

TEST(Simulate, TheLoopEndsWhenNoLaneIsLeftOrOnAnInterrupt) {
  ThreeLanes lanes;
  Counter a(2), b, c(3);
  const std::vector<std::vector<Observer*>> observers{{&a}, {&b}, {&c}};
  (void)simulate(lanes, 100, observers);
  EXPECT_EQ(lanes.advances, 4);  // lane 1 breaks at step 4, the last one left

  ThreeLanes more;
  Counter d, e, f;
  const std::vector<std::vector<Observer*>> others{{&d}, {&e}, {&f}};
  std::atomic<bool> interrupt{true};
  const auto r = simulate(more, 100, others, &interrupt);
  EXPECT_EQ(more.advances, 1);  // the step under way, then every lane ends
  EXPECT_EQ(r[0].status, RunStatus::interrupted);
  EXPECT_EQ(r[2].status, RunStatus::interrupted);
  EXPECT_EQ(r[0].steps_done, 1);
}

}  // namespace
}  // namespace barimpact
