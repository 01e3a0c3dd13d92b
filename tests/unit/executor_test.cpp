// The studies' executor (executor.hpp): every task index run exactly once
// on any number of threads, the --jobs rule, and the first output error of
// a study kept and thrown once.
#include "barimpact/study/executor.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <string>
#include <vector>

namespace barimpact {
namespace {

TEST(RunParallel, RunsEveryTaskExactlyOnceOnAnyNumberOfThreads) {
  for (const int jobs : {1, 2, 7, 0}) {
    std::vector<std::atomic<int>> calls(1000);
    run_parallel(calls.size(), jobs, [&](std::size_t i) { calls[i].fetch_add(1); });
    for (std::size_t i = 0; i < calls.size(); ++i) ASSERT_EQ(calls[i].load(), 1) << "task " << i << " jobs " << jobs;
  }
  std::atomic<int> none{0};
  run_parallel(0, 4, [&](std::size_t) { none.fetch_add(1); });
  EXPECT_EQ(none.load(), 0);
  // More threads than tasks: still once each.
  std::vector<std::atomic<int>> few(3);
  run_parallel(few.size(), 16, [&](std::size_t i) { few[i].fetch_add(1); });
  for (const auto& c : few) EXPECT_EQ(c.load(), 1);
}

// 1 .. 1024 threads, or 0 for all cores; anything else names --jobs.
TEST(RunParallel, JobsAreOneTo1024OrZero) {
  for (const int jobs : {0, 1, 1024}) EXPECT_NO_THROW(check_jobs(jobs)) << jobs;
  for (const int jobs : {-1, 1025}) {
    try {
      check_jobs(jobs);
      ADD_FAILURE() << "accepted " << jobs;
    } catch (const InputError& e) {
      EXPECT_EQ(std::string(e.what()),
                "--jobs: must be 1 .. 1024, or 0 for all cores (got " + std::to_string(jobs) + ")");
    }
  }
}

// The first error recorded is the one thrown, a run's file named by its
// place in the study's directory; later ones only keep the study stopped.
TEST(OutputStop, ThrowsTheFirstErrorOnceTheRunsAreDone) {
  OutputStop stop("/tmp/study");
  EXPECT_FALSE(stop.stopped());
  EXPECT_NO_THROW(stop.rethrow());
  stop.record(OutputError("/tmp/study/runs/003/history.csv", "No space left on device"));
  stop.record(OutputError("/tmp/study/runs/004/history.csv", "Disk quota exceeded"));
  EXPECT_TRUE(stop.stopped());
  try {
    stop.rethrow();
    ADD_FAILURE() << "nothing thrown";
  } catch (const OutputError& e) {
    EXPECT_EQ(std::string(e.what()), "--out /tmp/study: cannot write runs/003/history.csv: No space left on device");
    EXPECT_EQ(e.path(), "/tmp/study/runs/003/history.csv");
    EXPECT_EQ(e.reason(), "No space left on device");
  }
  // A file outside the study's directory keeps its own message.
  OutputStop elsewhere("/tmp/study");
  elsewhere.record(OutputError("/var/other.csv", "Read-only file system"));
  try {
    elsewhere.rethrow();
    ADD_FAILURE() << "nothing thrown";
  } catch (const OutputError& e) {
    EXPECT_EQ(std::string(e.what()), "cannot write /var/other.csv: Read-only file system");
  }
}

}  // namespace
}  // namespace barimpact
