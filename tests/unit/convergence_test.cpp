#include "barimpact/study/convergence.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

#include "../support/run_case.hpp"

namespace barimpact {
namespace {

TEST(ObservedOrder, RecoversTheOrderOfAManufacturedSequence) {
  // e = C h^p with h halved: log(e_prev/e)/log(2) = p to round-off.
  for (double p : {0.5, 1.0, 2.0, 3.7}) {
    const double e0 = 3.0 * std::pow(0.1, p), e1 = 3.0 * std::pow(0.05, p);
    EXPECT_NEAR(observed_order(e0, e1, 1.0, 2.0), p, 1e-12);
  }
  // In a varied key: e = C k^-1 along k = 100, 400 gives order 1.
  EXPECT_NEAR(observed_order(1.0 / 100, 1.0 / 400, 100, 400), 1.0, 1e-12);
  EXPECT_TRUE(std::isnan(observed_order(0.0, 1.0, 1.0, 2.0)));
  EXPECT_TRUE(std::isnan(observed_order(1.0, NAN, 1.0, 2.0)));
}

TEST(Variation, ParsesListsAndRanges) {
  EXPECT_EQ(Variation::parse("obstacle.stiffness=10,100,1e3").values, (std::vector<std::string>{"10", "100", "1e3"}));
  const auto lin = Variation::parse("time.alpha=0:0.5:3");
  EXPECT_EQ(lin.key, "time.alpha");
  EXPECT_EQ(lin.values, (std::vector<std::string>{"0", "0.25", "0.5"}));
  const auto log = Variation::parse("obstacle.stiffness=log:1e2:1e4:3");
  ASSERT_EQ(log.values.size(), 3u);
  EXPECT_NEAR(std::stod(log.values[1]), 1e3, 1e-9);
  // Issue 36: ends whose difference or ratio overflows still give finite points between them.
  for (const char* range : {"obstacle.gap=-1.7e308:1.7e308:4", "obstacle.stiffness=log:1e-300:1e300:4",
                            "obstacle.stiffness=log:1e300:1e-300:4"}) {
    const auto v = Variation::parse(range);
    ASSERT_EQ(v.values.size(), 4u) << range;
    for (const auto& x : v.values) EXPECT_TRUE(std::isfinite(std::stod(x))) << range << ": " << x;
  }
  for (const char* bad : {"stiffness=1,2", "obstacle.stiffness", "obstacle.stiffness=1", "obstacle.stiffness=log:0:1:3",
                          "obstacle.stiffness=1:2:1", "obstacle.stiffness=1,,2", "obstacle.stiffness=a:b:3"})
    EXPECT_THROW((void)Variation::parse(bad), InputError) << bad;
}

TEST(Converge, MeasuresTheKnownFirstOrderOfCentralDifferencesOnExampleOne) {
  // Lumped central differences at Courant 1 on Example 1 with a rigid
  // obstacle: U lags the exact solution by exactly h after lift-off, so the
  // error halves with h: order 1 to round-off.
  const Case c = testing::example("paper-example1-rigid.toml", {"time.scheme=\"central-difference\""});
  StudyOptions o;
  o.levels = 3;
  const Study s = converge(c, o);
  ASSERT_EQ(s.runs.size(), 3u);
  EXPECT_NE(s.reference.find("exact"), std::string::npos);
  for (std::size_t i = 1; i < 3; ++i) {
    EXPECT_EQ(s.runs[i].status, "complete");
    EXPECT_NEAR(s.runs[i].order_U, 1.0, 1e-9);
    EXPECT_NEAR(s.runs[i].order_R, 1.0, 1e-6);
    EXPECT_EQ(s.runs[i].elements, 100 << i);
    EXPECT_DOUBLE_EQ(s.runs[i].step, 0.01 / (1 << i));
  }
  EXPECT_NEAR(s.runs[0].error_U_max, 0.01, 1e-12);
}

TEST(Converge, ReportsAFailingRunAndGoesOn) {
  // alpha = 0 at dt = 0.1 on h = 0.01 blows up; alpha = 0.25 does not.
  const Case c = testing::example("paper-example1.toml", {"time.step=0.1", "time.end=40"});
  StudyOptions o;
  o.vary = Variation::parse("time.alpha=0,0.25");
  o.refine = Refine::none;
  o.reference = Reference::finest;
  const Study s = converge(c, o);
  ASSERT_EQ(s.runs.size(), 2u);
  EXPECT_EQ(s.runs[0].status, "non-finite");
  EXPECT_NE(s.runs[0].message.find("step"), std::string::npos);
  EXPECT_EQ(s.runs[1].status, "reference");
}

TEST(Converge, MarkdownAndCsvAgree) {
  const Case c = testing::example("paper-example1.toml", {"time.end=2.5", "output.fields_at=[]"});
  StudyOptions o;
  o.levels = 3;
  o.schemes = {"paper", "newmark"};
  o.reference = Reference::rigid;
  const Study s = converge(c, o);
  const std::string csv = study_csv(s), md = study_markdown(s, "barimpact converge ...");
  // Every CSV row's U error and order, printed with 3 and 2 decimals, is in the Markdown.
  std::istringstream lines(csv);
  std::string line;
  std::getline(lines, line);  // header
  int rows = 0;
  for (const auto& r : s.runs) {
    std::getline(lines, line);
    ++rows;
    EXPECT_EQ(line.rfind(r.scheme + "," + std::to_string(r.level) + ",", 0), 0u) << line;
    EXPECT_NE(line.find(fmt::format(",{},", r.error_U_max)), std::string::npos) << line;
    const std::string md_row =
        fmt::format("| {} | {:.4g} | {} | {:.4g} | {:.3e} |", r.level, r.h, r.elements, r.step, r.error_U_max);
    EXPECT_NE(md.find(md_row), std::string::npos) << md_row;
  }
  EXPECT_EQ(rows, 6);
  EXPECT_NE(md.find("**newmark**"), std::string::npos);
  EXPECT_NE(md.find("Reference: exact solution: rigid obstacle"), std::string::npos);
}

TEST(Converge, RefusesBadOptionsBeforeRunning) {
  const Case c = testing::example("paper-example1.toml");
  StudyOptions o;
  o.levels = 1;
  EXPECT_THROW((void)converge(c, o), InputError);
  o.levels = 3;
  o.refine = Refine::none;
  EXPECT_THROW((void)converge(c, o), InputError);
}

// The message of the InputError check_study throws ("" if none).
std::string refusal(const Case& c, const StudyOptions& o) {
  try {
    check_study(c, o);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(Converge, RefusesOptionsOutOfTheirRanges) {
  const Case c = testing::example("paper-example1.toml");
  for (auto [option, set] : std::initializer_list<std::pair<const char*, void (*)(StudyOptions&)>>{
           {"--ratio: must be 2 .. 16 (got 17)", [](StudyOptions& o) { o.ratio = 17; }},
           {"--ratio: must be 2 .. 16 (got 1)", [](StudyOptions& o) { o.ratio = 1; }},
           {"--levels: must be 2 .. 12 (got 13)", [](StudyOptions& o) { o.levels = 13; }},
           {"--levels: must be 2 .. 12 (got 1)", [](StudyOptions& o) { o.levels = 1; }},
           {"--jobs: must be 1 .. 1024, or 0 for all cores (got 1025)", [](StudyOptions& o) { o.jobs = 1025; }},
           {"--jobs: must be 1 .. 1024, or 0 for all cores (got -1)", [](StudyOptions& o) { o.jobs = -1; }},
           {"--vary obstacle.stiffness: must give 2 .. 12 values, one per level (got 13)",
            [](StudyOptions& o) { o.vary = Variation::parse("obstacle.stiffness=1:13:13"); }}}) {
    StudyOptions o;
    set(o);
    EXPECT_EQ(refusal(c, o), option);
  }
  StudyOptions o;
  o.ratio = 16;
  o.levels = 12;
  o.jobs = 1024;
  EXPECT_EQ(refusal(c, o), "");
}

TEST(Converge, ReadsTheCommandsWords) {
  StudyArguments a;
  a.vary = "time.step=0.01,0.005";
  a.schemes = {"paper", "newmark"};
  a.reference = "finest";
  const StudyOptions o = study_options(a);
  EXPECT_EQ(o.refine, Refine::none);  // a variation alone changes only its key
  EXPECT_EQ(o.schemes.size(), 2u);
  EXPECT_EQ(o.reference, Reference::finest);
  a.refine = "h";
  EXPECT_EQ(study_options(a).refine, Refine::h);
  for (auto bad : {&StudyArguments::refine, &StudyArguments::vary}) {
    StudyArguments b;
    b.*bad = "sideways";
    EXPECT_THROW((void)study_options(b), InputError);
  }
  a.schemes = {"euler"};
  EXPECT_THROW((void)study_options(a), InputError);
}

// A study along `vary` alone (--refine none).
StudyOptions varying(const char* vary) {
  StudyOptions o;
  o.vary = Variation::parse(vary);
  o.refine = Refine::none;
  return o;
}

// Three levels, each complete at step 0.01 / 2^level, on 100 elements or,
// if the mesh doubles too, 100 * 2^level.
void expect_three_levels(const Study& s, bool mesh_doubles) {
  ASSERT_EQ(s.runs.size(), 3u);
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(s.runs[i].status, "complete") << s.runs[i].message;
    EXPECT_EQ(s.runs[i].elements, mesh_doubles ? 100 << i : 100);
    EXPECT_DOUBLE_EQ(s.runs[i].step, 0.01 / (1 << i));
  }
}

TEST(Converge, AVariedStepRunsAtEachLevelOnTheSameMesh) {
  // --vary time.step with h fixed: each level steps at its own value (the
  // study's own time.step once came after the variation, and every level
  // ran the case's step: identical rows). Central differences at a falling
  // Courant number on Example 1 with a rigid obstacle.
  const Case c = testing::example("paper-example1-rigid.toml",
                                  {"time.scheme=\"central-difference\"", "time.end=2.5", "output.fields_at=[]"});
  StudyOptions o = varying("time.step=0.01,0.005,0.0025");
  const Study s = converge(c, o);
  expect_three_levels(s, false);
  EXPECT_NE(s.runs[0].error_U_max, s.runs[1].error_U_max);
  // The scale of a varied step is 1/dt, as 1/h's: the order has the sign of log(e_prev / e).
  EXPECT_GT(s.runs[1].order_U * std::log(s.runs[0].error_U_max / s.runs[1].error_U_max), 0.0);
  // With the mesh refined too (--refine h), the step still varies (at Courant 1 here).
  o.refine = Refine::h;
  expect_three_levels(converge(c, o), true);
}

TEST(Converge, AVariedMeshKeepsTheCharacteristicSchemeAtCourantOne) {
  const Case c = testing::example("paper-example1-rigid.toml", {"time.end=2.5", "output.fields_at=[]"});
  const Study s = converge(c, varying("bar.elements=100,200,400"));
  expect_three_levels(s, true);                                  // dt = h/c
  for (const auto& r : s.runs) EXPECT_LT(r.error_U_max, 1e-12);  // exact at the nodes
}

TEST(Converge, RefusesAVariedKeyTheStudySetsItself) {
  const Case cd = testing::example("paper-example1-rigid.toml", {"time.scheme=\"central-difference\""});
  struct Rule {
    const char* vary;
    std::vector<Refine> conflicting;
    Refine fine;
  };
  for (const Rule& rule : {Rule{"time.step=0.01,0.005", {Refine::both, Refine::dt}, Refine::h},
                           Rule{"bar.elements=100,200", {Refine::both, Refine::h}, Refine::dt}}) {
    StudyOptions o = varying(rule.vary);
    EXPECT_EQ(refusal(cd, o), "");
    o.refine = rule.fine;
    EXPECT_EQ(refusal(cd, o), "");
    const std::string key(rule.vary, std::string_view(rule.vary).find('='));
    for (auto r : rule.conflicting) {
      o.refine = r;
      EXPECT_EQ(refusal(cd, o).rfind("--vary " + key + ": --refine ", 0), 0u) << refusal(cd, o);
    }
  }
  StudyOptions o = varying("time.step=0.01,0.005");
  o.schemes = {"central-difference", "characteristic"};
  EXPECT_NE(refusal(cd, o).find("characteristic scheme sets dt = h/c"), std::string::npos) << refusal(cd, o);
}

}  // namespace
}  // namespace barimpact
