// What a user should know about a case before running it (`barimpact
// check CASE`): its steps, the stable step of an explicit scheme, each
// penalty law's time constant against the step, and how long the run will
// take, measured on a short stretch of it.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "barimpact/case/case.hpp"
#include "barimpact/run/health.hpp"

namespace barimpact {

struct CaseCheck {
  long long steps = 0;
  std::size_t nodes = 0;
  /// The largest stable step, for an explicit scheme or a conditionally
  /// stable implicit one; `mass` names the mass matrix it was bounded with.
  std::optional<double> stable_step;
  std::string mass;       ///< "lumped" | "consistent"
  std::string stability;  ///< how the scheme's stability is decided, in words
  std::vector<PenaltyTimeConstant> penalties;
  long long timed_steps = 0;   ///< steps of the timing run
  double timed_seconds = 0.0;  ///< their wall time
  double estimate_seconds = 0.0;
  std::string trouble;  ///< the timing run's state became non-finite: where
};

/// Checks `c` (already validated by Case) and times up to `timing_budget`
/// node-steps of it. Throws InputError only as Case does.
[[nodiscard]] CaseCheck check_case(const Case& c, double timing_budget = 2e6);

/// The report `barimpact check` prints: one `key: value` line per item
/// (steps, stable step, penalty, time estimate), numbers to 4 digits.
[[nodiscard]] std::string check_text(const Case& c, const CaseCheck& k);

}  // namespace barimpact
