// A run's checks of its own health: what makes a run that completed still
// not to be trusted. Each finding is one line for the user (stderr and
// summary.json's `warnings`); `barimpact --strict` turns any into exit 4.
//   - energy-balance: the budget E_kin + E_strain + E_obstacle - W_ext +
//     D_visc drifts beyond what the scheme guarantees on a resolved run;
//   - penalty-unresolved: the penalty obstacle's time constant Z / k (Z =
//     rho c = sqrt(rho a), the bar's impedance) is below the time step, so a
//     contact lasts less than a step and its force is not resolved;
//   - unstable-step: the paper scheme with alpha < 1/4, or Newmark with
//     2 beta < gamma, at a step beyond its stable one (such a run may still
//     end before it blows up);
//   - contact-chatter: most contact episodes last a step or two (the
//     contact switches on and off numerically).
// An explicit scheme's step beyond its stable one is refused before the run
// (scheme.hpp).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "barimpact/case/case.hpp"
#include "barimpact/model/line.hpp"
#include "barimpact/run/simulate.hpp"

namespace barimpact {

/// The largest budget drift a resolved run of the case's scheme keeps to,
/// relative to the largest energy the run holds (see energy_scale).
[[nodiscard]] double energy_balance_bound(const Case& c);

/// The energy against which a budget drift is judged: the larger of
/// |E_total(0)| and |W_ext| over the rows, or, when both are zero, the
/// largest stored energy E_kin + E_strain + E_obstacle.
[[nodiscard]] double energy_scale(const std::vector<HistoryRow>& history);

/// A penalty law's own time constant: how long its spring takes to stop
/// what it meets. tau = Z/k against a bar (Z = rho c A), Z1 Z2/((Z1 + Z2) k)
/// between two bars (their impedances in series), sqrt(m/k) against a point
/// mass (m1 m2/(m1 + m2) between two), the smaller of Z/k and sqrt(m/k)
/// between a bar and a mass (m Z p^2 + k m p + k Z = 0 has roots near both).
/// A step above tau does not resolve the contact's force.
struct PenaltyTimeConstant {
  std::string link;   ///< "obstacle" on a single bar, else the link's name (near_end, a joint, far_end)
  double tau;         ///< the time constant
  std::string basis;  ///< the formula that gave it, e.g. "Z/k"
};

/// Every penalty law's time constant (rigid and welded links have none),
/// on `c`'s line (built, or the run's).
[[nodiscard]] std::vector<PenaltyTimeConstant> penalty_time_constants(const Case& c);
[[nodiscard]] std::vector<PenaltyTimeConstant> penalty_time_constants(const Case& c, const Line& line);

/// The largest stable step of the paper scheme with alpha < 1/4, or Newmark
/// with 2 beta < gamma (gamma >= 1/2): omega_max dt <= (gamma/2 - beta)^(-1/2),
/// omega_max of the consistent mass with every penalty as a spring; nothing
/// for a scheme that is unconditionally stable or explicit.
[[nodiscard]] std::optional<double> conditional_stable_step(const Case& c);

/// Warnings as one CSV cell: joined by " | ", which no message holds.
[[nodiscard]] std::string join_warnings(const std::vector<std::string>& warnings);

/// The warnings of a finished run on `line` (an empty list for a healthy one).
[[nodiscard]] std::vector<std::string> check_health(const Case& c, const Line& line, const Summary& s,
                                                    const std::vector<HistoryRow>& history);

}  // namespace barimpact
