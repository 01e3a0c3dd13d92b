// A run's set-up (its line built, its scheme made, its recorders) polls the
// interrupt of the study it is part of, as the run's time loop does, so
// that a signal ends a study within a second also while one of its cases
// is being set up: SetupPolling names the flag this thread's set-up polls,
// poll_setup() throws Interrupted once it is set. (A run or check alone is
// ended at once by its signal handler during its set-up.)
#pragma once

#include <atomic>
#include <stdexcept>

namespace barimpact {

/// A set-up ended by its interrupt.
struct Interrupted : std::runtime_error {
  Interrupted() : std::runtime_error("interrupted during its set-up") {}
};

/// While alive, this thread's set-up polls `flag` (nullptr: none).
class SetupPolling {
 public:
  explicit SetupPolling(const std::atomic<bool>* flag);
  ~SetupPolling();
  SetupPolling(const SetupPolling&) = delete;
  SetupPolling& operator=(const SetupPolling&) = delete;

 private:
  const std::atomic<bool>* previous_;
};

/// Throws Interrupted when the flag this thread's set-up polls is set.
void poll_setup();

}  // namespace barimpact
