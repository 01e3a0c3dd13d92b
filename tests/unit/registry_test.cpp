// The table of schemes (registry.hpp): every scheme's row as docs/methods.md
// states it (the laws it runs, its mass matrix and step, its energy bound),
// the refusals naming the schemes that can, and time.step = "auto".
#include "barimpact/schemes/registry.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <string_view>

#include "../support/diesel.hpp"
#include "../support/line_parts.hpp"
#include "../support/line_runs.hpp"
#include "../support/pile.hpp"
#include "../support/run_case.hpp"
#include "barimpact/case/line_builder.hpp"
#include "barimpact/schemes/line_scheme.hpp"

namespace barimpact {
namespace {

using testing::bar;
using testing::case_from;
using testing::joint;
using testing::law_joint;
using testing::line_case;
using testing::mass;
using testing::pile_toml;

// A row as docs/methods.md's table of schemes and its health checks state
// it: the laws each runs ("obstacles": none and rigid, the penalty laws, or
// all four), its mass matrix (M_L, M_h), how its step is set (the explicit
// schemes' limit, the characteristic's Courant 1) and its energy-balance
// bound (1% newmark, 2% paoli-schatzman, 5% mass-redistribution, 3% the others).
struct Row {
  std::string_view name;
  MassMatrix mass;
  StepRule step;
  bool penalty, rigid, soil, plastic;
  double energy_tolerance;
};

constexpr Row documented[] = {
    {"paper", MassMatrix::consistent, StepRule::given, true, false, true, true, 0.03},
    {"newmark", MassMatrix::consistent, StepRule::given, true, false, true, true, 0.01},
    {"central-difference", MassMatrix::lumped, StepRule::limited, true, true, true, true, 0.03},
    {"mass-redistribution", MassMatrix::redistributed, StepRule::given, false, true, false, true, 0.05},
    {"paoli-schatzman", MassMatrix::consistent, StepRule::limited, true, true, false, true, 0.02},
    {"moreau-jean", MassMatrix::consistent, StepRule::given, false, true, false, true, 0.03},
    {"characteristic", MassMatrix::lumped, StepRule::transit, false, true, false, false, 0.03},
};

TEST(Registry, EveryRowIsTheDocumentedOneInTheDocumentedOrder) {
  const auto table = schemes();
  ASSERT_EQ(table.size(), std::size(documented));
  const auto& names = scheme_names;
  ASSERT_EQ(names.size(), table.size());
  for (std::size_t i = 0; i < table.size(); ++i) {
    const SchemeInfo& s = table[i];
    const Row& d = documented[i];
    EXPECT_EQ(s.name, d.name);
    EXPECT_EQ(names[i], d.name);
    EXPECT_EQ(&scheme_info(d.name), &s) << d.name;
    EXPECT_EQ(s.mass, d.mass) << d.name;
    EXPECT_EQ(s.step, d.step) << d.name;
    EXPECT_EQ(s.penalty_laws, d.penalty) << d.name;
    EXPECT_EQ(s.rigid_laws, d.rigid) << d.name;
    EXPECT_EQ(s.soil, d.soil) << d.name;
    EXPECT_EQ(s.plastic, d.plastic) << d.name;
    EXPECT_EQ(s.energy_tolerance, d.energy_tolerance) << d.name;
    EXPECT_NE(s.make, nullptr) << d.name;
    // Only the paper's scheme has a kernel of its own for one bar (its fused sweep).
    EXPECT_EQ(s.one_bar != nullptr, d.name == "paper") << d.name;
  }
}

// The alpha-scheme is Newmark's average acceleration with beta = alpha,
// gamma = 1/2; newmark takes the case's beta and gamma; no other scheme is
// of the family.
TEST(Registry, NewmarksFamilyIsThePaperSchemesAndNewmarksOwn) {
  Case c;
  c.time.alpha = 0.3;
  c.time.beta = 0.2;
  c.time.gamma = 0.6;
  for (const SchemeInfo& s : schemes()) {
    if (s.name == "paper") {
      ASSERT_NE(s.family, nullptr);
      const NewmarkFamily f = s.family(c);
      EXPECT_EQ(f.beta, 0.3);
      EXPECT_EQ(f.gamma, 0.5);
      EXPECT_EQ(f.rule, "alpha < 1/4");
    } else if (s.name == "newmark") {
      ASSERT_NE(s.family, nullptr);
      const NewmarkFamily f = s.family(c);
      EXPECT_EQ(f.beta, 0.2);
      EXPECT_EQ(f.gamma, 0.6);
      EXPECT_EQ(f.rule, "2 beta < gamma");
    } else {
      EXPECT_EQ(s.family, nullptr) << s.name;
    }
  }
}

TEST(Registry, AnUnknownSchemeIsRefusedNamingTimeScheme) {
  try {
    (void)scheme_info("euler");
    ADD_FAILURE() << "accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), "time.scheme: unknown scheme \"euler\"");
  }
  EXPECT_REFUSED("[time]\nscheme = \"euler\"\n", "time.scheme", "\"euler\"");
}

// Each law or body a scheme does not run is refused naming it and, in the
// table's order, every scheme whose row runs it.
TEST(Registry, RefusalsNameWhatTheSchemeCannotRunAndTheSchemesThatCan) {
  Case c = line_case({bar("a", 1.0, 10), mass("m", 1.0, -1.0)}, {law_joint("a", "m", JointLaw::elastic, 100.0)}, 0.001,
                     1.0, "mass-redistribution");
  auto misfit = scheme_misfit(c, build_line(c));
  ASSERT_TRUE(misfit.has_value());
  EXPECT_EQ(misfit->key, "scheme");
  EXPECT_EQ(misfit->rule,
            "= \"mass-redistribution\" cannot run the elastic link \"joint.a-m\" (rigid links only; schemes that can: "
            "paper, newmark, central-difference, paoli-schatzman)");
  c.time.scheme = "moreau-jean";
  EXPECT_NE(scheme_misfit(c, build_line(c))->rule.find("= \"moreau-jean\" cannot run the elastic link"),
            std::string::npos);
  try {
    (void)make_scheme(c);
    ADD_FAILURE() << "made";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("time.scheme = \"moreau-jean\" cannot run the elastic link", 0), 0u)
        << e.what();
  }
  // An elastic-plastic body: every scheme but the characteristic one.
  Case plastic = line_case({bar("p", 1.0, 10)}, {}, 0.05, 1.0, "characteristic");
  plastic.bodies[0].material.kind = MaterialKind::plastic;
  const auto body = scheme_misfit(plastic, build_line(plastic));
  ASSERT_TRUE(body.has_value());
  EXPECT_EQ(body->rule,
            "= \"characteristic\" cannot run the elastic-plastic body \"p\" (schemes that can: paper, newmark, "
            "central-difference, mass-redistribution, paoli-schatzman, moreau-jean)");
  // A diesel cylinder: the explicit schemes with penalty laws only, refused naming the joint's law.
  for (const char* scheme : {"newmark", "paper", "characteristic", "moreau-jean"}) {
    const std::string msg = testing::refusal(testing::diesel_drop_text(), {fmt::format("time.scheme=\"{}\"", scheme)});
    EXPECT_EQ(msg.rfind("joint.gas.law = \"diesel\" runs on the schemes central-difference, paoli-schatzman only", 0),
              0u)
        << msg;
    EXPECT_NE(msg.find(fmt::format("(time.scheme is \"{}\")", scheme)), std::string::npos) << msg;
  }
  // A scheme the line fits: no misfit.
  c.joints[0].law.law = JointLaw::rigid;
  EXPECT_FALSE(scheme_misfit(c, build_line(c)).has_value());
}

// A uniform free bar of M elements, E = 4, rho = A = 1 (c = 2), h = 1 / M:
// every node's Gershgorin bound is 4 c^2 / h^2 with the lumped mass, so the
// explicit stable step is h / c, and h / (c sqrt 3) with the consistent mass.
// "auto" takes auto_step_fraction (0.9) of it; characteristic takes h / c.
// Tolerance 1e-14 relative: the rounding of h = L / M and of the square root.
TEST(Registry, AutoStepIsTheFractionOfTheExplicitSchemesStableStep) {
  EXPECT_EQ(auto_step_fraction, 0.9);
  const std::string bar10 = "[[body]]\nname = \"b\"\nelements = 10\nmodulus = 4.0\n[time]\nstep = \"auto\"\n";
  const double h_over_c = 0.1 / 2.0;
  const Case cd = case_from(bar10 + "scheme = \"central-difference\"\n");
  EXPECT_TRUE(cd.time.step_auto);
  EXPECT_NEAR(cd.time.step, 0.9 * h_over_c, 1e-14 * h_over_c);
  const Case ps = case_from(bar10 + "scheme = \"paoli-schatzman\"\n");
  EXPECT_NEAR(ps.time.step, 0.9 * h_over_c / std::sqrt(3.0), 1e-14 * h_over_c);
  const Case ch = case_from(bar10 + "scheme = \"characteristic\"\n");
  EXPECT_NEAR(ch.time.step, h_over_c, 1e-14 * h_over_c);
  // The implicit schemes need a number, and the refusal names the schemes that choose one.
  for (const char* scheme : {"paper", "newmark", "moreau-jean", "mass-redistribution"})
    EXPECT_REFUSED(bar10 + fmt::format("scheme = \"{}\"\n", scheme), "time.step",
                   "= \"auto\" chooses a stable step for the explicit schemes (central-difference, paoli-schatzman, "
                   "characteristic)",
                   fmt::format("\"{}\" needs a number", scheme));
}

// A step at the explicit limit h / c runs; one above it is refused, naming
// the limit (on the bar of the test above).
TEST(Registry, AnExplicitStepAboveItsLimitIsRefusedNamingTheLimit) {
  Case c = line_case({bar("b", 1.0, 10)}, {}, 0.05, 1.0);
  c.bodies[0].modulus = 4.0;
  EXPECT_FALSE(scheme_misfit(c, build_line(c)).has_value());
  c.time.step = 0.051;
  const auto misfit = scheme_misfit(c, build_line(c));
  ASSERT_TRUE(misfit.has_value());
  EXPECT_EQ(misfit->key, "step");
  EXPECT_EQ(misfit->rule, "= 0.051 is above central-difference's stable limit 0.05 for this line");
  c.time.scheme = "paoli-schatzman";
  c.time.step = 0.03;  // above 0.05 / sqrt(3) = 0.0289
  EXPECT_EQ(scheme_misfit(c, build_line(c))->rule,
            "= 0.03 is above paoli-schatzman's stable limit 0.0288675 for this line (consistent mass)");
  c.time.scheme = "newmark";  // implicit: any step
  c.time.step = 1.0;
  EXPECT_FALSE(scheme_misfit(c, build_line(c)).has_value());
}

// Paper and Newmark run the penalty laws only: a rigid link is refused,
// naming it and the schemes that can run it.
TEST(LineSchemes, ImplicitPenaltySchemesRefuseRigidLinks) {
  for (const char* scheme : {"paper", "newmark"}) {
    Case c =
        line_case({bar("a", 1.0, 10), mass("m", 1.0, -1.0)}, {joint("a", "m", JointLaw::rigid)}, 0.01, 1.0, scheme);
    const auto misfit = scheme_misfit(c, build_line(c));
    ASSERT_TRUE(misfit.has_value()) << scheme;
    EXPECT_EQ(misfit->key, "scheme");
    EXPECT_EQ(misfit->rule, fmt::format("= \"{}\" cannot run the rigid link \"joint.a-m\" (penalty laws only; schemes "
                                        "that can: central-difference, mass-redistribution, paoli-schatzman, "
                                        "moreau-jean, characteristic)",
                                        scheme));
    EXPECT_THROW((void)make_scheme(c), InputError);
    c.joints[0].law.law = JointLaw::cushion;
    c.joints[0].law.stiffness = 100.0;
    c.joints[0].law.restitution = 0.5;
    c.near_end.law = JointLaw::rigid;
    EXPECT_NE(scheme_misfit(c, build_line(c))->rule.find("\"near_end\""), std::string::npos);
    c.near_end.law = JointLaw::viscoelastic;
    c.near_end.stiffness = 100.0;
    EXPECT_FALSE(scheme_misfit(c, build_line(c)).has_value());
  }
}

TEST(SmithCase, AutoStepIsTheStableStepOfTheLineWithItsSoil) {
  const Case c = case_from(pile_toml);
  const Line line = build_line(c);
  EXPECT_DOUBLE_EQ(c.time.step, auto_step_fraction * line_stable_step(line, false));
  // The soil stiffens the toe node: the step is below the bare pile's.
  std::string free = pile_toml;
  free.replace(free.find("[near_end]"), free.find("[time]") - free.find("[near_end]"), "");
  const Case bare = case_from(free, {"body.pile.shaft.ultimate=0"});
  EXPECT_LT(c.time.step, bare.time.step);
  // The resolved case reads back to the same case, fitted again.
  const Case again = fit_scheme(Case::from_string(c.to_toml(), {}, "resolved")).c;
  EXPECT_EQ(again.to_toml(), c.to_toml());
  EXPECT_EQ(again.time.step, c.time.step);
}

}  // namespace
}  // namespace barimpact
