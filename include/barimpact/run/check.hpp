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

/// What a run of a case will take, from its size alone (the line is not
/// built): the memory it adds to the process at its peak, and the run
/// directory's files. The model and its measured constants: check.cpp.
struct ResourceEstimate {
  std::size_t nodes = 0;
  long long history_rows = 0;
  std::size_t snapshots = 0;  ///< field snapshots (output.fields_at, each step once at most)
  double memory_bytes = 0.0;
  double output_bytes = 0.0;
};

/// `streamed_fields`: the snapshots go to the run directory as they are
/// taken (RunOptions::fields), else all are held to the end.
[[nodiscard]] ResourceEstimate estimate_resources(const Case& c, bool streamed_fields);

/// The memory a run may still take: MemAvailable (/proc/meminfo), or what
/// the address-space limit (ulimit -v) leaves of it, whichever is smaller;
/// infinity when neither is known.
[[nodiscard]] double available_memory();

/// Throws InputError when `e.memory_bytes` exceeds `available`, naming the
/// keys that would bring it down (the elements, output.fields_at,
/// output.every, time.end / time.step) and both numbers.
void refuse_beyond_memory(const Case& c, const ResourceEstimate& e, double available);

/// Above this, the outputs get a warning before the run.
inline constexpr double large_output_bytes = 1e9;

/// The warning (without "warning: ") when the outputs will exceed
/// large_output_bytes; empty otherwise.
[[nodiscard]] std::string output_size_warning(const Case& c, const ResourceEstimate& e);

/// Estimates `c`'s resources, refuses it beyond the available memory and
/// returns the outputs' warning, if any: what `run` and `check` do first,
/// on the case as read (before fitting builds its line; a step left to the
/// scheme counts its nodes and snapshots only) and again once fitted.
[[nodiscard]] std::string check_resources(const Case& c, bool streamed_fields);

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
  ResourceEstimate resources;
};

/// Checks `c` (already validated by Case) and times up to `timing_budget`
/// node-steps of it. Throws InputError only as Case does.
[[nodiscard]] CaseCheck check_case(const Case& c, double timing_budget = 2e6);

/// The report `barimpact check` prints: one `key: value` line per item
/// (steps, stable step, penalty, time estimate), numbers to 4 digits.
[[nodiscard]] std::string check_text(const Case& c, const CaseCheck& k);

}  // namespace barimpact
