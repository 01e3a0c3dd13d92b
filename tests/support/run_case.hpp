// Helpers shared by the tests: build a case from TOML text and overrides,
// run it, and read columns of its history.
#pragma once

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <gtest/gtest.h>

#include <chrono>
#include <initializer_list>
#include <string>
#include <vector>

#include "barimpact/case/case.hpp"
#include "barimpact/case/line_builder.hpp"
#include "barimpact/run/simulate.hpp"
#include "barimpact/schemes/registry.hpp"

namespace barimpact::testing {

// The case as the command and the module hand it on: read, then fitted to
// its scheme (its step as the scheme takes it, every refusal made).
inline Case case_from(const std::string& toml, const std::vector<std::string>& sets = {}) {
  std::vector<Case::Override> overrides;
  for (const auto& s : sets) overrides.push_back({s});
  return fit_scheme(Case::from_string(toml, overrides, "test.toml")).c;
}

// The one-line message of a case that must be refused; a failure (and "")
// if it is accepted.
inline std::string refusal(const std::string& toml, const std::vector<std::string>& sets = {}) {
  try {
    (void)case_from(toml, sets);
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_EQ(what.find('\n'), std::string::npos) << "one line: " << what;
    return what;
  }
  ADD_FAILURE() << "accepted: " << toml << "\nwith " << fmt::format("{}", fmt::join(sets, " "));
  return "";
}

// The case is refused (reading or fitting it throws) with a message holding every part
// (the key first).
#define EXPECT_REFUSED(toml, ...)                                                    \
  do {                                                                               \
    const std::string msg_ = ::barimpact::testing::refusal(toml);                    \
    for (const std::string& part_ : std::initializer_list<std::string>{__VA_ARGS__}) \
      EXPECT_NE(msg_.find(part_), std::string::npos) << msg_;                        \
  } while (0)

inline Case example(const std::string& name, const std::vector<std::string>& sets = {}) {
  std::vector<Case::Override> overrides;
  for (const auto& s : sets) overrides.push_back({s});
  return fit_scheme(Case::from_file(std::string(BARIMPACT_EXAMPLES_DIR) + "/" + name, overrides)).c;
}

// The case through the line engine's scheme (the table's factory), never a
// one-bar kernel of its own (the paper's fused sweep): what the scheme runs
// on a line of several bodies, here on any line.
inline RunResult run_line_engine(const Case& c) {
  auto scheme = scheme_info(c.time.scheme).make(c, build_line(c));
  RunRecorder recorder(c, *scheme);
  const auto started = std::chrono::steady_clock::now();
  const LoopResult loop = simulate(*scheme, c.step_count(), recorder.observers());
  return recorder.finish(loop, c.step_count(), started);
}

inline double total_energy(const HistoryRow& r) {
  return r.total();
}

}  // namespace barimpact::testing
