#include "barimpact/schemes/registry.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

#include "barimpact/case/line_builder.hpp"
#include "barimpact/model/setup_polling.hpp"
#include "barimpact/schemes/line_central_difference.hpp"
#include "barimpact/schemes/line_characteristic.hpp"
#include "barimpact/schemes/line_mass_redistribution.hpp"
#include "barimpact/schemes/line_moreau_jean.hpp"
#include "barimpact/schemes/line_newmark.hpp"
#include "barimpact/schemes/line_paoli_schatzman.hpp"
#include "barimpact/schemes/line_paper.hpp"
#include "barimpact/schemes/line_rigid.hpp"
#include "barimpact/schemes/paper_scheme.hpp"

namespace barimpact {

namespace {

template <class S>
std::unique_ptr<Scheme> make(const Case& c, Line line) {
  return std::make_unique<S>(c, std::move(line));
}

// The paper's scheme on one bar and its near end: the fused sweep of its
// one uniform stretch (paper_scheme.hpp), which the SIMD batch shares.
std::unique_ptr<Scheme> make_fused_paper(const Case& c, Line line) {
  return std::make_unique<PaperScheme>(c, std::move(line));
}

bool has_soil(const Line& line) {
  return !line.shaft.empty() ||
         std::any_of(line.links.begin(), line.links.end(), [](const Link& l) { return l.law.kind == LawKind::smith; });
}

// The implicit schemes solve Smith's soil by Newton's iteration at the new
// level (soil_iteration.hpp), which does not yet share its step with the
// plastic iteration.
std::optional<SchemeMisfit> implicit_soil_misfit(const Case& c, const Line& line) {
  if (has_soil(line))
    for (std::size_t b = 0; b < line.plasticity.size(); ++b)
      if (line.plasticity[b])
        return SchemeMisfit{"scheme", fmt::format("= \"{}\" cannot run Smith's soil beside the elastic-plastic "
                                                  "body \"{}\" yet (scheme that can: central-difference)",
                                                  c.time.scheme, line.bodies[b].name)};
  return std::nullopt;
}

std::optional<SchemeMisfit> newmark_misfit(const Case& c, const Line& line) {
  if (has_soil(line) && !(c.time.beta > 0.0))
    return SchemeMisfit{"beta",
                        "= 0 (explicit newmark) cannot run Smith's soil: its iteration needs beta > 0 (or use "
                        "scheme = \"central-difference\")"};
  return implicit_soil_misfit(c, line);
}

// The alpha-scheme is Newmark's average acceleration with beta = alpha
// (docs/methods.md); newmark takes its own.
NewmarkFamily paper_family(const Case& c) {
  return {c.time.alpha, 0.5, "alpha < 1/4"};
}
NewmarkFamily newmark_family(const Case& c) {
  return {c.time.beta, c.time.gamma, "2 beta < gamma"};
}

// name, factory, mass, step, penalty, rigid, soil, plastic, energy tolerance,
// bytes per node, own rules, Newmark's family, one-bar kernel.
// The tolerances: about three times the largest drift of a resolved run of
// the scheme on the examples it fits (paper 0.85%, newmark 0.12%, central
// differences 0.72%, characteristic 1.0% (an impact between grid times),
// paoli-schatzman 0.48%, moreau-jean 0.86%, mass redistribution 1.4%).
// Characteristic runs no elastic-plastic bar: its plastic bytes are never read.
// The paper's bar alone: 190 + 32 for its partitioned solve's factors and
// spikes (peak RSS of a 20-step run, 10^6 against 10^3 elements, with and
// without them).
constexpr std::array<SchemeInfo, scheme_names.size()> table{{
    {"paper", make<LinePaper>, MassMatrix::consistent, StepRule::given, true, false, true, true, 0.03,
     NodeBytes{222, 420, 590}, implicit_soil_misfit, paper_family, make_fused_paper},
    {"newmark", make<LineNewmark>, MassMatrix::consistent, StepRule::given, true, false, true, true, 0.01,
     NodeBytes{400, 400, 490}, newmark_misfit, newmark_family},
    {"central-difference", make<LineCentralDifference>, MassMatrix::lumped, StepRule::limited, true, true, true, true,
     0.03, NodeBytes{280, 280, 300}, nullptr},
    {"mass-redistribution", make<LineMassRedistribution>, MassMatrix::redistributed, StepRule::given, false, true,
     false, true, 0.05, NodeBytes{280, 280, 350}, redistribution_misfit},
    {"paoli-schatzman", make<LinePaoliSchatzman>, MassMatrix::consistent, StepRule::limited, true, true, false, true,
     0.02, NodeBytes{310, 310, 320}, nullptr},
    {"moreau-jean", make<LineMoreauJean>, MassMatrix::consistent, StepRule::given, false, true, false, true, 0.03,
     NodeBytes{290, 290, 360}, nullptr},
    {"characteristic", make<LineCharacteristic>, MassMatrix::lumped, StepRule::transit, false, true, false, false, 0.03,
     NodeBytes{200, 200, 200}, characteristic_line_misfit},
}};

// The case layer reads time.scheme against its list of names: the table's.
constexpr bool names_agree() {
  for (std::size_t i = 0; i < table.size(); ++i)
    if (table[i].name != scheme_names[i]) return false;
  return true;
}
static_assert(names_agree(), "case.hpp's scheme_names must list the table's schemes, in its order");

// "a, b, c": the schemes whose row has `can`.
std::string schemes_that(bool SchemeInfo::*can) {
  std::string out;
  for (const auto& s : table)
    if (s.*can) out += (out.empty() ? "" : ", ") + std::string(s.name);
  return out;
}

// A diesel cylinder's gas is no piecewise-linear law: the schemes that apply
// penalty laws as forces at t_n (the explicit ones) run it, not the implicit
// ones' exact branch solve (penalty_links.hpp).
bool runs_diesel(const SchemeInfo& s) {
  return s.penalty_laws && s.step == StepRule::limited;
}

std::optional<SchemeMisfit> diesel_misfit(const SchemeInfo& s, const Line& line) {
  for (const auto& l : line.links) {
    if (l.law.kind != LawKind::diesel || runs_diesel(s)) continue;
    std::string names;
    for (const auto& other : table)
      if (runs_diesel(other)) names += (names.empty() ? "" : ", ") + std::string(other.name);
    return SchemeMisfit{l.name + ".law",
                        fmt::format("= \"diesel\" runs on the schemes {} only (time.scheme is \"{}\")", names, s.name)};
  }
  return std::nullopt;
}

// The laws and bodies a scheme does not run, by its row.
std::optional<SchemeMisfit> law_misfit(const SchemeInfo& s, const Line& line) {
  auto refuse = [](std::string rule) { return SchemeMisfit{"scheme", std::move(rule)}; };
  const std::string me = fmt::format("= \"{}\"", s.name);
  if (!s.soil && has_soil(line))
    return refuse(fmt::format("{} cannot run Smith's soil (law = \"smith\", [body.shaft]) yet (schemes that can: {})",
                              me, schemes_that(&SchemeInfo::soil)));
  if (!s.plastic)
    for (std::size_t b = 0; b < line.plasticity.size(); ++b)
      if (line.plasticity[b])
        return refuse(fmt::format("{} cannot run the elastic-plastic body \"{}\" (schemes that can: {})", me,
                                  line.bodies[b].name, schemes_that(&SchemeInfo::plastic)));
  for (const auto& l : line.links) {
    if (l.law.rigid() && !s.rigid_laws)
      return refuse(fmt::format("{} cannot run the rigid link \"{}\" (penalty laws only; schemes that can: {})", me,
                                l.name, schemes_that(&SchemeInfo::rigid_laws)));
    if (!l.law.rigid() && l.law.kind != LawKind::smith && !s.penalty_laws)
      return refuse(fmt::format("{} cannot run the {} link \"{}\" (rigid links only; schemes that can: {})", me,
                                to_string(l.law.kind), l.name, schemes_that(&SchemeInfo::penalty_laws)));
  }
  return std::nullopt;
}

// An explicit scheme's step against its stable limit (a step at the limit,
// Courant 1, is stable).
std::optional<SchemeMisfit> step_misfit(const SchemeInfo& s, const Case& c, const Line& line) {
  if (s.step != StepRule::limited) return std::nullopt;
  const bool consistent = s.mass == MassMatrix::consistent;
  const double limit = line_stable_step(line, consistent);
  if (c.time.step > limit * (1.0 + 1e-12))
    return SchemeMisfit{"step", fmt::format("= {} is above {}'s stable limit {:.6g} for this line{}", c.time.step,
                                            s.name, limit, consistent ? " (consistent mass)" : "")};
  return std::nullopt;
}

// time.step = "auto": 0.9 of the explicit scheme's stable limit (its
// Gershgorin bound, already below the true limit, with a margin for the
// soil's damping, which grows with its static force).
std::optional<SchemeMisfit> choose_step(const SchemeInfo& s, Case& c, const Line& line) {
  if (s.step == StepRule::transit) return std::nullopt;  // it sets dt = h/c itself
  if (s.step != StepRule::limited) {
    std::string explicit_names;
    for (const auto& other : table)
      if (other.step != StepRule::given)
        explicit_names += (explicit_names.empty() ? "" : ", ") + std::string(other.name);
    return SchemeMisfit{"step", fmt::format("= \"auto\" chooses a stable step for the explicit schemes ({}); \"{}\" "
                                            "needs a number",
                                            explicit_names, s.name)};
  }
  c.time.step = auto_step_fraction * line_stable_step(line, s.mass == MassMatrix::consistent);
  if (!(c.time.step > 0) || !std::isfinite(c.time.step))
    return SchemeMisfit{"step",
                        "= \"auto\" finds no stable step for this line: its stable limit is 0 (a stiffness too large "
                        "for any step against its masses: a soil's ultimate / quake, a joint's or an end's stiffness) "
                        "or unbounded (nothing stiff in it): give a number"};
  return std::nullopt;
}

// The transit-time scheme steps at the bars' common h/c (an elastic-plastic
// line it refuses, whatever the step).
std::optional<SchemeMisfit> set_transit_step(const SchemeInfo& s, Case& c, const Line& line, bool step_given) {
  if (s.step != StepRule::transit || line.plastic()) return std::nullopt;
  const auto dt = line_characteristic_step(line);
  if (!dt) return std::nullopt;
  if (step_given && std::abs(c.time.step - *dt) > 1e-9 * *dt)
    return SchemeMisfit{"step", fmt::format("= {} conflicts with {}, which sets dt = h/c = {} (omit time.step or "
                                            "give that value)",
                                            c.time.step, s.name, *dt)};
  c.time.step = *dt;
  return std::nullopt;
}

// Only the explicit schemes' limits, "auto" and the transit time depend on
// the mesh.
bool mesh_matters(const SchemeInfo& s, const Case& c) {
  return c.time.step_auto || s.step != StepRule::given;
}

// The line a scheme is checked against: for a scheme whose fit does not
// depend on the mesh, each bar with at most two elements (what mass
// redistribution asks of a bar between two rigid links), so that reading a
// case costs its bodies, not its nodes.
Line checked_line(const SchemeInfo& s, const Case& c) {
  if (mesh_matters(s, c)) return build_line(c);
  Case coarse = c;
  for (auto& b : coarse.bodies)
    if (b.kind == BodyKind::bar) b.elements = std::min(b.elements, 2);
  return build_line(coarse);
}

}  // namespace

std::span<const SchemeInfo> schemes() {
  return table;
}

const SchemeInfo& scheme_info(std::string_view name) {
  for (const auto& s : table)
    if (s.name == name) return s;
  throw InputError(fmt::format("time.scheme: unknown scheme \"{}\"", name));
}

std::optional<SchemeMisfit> scheme_misfit(const Case& c, const Line& line) {
  const SchemeInfo& s = scheme_info(c.time.scheme);
  if (auto m = diesel_misfit(s, line)) return m;
  if (auto m = law_misfit(s, line)) return m;
  if (s.misfit)
    if (auto m = s.misfit(c, line)) return m;
  return step_misfit(s, c, line);
}

FittedCase fit_scheme(Case c) {
  const SchemeInfo& s = scheme_info(c.time.scheme);
  Line line = checked_line(s, c);
  // A time key by its name alone, another (a joint's law) by its full name.
  auto refuse = [&c](const SchemeMisfit& m) {
    c.refuse(m.key.find('.') == std::string::npos ? "time." + m.key : m.key, m.rule);
  };
  if (c.time.step_auto)
    if (const auto m = choose_step(s, c, line)) refuse(*m);
  if (const auto m = set_transit_step(s, c, line, c.time.step_given)) refuse(*m);
  if (const auto m = scheme_misfit(c, line)) refuse(*m);
  c.check_steps();
  c.time.step_given = !c.time.step_auto;  // the step is the scheme's now: a resolved case writes it
  const bool whole = mesh_matters(s, c);
  return {std::move(c), whole ? std::optional<Line>(std::move(line)) : std::nullopt};
}

std::unique_ptr<Scheme> make_scheme(FittedCase& fitted) {
  const Case& c = fitted.c;
  const SchemeInfo& s = scheme_info(c.time.scheme);
  Line line = fitted.line ? std::move(*fitted.line) : build_line(c);
  fitted.line.reset();
  poll_setup();
  auto scheme = s.one_bar && c.one_bar() ? s.one_bar(c, std::move(line)) : s.make(c, std::move(line));
  poll_setup();
  return scheme;
}

std::unique_ptr<Scheme> make_scheme(const Case& c) {
  FittedCase fitted = fit_scheme(c);
  return make_scheme(fitted);
}

}  // namespace barimpact
