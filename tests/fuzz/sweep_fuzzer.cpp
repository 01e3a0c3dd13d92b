// Fuzz target: a sweep file's text through SweepPlan::from_string, and the
// case of its first points (parsed, never run). `case` is resolved in
// tests/fuzz/sweep/, which holds a small fixed case.toml.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "barimpact/study/sweep.hpp"
#include "fuzz_target.hpp"

#ifndef BARIMPACT_FUZZ_SWEEP_DIR
#error "BARIMPACT_FUZZ_SWEEP_DIR must name tests/fuzz/sweep"
#endif

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  barimpact::fuzz::expect_parsed_or_refused([&] {
    const auto plan = barimpact::SweepPlan::from_string(text, "fuzz-sweep.toml", BARIMPACT_FUZZ_SWEEP_DIR);
    if (plan.points().empty()) barimpact::fuzz::finding("a sweep plan without points", text);
    std::size_t tried = 0;
    for (const auto& p : plan.points()) {
      if (++tried > 4) break;
      // A point whose combination is invalid is a refused row, not a plan error.
      barimpact::fuzz::expect_parsed_or_refused([&] { barimpact::fuzz::expect_round_trip(plan.case_at(p)); });
    }
  });
  return 0;
}
