// The one executor for independent runs (sweeps, convergence studies): a
// pool of threads taking task indices in order until none are left.
#pragma once

#include <cstddef>
#include <functional>

namespace barimpact {

/// Calls task(i) for i = 0 .. count-1 on `jobs` threads (0: all cores).
/// Tasks must not throw (record failures in their results).
void run_parallel(std::size_t count, int jobs, const std::function<void(std::size_t)>& task);

/// The studies' --jobs rule: 1 .. 1024 threads, or 0 for all cores. Throws
/// InputError naming --jobs otherwise.
void check_jobs(int jobs);

}  // namespace barimpact
