// Today's results, pinned: every example under every scheme that fits it,
// with viscosity and a viscoelastic obstacle where the scheme takes them.
// Sampled history rows (about 20 per run and the last) must come out bit
// for bit as recorded in pinned.txt: a restructuring of the code keeps the
// arithmetic, so any change is a change of results, to be explained.
//
// To record anew after a change of results that is meant (say why in the
// commit): BARIMPACT_PIN_WRITE=tests/regression/pinned.txt (the single-bar
// rows) or BARIMPACT_PIN_LINE_WRITE=tests/regression/pinned_line.txt (the
// line engine's) barimpact_tests --gtest_filter='Pinned.*'
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "../support/run_case.hpp"
#include "barimpact/schemes/line_scheme.hpp"
#include "barimpact/schemes/registry.hpp"

namespace barimpact {
namespace {

struct PinnedRun {
  std::string name;
  std::string example;
  std::vector<std::string> sets;
};

std::vector<PinnedRun> pinned_runs() {
  const std::vector<std::string> penalty{"paper", "newmark", "central-difference"};
  const std::vector<std::string> rigid{"central-difference", "paoli-schatzman", "moreau-jean", "mass-redistribution",
                                       "characteristic"};
  std::vector<PinnedRun> runs;
  auto add = [&](const std::string& example, const std::string& scheme, std::vector<std::string> extra,
                 const std::string& tag) {
    std::vector<std::string> sets{"time.scheme=\"" + scheme + "\"", "output.fields_at=[]"};
    // The explicit schemes at a step within their limit (the CLI test's).
    if (scheme == "central-difference" || scheme == "paoli-schatzman") sets.push_back("time.step=0.002");
    sets.insert(sets.end(), extra.begin(), extra.end());
    try {
      (void)testing::example(example, sets);
    } catch (const InputError&) {
      return;  // refused (characteristic under a body force): nothing to pin
    }
    runs.push_back({example + "/" + scheme + tag, example, sets});
  };
  for (const auto& s : penalty) {
    add("paper-example1.toml", s, {}, "");
    add("paper-example2.toml", s, {}, "");
    add("paper-example1.toml", s, {"bar.viscosity=0.01", "obstacle.kind=\"viscoelastic\"", "obstacle.viscosity=2"},
        "+viscous");
  }
  add("paper-example1.toml", "paper", {"time.lambda=0.25", "time.alpha=0.3"}, "+shift");
  for (const auto& s : rigid) {
    add("paper-example1-rigid.toml", s, {}, "");
    add("paper-example2-rigid.toml", s, {}, "");
    add("clamped-periodic.toml", s, {}, "");
  }
  return runs;
}

// "name t U V R E_kin E_strain E_obstacle W_ext D_visc" lines, shortest exact form.
std::vector<std::string> sample(const PinnedRun& p) {
  const auto r = run(testing::example(p.example, p.sets));
  const auto& h = r.history;
  const std::size_t stride = std::max<std::size_t>(1, h.size() / 20);
  std::vector<std::string> lines;
  for (std::size_t i = 0; i < h.size(); ++i)
    if (i % stride == 0 || i + 1 == h.size())
      lines.push_back(fmt::format("{} {} {} {} {} {} {} {} {} {}", p.name, h[i].t, h[i].U, h[i].V, h[i].R, h[i].E_kin,
                                  h[i].E_strain, h[i].E_obstacle, h[i].W_ext, h[i].D_visc));
  return lines;
}

// The line engine, pinned on its own: every example (the paper's one-bar
// cases forced through the line engine, the lines, the elastic-plastic bars,
// the piles and the Hopkinson bar) under every scheme that takes it, at the
// example's own step or, for the explicit schemes, at 0.9 of the limit
// the line engine computes. Every history column is pinned, the links',
// masses' and gauges' included.
struct LineRun {
  std::string name;
  Case c;
};

// The example under `sets`; an implicit scheme on an example whose step is
// "auto" (the explicit schemes' word) at central differences' step.
Case read_pinned(const std::string& example, std::vector<std::string> sets) {
  try {
    return testing::example(example, sets);
  } catch (const InputError&) {
    const Case explicit_case = testing::example(example, {"time.scheme=\"central-difference\""});
    if (!explicit_case.time.step_auto) throw;
    sets.push_back(fmt::format("time.step={}", explicit_case.time.step));
    return testing::example(example, sets);
  }
}

std::vector<LineRun> line_runs() {
  const std::vector<std::string> examples{
      "paper-example1.toml",       "paper-example2.toml",     "paper-example1-rigid.toml",
      "paper-example2-rigid.toml", "clamped-periodic.toml",   "steel-bar.toml",
      "lines/drop-mass.toml",      "lines/hopkinson.toml",    "lines/pile-hammer.toml",
      "lines/saint-venant.toml",   "plastic/cyclic.toml",     "plastic/paper-example1-yielding.toml",
      "plastic/pipe-whip.toml",    "plastic/taylor-bar.toml", "plastic/von-karman.toml",
      "pile/concrete-clay.toml",   "pile/hammer-impact.toml", "pile/steel-pipe-sand.toml",
      "hopkinson/shpb.toml"};
  std::vector<LineRun> runs;
  for (const auto& example : examples)
    for (const auto scheme : scheme_names) {
      const std::string s(scheme);
      std::vector<std::string> sets{"time.scheme=\"" + s + "\"", "output.fields_at=[]"};
      if (s == "central-difference" || s == "paoli-schatzman") sets.push_back("time.step=\"auto\"");
      if (s == "characteristic") sets.push_back("time.step=\"auto\"");
      try {
        Case c = read_pinned(example, sets);
        // At most 4,000 steps each: the pin guards the arithmetic, not the physics.
        if (c.step_count() > 4000) c.time.end = 4000 * c.time.step;
        (void)make_scheme(c);
        runs.push_back({"line:" + example + "/" + s, std::move(c)});
      } catch (const InputError&) {
        // The scheme does not take this example: nothing to pin.
      }
    }
  return runs;
}

// "name t U V R E_kin E_strain E_obstacle W_ext D_visc D_contact D_plastic extra...".
std::vector<std::string> sample(const LineRun& p) {
  const auto r = testing::run_line_engine(p.c);  // the paper's one-bar cases too, not its fused kernel
  const auto& h = r.history;
  const std::size_t stride = std::max<std::size_t>(1, h.size() / 20), width = r.columns.size();
  std::vector<std::string> lines;
  for (std::size_t i = 0; i < h.size(); ++i)
    if (i % stride == 0 || i + 1 == h.size()) {
      std::string line =
          fmt::format("{} {} {} {} {} {} {} {} {} {} {} {}", p.name, h[i].t, h[i].U, h[i].V, h[i].R, h[i].E_kin,
                      h[i].E_strain, h[i].E_obstacle, h[i].W_ext, h[i].D_visc, h[i].D_contact, h[i].D_plastic);
      for (std::size_t k = 0; k < width; ++k) line += fmt::format(" {}", r.extra[i * width + k]);
      lines.push_back(line);
    }
  return lines;
}

// Compares each run's samples with the file's (or records them, when the
// environment variable `record` names a file).
template <class Run>
void expect_pinned(const std::string& file_name, const char* record, const std::vector<Run>& runs) {
  const std::string path = std::string(BARIMPACT_SOURCE_DIR) + "/tests/regression/" + file_name;
  if (const char* out = std::getenv(record)) {
    std::ofstream file(out);
    for (const auto& p : runs)
      for (const auto& line : sample(p)) file << line << '\n';
    GTEST_SKIP() << "recorded into " << out;
  }
  std::ifstream file(path);
  ASSERT_TRUE(file) << path;
  std::map<std::string, std::vector<std::string>> recorded;
  for (std::string line; std::getline(file, line);) recorded[line.substr(0, line.find(' '))].push_back(line);
  EXPECT_EQ(recorded.size(), runs.size()) << "runs pinned against runs made";
  for (const auto& p : runs) {
    ASSERT_TRUE(recorded.count(p.name)) << p.name << " is not in " << path;
    EXPECT_EQ(sample(p), recorded[p.name]) << p.name;
  }
}

TEST(Pinned, EveryExampleThroughTheLineEngineGivesTodaysBits) {
  expect_pinned("pinned_line.txt", "BARIMPACT_PIN_LINE_WRITE", line_runs());
}

TEST(Pinned, EveryExampleUnderEverySchemeGivesTodaysBits) {
  expect_pinned("pinned.txt", "BARIMPACT_PIN_WRITE", pinned_runs());
}

}  // namespace
}  // namespace barimpact
