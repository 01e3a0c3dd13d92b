#include "barimpact/schemes/scheme.hpp"

#include "barimpact/case/line_builder.hpp"
#include "barimpact/schemes/line_characteristic.hpp"
#include "barimpact/schemes/line_scheme.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <array>
#include <cmath>

#include "barimpact/schemes/paper_scheme.hpp"

namespace barimpact {

namespace {

// Every scheme's name, in the order `check` and the documentation list them.
constexpr std::array<std::string_view, 7> names{
    "paper",           "newmark",     "central-difference", "mass-redistribution",
    "paoli-schatzman", "moreau-jean", "characteristic"};

void check_name(std::string_view name) {
  if (std::find(names.begin(), names.end(), name) == names.end())
    throw InputError(fmt::format("time.scheme: unknown scheme \"{}\"", name));
}

}  // namespace

std::vector<std::string_view> scheme_names() {
  return {names.begin(), names.end()};
}

namespace {

// time.step = "auto": 0.9 of the explicit scheme's stable limit (its
// Gershgorin bound, already below the true limit, with a margin for the
// soil's damping, which grows with its static force).
std::optional<SchemeMisfit> choose_step(Case& c, const Line& line) {
  const std::string& name = c.time.scheme;
  if (name == "characteristic") return std::nullopt;  // it sets dt = h/c itself
  if (name != "central-difference" && name != "paoli-schatzman")
    return SchemeMisfit{"step", fmt::format("= \"auto\" chooses a stable step for the explicit schemes "
                                            "(central-difference, paoli-schatzman, characteristic); \"{}\" needs a "
                                            "number",
                                            name)};
  const bool consistent = name == "paoli-schatzman";
  c.time.step = auto_step_fraction * line_stable_step(line, consistent);
  if (!(c.time.step > 0) || !std::isfinite(c.time.step))
    return SchemeMisfit{"step", "= \"auto\" finds no stable limit for this line (nothing stiff in it): give a number"};
  return std::nullopt;
}

}  // namespace

namespace {

// The line a scheme is checked against while the case is read. Only the
// explicit schemes' limits, "auto" and characteristic's h/c depend on the
// mesh; for the others each bar is checked with at most two elements (what
// mass redistribution asks of a bar between two rigid links), so that
// reading a case costs its bodies, not its nodes.
Line checked_line(const Case& c) {
  const std::string& name = c.time.scheme;
  if (c.time.step_auto || name == "central-difference" || name == "paoli-schatzman" || name == "characteristic")
    return build_line(c);
  Case coarse = c;
  for (auto& b : coarse.bodies)
    if (b.kind == BodyKind::bar) b.elements = std::min(b.elements, 2);
  coarse.bar.elements = std::min(coarse.bar.elements, 2);  // the paper view of one bar
  return build_line(coarse);
}

}  // namespace

std::optional<SchemeMisfit> scheme_misfit(Case& c, bool step_given) {
  check_name(c.time.scheme);
  const Line line = checked_line(c);
  if (c.time.step_auto)
    if (auto m = choose_step(c, line)) return m;
  // The characteristic scheme steps at the bars' common transit time h/c
  // (an elastic-plastic line it refuses first, below, whatever the step).
  if (c.time.scheme == "characteristic" && !line.plastic())
    if (const auto dt = line_characteristic_step(line)) {
      if (step_given && std::abs(c.time.step - *dt) > 1e-9 * *dt)
        return SchemeMisfit{"step", fmt::format("= {} conflicts with characteristic, which sets dt = h/c = {} "
                                                "(omit time.step or give that value)",
                                                c.time.step, *dt)};
      c.time.step = *dt;
    }
  if (auto m = line_scheme_misfit(c, line)) return SchemeMisfit{m->key, m->rule};
  return std::nullopt;
}

double Scheme::far_force() const {
  return std::numeric_limits<double>::quiet_NaN();
}

std::unique_ptr<Scheme> make_scheme(const Case& c) {
  // One bar and its near end under the paper's scheme: the fused sweep of
  // its one uniform stretch (paper_scheme.hpp), which the SIMD batch shares.
  if (c.single_bar && c.time.scheme == "paper") return std::make_unique<PaperScheme>(c);
  return make_line_scheme(c);
}

}  // namespace barimpact
