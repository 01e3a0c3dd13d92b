#include "barimpact/model/setup_polling.hpp"

#include <utility>

namespace barimpact {

namespace {

thread_local const std::atomic<bool>* polled = nullptr;

}  // namespace

SetupPolling::SetupPolling(const std::atomic<bool>* flag) : previous_(std::exchange(polled, flag)) {}

SetupPolling::~SetupPolling() {
  polled = previous_;
}

void poll_setup() {
  if (polled != nullptr && polled->load(std::memory_order_relaxed)) throw Interrupted();
}

}  // namespace barimpact
