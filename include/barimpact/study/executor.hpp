// The one executor for independent runs (sweeps, convergence studies): a
// pool of threads taking task indices in order until none are left.
#pragma once

#include <atomic>
#include <cstddef>
#include <filesystem>
#include <functional>
#include <mutex>
#include <optional>
#include <utility>

#include "barimpact/model/input_error.hpp"

namespace barimpact {

/// Calls task(i) for i = 0 .. count-1 on `jobs` threads (0: all cores).
/// Tasks must not throw (record failures in their results).
void run_parallel(std::size_t count, int jobs, const std::function<void(std::size_t)>& task);

/// The first OutputError among a study's runs: the file system refused a
/// run's results (a full disk), which no later run would escape. Runs not
/// yet begun are skipped (stopped()), and the study throws it once the
/// runs in flight are done (rethrow()); a run's own failure (a refused
/// case, a non-finite state) stays a row. Safe to share between threads.
class OutputStop {
 public:
  /// `out`: the study's directory (--out), which the error names.
  explicit OutputStop(std::filesystem::path out) : out_(std::move(out)) {}
  void record(const OutputError& e);
  [[nodiscard]] bool stopped() const { return stopped_.load(); }
  /// Throws the first OutputError recorded, if any.
  void rethrow() const;

 private:
  std::filesystem::path out_;
  std::atomic<bool> stopped_{false};
  mutable std::mutex mutex_;
  std::optional<OutputError> first_;
};

/// The studies' --jobs rule: 1 .. 1024 threads, or 0 for all cores. Throws
/// InputError naming --jobs otherwise.
void check_jobs(int jobs);

}  // namespace barimpact
