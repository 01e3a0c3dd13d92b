// Residual stresses in pile driving: the blows at one penetration, each
// starting from the rest the previous one left (Holloway et al. 1978's
// residual stress analysis; GRLWEAP's "residual stress analysis"). Between
// blows a static solve on the soil's springs brings the pile to rest: the
// forces the blow locked into the pile, the shaft and the toe balance.
#pragma once

#include "barimpact/run/simulate.hpp"
#include "barimpact/schemes/line_scheme.hpp"

namespace barimpact {

/// Brings the pile (the line's nodes first..last, its toe at `first` on the
/// near end's Smith link `toe`, or none) to static rest on its soil, from
/// `rest`: Newton's iteration on the bar's stiffness and the springs'
/// elastic-plastic forces (each spring slipping on from its state in
/// `rest`), until every node's forces balance to `tolerance` (N). Updates
/// `rest` (displacements, slips, the toe's largest compression) and returns
/// the toe's locked-in force (compression > 0). Throws std::runtime_error
/// when the iteration does not converge.
double settle(const Line& line, std::size_t first, std::size_t last, std::size_t toe, LineScheme::SoilRest& rest,
              double tolerance);

/// The blows of a case with [drive] blows = N > 1 at its depth: the first
/// from rest, each next from the static rest of the previous (the hammer's
/// bodies touching the pile head again, their cushions unloaded), until the
/// set changes by less than 1% or N blows. The last blow is the result; its
/// summary gives the first blow's set, the blows run and the toe's force
/// locked in before the last blow (residual_toe_force).
[[nodiscard]] RunResult run_residual(const FittedCase& fitted, const RunOptions& options);

}  // namespace barimpact
