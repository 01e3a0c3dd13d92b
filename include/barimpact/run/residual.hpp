// Residual stresses in pile driving: the blows at one penetration, each
// starting from the rest the previous one left (Holloway et al. 1978's
// residual stress analysis; GRLWEAP's "residual stress analysis"). Between
// blows a static solve on the soil's springs brings the pile to rest: the
// forces the blow locked into the pile, the shaft and the toe balance.
#pragma once

#include "barimpact/run/simulate.hpp"
#include "barimpact/schemes/line_scheme.hpp"

namespace barimpact {

/// Brings the line's nodes 0..count-1 (the pile and what rests on it below
/// the ram) to static rest on their soil under `gravity`, from `rest`:
/// Newton's iteration on the bonds' stiffness, the links' and the springs'
/// elastic-plastic forces (each spring slipping on from its state in
/// `rest`), until every node's forces balance to `tolerance` (N). Updates
/// `rest` (displacements, slips, the links' largest compressions) and
/// returns the toe's force (compression > 0). Throws std::runtime_error
/// when the iteration does not converge.
double settle(const Line& line, std::size_t count, double gravity, LineScheme::SoilRest& rest, double tolerance);

/// A pile line under gravity starts from static equilibrium: the pile's
/// weight on the soil, the helmet and cushions on the pile; the ram takes
/// no part (it starts touching the body below, at its velocity). Sets the
/// scheme's start; false when the scheme cannot start from a given state.
bool start_at_rest(const Case& c, Scheme& scheme);

/// The blows of a case with [drive] blows = N > 1 at its depth: the first
/// from rest, each next from the static rest of the previous (the hammer's
/// bodies touching the pile head again, their cushions unloaded), until the
/// set changes by less than 1% or N blows. The last blow is the result; its
/// summary gives the first blow's set, the blows run and the toe's force
/// locked in before the last blow (residual_toe_force).
[[nodiscard]] RunResult run_residual(const FittedCase& fitted, const RunOptions& options);

}  // namespace barimpact
