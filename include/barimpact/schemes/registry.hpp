// The one table of schemes: for each name `time.scheme` accepts, how it is
// made from the built line, whether it is explicit and with which mass
// matrix, which laws and bodies it runs, how its step is set, the energy
// drift a resolved run stays within, and what it says when it cannot run a
// case. Everything that asks "which scheme is this?" asks this table; no
// other file compares scheme names. Adding a scheme is one row here.
//
// It owns the fit of a scheme to a line (`scheme_misfit`) and the factory
// (`make_scheme`); the schemes themselves know nothing of each other.
#pragma once

#include <memory>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

#include "barimpact/case/case.hpp"
#include "barimpact/model/line.hpp"
#include "barimpact/schemes/scheme.hpp"

namespace barimpact {

/// The mass matrix a scheme steps with.
enum class MassMatrix { lumped, consistent, redistributed };

/// How a scheme's step is set.
enum class StepRule {
  given,    ///< time.step, any size (implicit schemes)
  limited,  ///< time.step below the explicit stable limit, or "auto"
  transit,  ///< dt = h/c, the bars' element transit time, set by the scheme
};

/// An implicit scheme of Newmark's family at the case's parameters: stable
/// for every step from 2 beta >= gamma >= 1/2, below it only conditionally
/// (health.hpp's conditional_stable_step).
struct NewmarkFamily {
  double beta, gamma;
  std::string_view rule;  ///< the condition in the scheme's own parameters, e.g. "alpha < 1/4"
};

/// Bytes a node adds to a run's peak memory with this scheme (check's
/// estimate): measured as (peak RSS at 10^6 elements - at 10^3) / 10^6 of
/// `barimpact run` without snapshots, rounded up.
struct NodeBytes {
  double one_bar;  ///< an elastic bar alone (its one-bar kernel, if any)
  double line;     ///< an elastic line of several bodies
  double plastic;  ///< an elastic-plastic bar
};

struct SchemeInfo {
  std::string_view name;
  /// Makes the scheme on the case's built line (the line must fit: scheme_misfit).
  std::unique_ptr<Scheme> (*make)(const Case& c, Line line);
  MassMatrix mass;
  StepRule step;
  bool penalty_laws;  ///< elastic, viscoelastic and cushion links
  bool rigid_laws;    ///< rigid links (Signorini with restitution)
  bool soil;          ///< Smith's soil (law "smith", [body.shaft])
  bool plastic;       ///< elastic-plastic bodies
  /// About three times the largest budget drift, relative to the run's
  /// energy, of a resolved run on the examples (health.hpp's energy-balance).
  double energy_tolerance;
  NodeBytes bytes_per_node;
  /// What else the scheme cannot run (a row of its own rules), or null.
  std::optional<SchemeMisfit> (*misfit)(const Case& c, const Line& line);
  /// Its (beta, gamma) when it is of Newmark's family, or null.
  NewmarkFamily (*family)(const Case& c) = nullptr;
  /// A kernel of its own for one bar and its near end (the paper's fused
  /// sweep of one uniform stretch, which the SIMD batch shares), or null.
  std::unique_ptr<Scheme> (*one_bar)(const Case& c, Line line) = nullptr;
};

/// Every scheme, in the order `check`, the refusals and the docs list them.
[[nodiscard]] std::span<const SchemeInfo> schemes();

/// The row of `name`. Throws InputError naming time.scheme when there is none.
[[nodiscard]] const SchemeInfo& scheme_info(std::string_view name);

/// time.step = "auto" takes this fraction of the explicit scheme's stable step.
inline constexpr double auto_step_fraction = 0.9;

/// Why `c.time.scheme` cannot run the line of `c`: the laws and bodies it
/// does not run, then its step (above an explicit limit, or not h/c).
[[nodiscard]] std::optional<SchemeMisfit> scheme_misfit(const Case& c, const Line& line);

/// A case fitted to its scheme (fit_scheme), and its line when fitting
/// needed it whole (an explicit scheme's limit, "auto", h/c): the run takes
/// that line rather than building it again. Empty when the scheme's fit
/// reads the bodies alone (a coarse line of them), so that fitting a large
/// case costs its bodies, not its nodes.
struct FittedCase {
  Case c;
  std::optional<Line> line;
};

/// Fits `c` to its scheme where the scheme is made, not where the case is
/// read: time.step = "auto" becomes auto_step_fraction of an explicit
/// scheme's stable step and characteristic's step dt = h/c (a step given
/// must be that); the laws, bodies and step the scheme cannot run are
/// refused, then the rules that follow from the step (Case::check_steps).
/// Throws InputError naming the key where it was set, as reading does.
[[nodiscard]] FittedCase fit_scheme(Case c);

/// The scheme of a fitted case, on its line (taken from `fitted`, or built).
[[nodiscard]] std::unique_ptr<Scheme> make_scheme(FittedCase& fitted);
/// Fits a copy of `c` and makes its scheme (its step the fitted one).
[[nodiscard]] std::unique_ptr<Scheme> make_scheme(const Case& c);

}  // namespace barimpact
