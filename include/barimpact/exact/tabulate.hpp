// An exact solution run as a case: tabulated on the case's time grid
// through a run's observers, so that it gives the files and the history
// columns of `run` and is compared with runs column by column.
#pragma once

#include "barimpact/case/case.hpp"
#include "barimpact/run/simulate.hpp"

namespace barimpact {

/// Tabulates the exact solution the case admits (exact.hpp, lines.hpp) on
/// its time grid, through the same observers: same history columns as
/// `run`, rows up to the end or to where the solution is known. Throws
/// InputError when the case admits none.
[[nodiscard]] RunResult run_exact(const Case& c, const RunOptions& options = {});

}  // namespace barimpact
