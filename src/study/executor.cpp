#include "barimpact/study/executor.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <atomic>
#include <thread>
#include <vector>

#include "barimpact/model/input_error.hpp"

namespace barimpact {

void run_parallel(std::size_t count, int jobs, const std::function<void(std::size_t)>& task) {
  const unsigned hardware = std::max(1u, std::thread::hardware_concurrency());
  const std::size_t threads = std::min<std::size_t>(jobs > 0 ? static_cast<std::size_t>(jobs) : hardware, count);
  std::atomic<std::size_t> next{0};
  auto worker = [&] {
    for (std::size_t i = next++; i < count; i = next++) task(i);
  };
  if (threads <= 1) {
    worker();
    return;
  }
  std::vector<std::thread> pool;
  for (std::size_t j = 0; j < threads; ++j) pool.emplace_back(worker);
  for (auto& t : pool) t.join();
}

void OutputStop::record(const OutputError& e) {
  const std::lock_guard lock(mutex_);
  stopped_.store(true);
  if (first_) return;
  // A run's file by its name in the study: runs/<id>/history.csv.
  const auto name = e.path().lexically_relative(out_);
  if (name.empty() || *name.begin() == "..")
    first_.emplace(e);
  else
    first_.emplace(fmt::format("--out {}: cannot write {}: {}", out_.string(), name.string(), e.reason()), e.path(),
                   e.reason());
}

void OutputStop::rethrow() const {
  const std::lock_guard lock(mutex_);
  if (first_) throw *first_;
}

void check_jobs(int jobs) {
  if (jobs < 0 || jobs > 1024)
    throw InputError(fmt::format("--jobs: must be 1 .. 1024, or 0 for all cores (got {})", jobs));
}

}  // namespace barimpact
