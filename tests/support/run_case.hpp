// Helpers shared by the tests: build a case from TOML text and overrides,
// run it, and read columns of its history.
#pragma once

#include <string>
#include <vector>

#include "barimpact/case/case.hpp"
#include "barimpact/run/simulate.hpp"

namespace barimpact::testing {

inline Case case_from(const std::string& toml, const std::vector<std::string>& sets = {}) {
  std::vector<Case::Override> overrides;
  for (const auto& s : sets) overrides.push_back({s});
  return Case::from_string(toml, overrides, "test.toml");
}

inline Case example(const std::string& name, const std::vector<std::string>& sets = {}) {
  std::vector<Case::Override> overrides;
  for (const auto& s : sets) overrides.push_back({s});
  return Case::from_file(std::string(BARIMPACT_EXAMPLES_DIR) + "/" + name, overrides);
}

inline double total_energy(const HistoryRow& r) {
  return r.total();
}

}  // namespace barimpact::testing
