// A diesel hammer's ram dropped from its ports onto its anvil on a rigid
// stop (examples/pile/diesel-rigid-stop.toml), shared by the tests of the
// diesel cylinder's runs (its gas history, the budget, the rebound): ram
// 1000 kg from H = 2 m above impact, so at the ports (0.5 m) moving down at
// sqrt(2 g (H - 0.5)); bore 0.05 m^2, chamber 0.1 m, 3 MPa after
// combustion, the impact cushion's defaults (2e10 N/m, e = 0.8). On the
// stop the ram rebounds to e^2 (H - W_c / m g) + W_e / m g.
#pragma once

#include <cmath>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "run_case.hpp"

namespace barimpact::testing {

struct DieselDrop {
  static constexpr double g = 9.81, ram = 1000.0, stroke = 2.0, restitution = 0.8;
  static constexpr double area = 0.05, ports = 0.5, chamber = 0.1, combustion = 3e6, atmosphere = 101325.0;
  /// The rebound height from energy: the cushion gives back e^2 of what the
  /// ram brings, the gas takes W_c on the way down and gives W_e back.
  static double rebound(double w_c, double w_e) {
    return restitution * restitution * (stroke - w_c / (ram * g)) + w_e / (ram * g);
  }
  /// The gas's absolute pressure at opening y on its polytropes, before or after impact.
  static double pressure(double y, bool fired) {
    if (y >= ports) return atmosphere;
    return fired ? combustion * std::pow(chamber / (chamber + y), 1.25)
                 : atmosphere * std::pow((chamber + ports) / (chamber + y), 1.35);
  }
};

// examples/pile/diesel-rigid-stop.toml's text.
inline std::string diesel_drop_text() {
  std::ifstream in(std::string(BARIMPACT_EXAMPLES_DIR) + "/pile/diesel-rigid-stop.toml");
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// The example, every step in its history (and `sets`).
inline Case diesel_drop(std::vector<std::string> sets = {}) {
  sets.insert(sets.begin(), "output.every=1");
  return example("pile/diesel-rigid-stop.toml", sets);
}

}  // namespace barimpact::testing
