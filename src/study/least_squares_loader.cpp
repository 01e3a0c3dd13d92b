#include "barimpact/model/input_error.hpp"

#include "../model/module_loader.hpp"
#include "least_squares.hpp"

namespace barimpact::detail {

namespace {

// Loaded the first time a match fits; a failure is reported each time (a
// thrown static initialisation is tried again).
const FitModule& fit_module() {
  static const FitModule* module = load_module<FitModule, MissingModule>(BARIMPACT_FIT_MODULE, fit_module_entry,
                                                                         "signal matching", "fitting module");
  return *module;
}

}  // namespace

void load_least_squares() {
  fit_module();
}

LeastSquaresSummary solve_least_squares(const LeastSquaresProblem& p, double* x) {
  return fit_module().solve(p, x);
}

}  // namespace barimpact::detail
