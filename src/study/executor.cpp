#include "barimpact/study/executor.hpp"

#include <algorithm>
#include <atomic>
#include <thread>
#include <vector>

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

}  // namespace barimpact
