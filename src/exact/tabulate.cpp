#include "barimpact/exact/tabulate.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>

#include "barimpact/exact/exact.hpp"
#include "barimpact/exact/lines.hpp"
#include "barimpact/schemes/registry.hpp"

namespace barimpact {

namespace {

// An exact solution tabulated as a run, up to where it is known (the
// case's end, or the solution's horizon: then said in a warning).
RunResult run_known(const Case& c, Scheme& scheme, double known, const std::string& name, const RunOptions& options) {
  long long steps = c.step_count();
  if (std::isfinite(known)) steps = std::min(steps, static_cast<long long>(std::floor(known / c.time.step)));
  RunResult r = run_scheme(c, scheme, steps, options, false);
  r.summary.method = "exact";
  r.summary.message = name;
  if (steps < c.step_count())
    r.summary.warnings.push_back(
        fmt::format("exact-horizon: the exact solution is known up to t = {:.6g} only; tabulated to t = {:.6g}, not to "
                    "time.end = {:.6g}",
                    known, static_cast<double>(steps) * c.time.step, c.time.end));
  return r;
}

RunResult run_exact_line(const Case& c, const RunOptions& options) {
  std::shared_ptr<const exact::LineSolution> solution = exact::for_line_case(c);
  if (!solution)
    throw InputError(
        "exact: this line admits no exact solution barimpact knows (two free bars of one material through a rigid "
        "joint; a mass on a rigid joint striking a bar clamped at x = 0; two welded bars under a constant force at x "
        "= 0; each at rest or in uniform motion, without viscosity, body force or gravity; or von Karman's "
        "elastic-plastic bar, E_t > 0, driven at a constant velocity at x = 0 or moving onto a rigid wall)");
  auto scheme = exact::as_line_scheme(c, solution);
  return run_known(c, *scheme, solution->valid_until(), solution->name(), options);
}
}  // namespace

RunResult run_exact(const Case& case_read, const RunOptions& options) {
  const Case c = fit_scheme(case_read).c;  // the step the case's scheme takes: the table's rows
  if (!c.one_bar()) return run_exact_line(c, options);
  std::shared_ptr<const exact::Solution> solution = exact::for_case(c);
  if (!solution)
    throw InputError(
        "exact: this case admits no exact solution barimpact knows (uniform elastic bar, u0 = 0 and uniform v0 < 0 "
        "against a rigid obstacle with gap, or with a constant load, or against an elastic obstacle; or the clamped "
        "bar released from u0 = kappa (L - x) onto a rigid obstacle)");
  auto scheme = exact::as_scheme(c, solution);  // energies are NaN where u(x, t) is not known
  return run_known(c, *scheme, solution->valid_until(), solution->name(), options);
}

}  // namespace barimpact
