// The run loop (simulate.hpp): an interrupt ends a run after the step under way.
#include "barimpact/run/simulate.hpp"

#include <gtest/gtest.h>

#include <atomic>

#include "../support/run_case.hpp"

namespace barimpact {
namespace {

TEST(Simulate, AnInterruptEndsTheRunAfterTheStepUnderWay) {
  const auto c = testing::example("paper-example1.toml", {"output.fields_at=[]"});
  std::atomic<bool> interrupt{true};
  RunOptions options;
  options.interrupt = &interrupt;
  const auto r = run(c, options);
  EXPECT_EQ(r.summary.status, RunStatus::interrupted);
  EXPECT_FALSE(r.summary.complete);
  EXPECT_EQ(r.summary.steps_done, 1);
  EXPECT_EQ(r.history.size(), 2u);
}

}  // namespace
}  // namespace barimpact
