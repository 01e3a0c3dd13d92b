// summary.json's "units": what its numbers are in, and what the console
// prints them in. Internal to src/.
#pragma once

#include <nlohmann/json.hpp>
#include <string_view>

#include "barimpact/case/units.hpp"

namespace barimpact {

/// {"system": "SI" | "US", "numbers": "SI", the numbers' base units, "display":
/// the console's units}, or {"system": "none"} (the case's own numbers).
/// Under "US" the numbers stay SI: only the console and figures convert.
inline nlohmann::json units_json(std::string_view system) {
  const units::Display* d = units::display(system);
  if (d == nullptr) return {{"system", system}};
  return {{"system", system},
          {"numbers", "SI"},
          {"length", "m"},
          {"time", "s"},
          {"force", "N"},
          {"stress", "Pa"},
          {"energy", "J"},
          {"velocity", "m/s"},
          {"display",
           {{"set", d->set.name},
            {"depth", d->depth.name},
            {"force", d->force.name},
            {"stress", d->stress.name},
            {"energy", d->energy.name},
            {"velocity", d->velocity.name},
            {"blow_count", d->count_name}}}};
}

}  // namespace barimpact
