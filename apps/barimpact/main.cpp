// barimpact: the command line, thin over the library.
//
//   barimpact run CASE.toml --out DIR [--set section.key=value]...
//   barimpact exact CASE.toml --out DIR [--set ...]   (the exact solution, same files)
//   barimpact plot DIR [--out FIGURES]      (runs the Python package's plots)
//
// Exit status: 0 done, 2 bad input (one line on stderr, nothing written),
// 3 the state became non-finite (rows so far kept, summary.json marks them
// incomplete), 1 anything else.
#include <fmt/format.h>
#include <CLI/CLI.hpp>

#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <new>
#include <string_view>

#include "barimpact/case.hpp"
#include "barimpact/output.hpp"
#include "barimpact/simulate.hpp"

namespace {

constexpr int exit_bad_input = 2;
constexpr int exit_non_finite = 3;

int run_command(const std::string& case_path, const std::string& out_dir, const std::vector<std::string>& sets,
                bool exact) {
  std::vector<barimpact::Case::Override> overrides;
  for (const auto& s : sets) overrides.push_back({s});
  const auto c = barimpact::Case::from_file(case_path, overrides);
  barimpact::RunDirectory dir(out_dir);
  barimpact::RunOptions options;
  bool reported = false;
  if (isatty(STDERR_FILENO)) {
    // A run longer than about two seconds shows where it stands on a terminal.
    options.progress_delay = 2.0;
    options.progress = [&reported](const barimpact::Progress& p) {
      const double rate = static_cast<double>(p.step) / p.elapsed_seconds;
      const double left = rate > 0 ? static_cast<double>(p.steps - p.step) / rate : 0.0;
      fmt::print(stderr, "\r\033[K  step {}/{}  t = {:.4g} of {:.4g}  {:.3g} steps/s  {:.0f} s left", p.step, p.steps,
                 p.t, p.t_end, rate, left);
      std::fflush(stderr);
      reported = true;
      return true;
    };
  }
  const auto result = exact ? barimpact::run_exact(c) : barimpact::run(c, options);
  if (reported) fmt::print(stderr, "\r\033[K");
  dir.commit(c, result);
  if (exact) fmt::print("exact solution: {}\n", result.summary.message);
  fmt::print("{}", barimpact::summary_text(c, result.summary));
  fmt::print("  results in {}\n", dir.target().string());
  if (!result.summary.complete) {
    fmt::print(stderr, "barimpact: {} (results so far kept in {})\n", result.summary.message, dir.target().string());
    return exit_non_finite;
  }
  return 0;
}

// The figures are drawn by the Python package (matplotlib): hand over to it.
int plot_command(const std::string& run_dir, const std::string& figures) {
  std::string path = BARIMPACT_PYTHON_DIR;
  if (const char* old = std::getenv("PYTHONPATH"); old != nullptr && *old != '\0') path += std::string(":") + old;
  setenv("PYTHONPATH", path.c_str(), 1);
  std::vector<std::string> args{BARIMPACT_PYTHON, "-m", "barimpact", "plot", run_dir};
  if (!figures.empty()) {
    args.emplace_back("--out");
    args.push_back(figures);
  }
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  execv(argv[0], argv.data());
  fmt::print(stderr, "barimpact: error: plot: cannot start {} ({})\n", BARIMPACT_PYTHON, std::strerror(errno));
  return exit_bad_input;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"barimpact: a visco-elastic bar hitting obstacles (Do, Raupp & Feijoo 1979)"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "barimpact 0.1.0");

  std::string case_path, out_dir;
  std::vector<std::string> sets;
  auto* run = app.add_subcommand("run", "Run one case and write history.csv, fields.csv, case.toml, summary.json");
  run->add_option("case", case_path, "Case file (TOML)")->required();
  run->add_option("--out", out_dir, "Output directory (replaced when the run completes)")->required();
  run->add_option("--set", sets, "Override a case key: section.key=value (value read as TOML, a bare word as a string)")
      ->take_all()
      ->allow_extra_args(false);

  if (argc > 1 && argv[1][0] != '-' && std::string_view(argv[1]) != "run" && std::string_view(argv[1]) != "plot" &&
      std::string_view(argv[1]) != "exact") {
    fmt::print(stderr, "barimpact: error: unknown command \"{}\" (commands: run, exact, plot; see barimpact --help)\n",
               argv[1]);
    return exit_bad_input;
  }
  std::string exact_case, exact_out;
  std::vector<std::string> exact_sets;
  auto* exact = app.add_subcommand("exact", "Tabulate the exact solution the case admits (same files as run)");
  exact->add_option("case", exact_case, "Case file (TOML)")->required();
  exact->add_option("--out", exact_out, "Output directory (replaced when complete)")->required();
  exact->add_option("--set", exact_sets, "Override a case key: section.key=value")->take_all()->allow_extra_args(false);

  std::string plot_dir, plot_out;
  auto* plot = app.add_subcommand("plot", "Draw the figures of a run directory (PNG and SVG) with matplotlib");
  plot->add_option("dir", plot_dir, "A directory written by barimpact run")->required();
  plot->add_option("--out", plot_out, "Where the figures go (default: DIR/figures)");

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    fmt::print(stderr, "barimpact: error: {} (see barimpact --help)\n", e.what());
    return exit_bad_input;
  }

  try {
    if (run->parsed()) return run_command(case_path, out_dir, sets, false);
    if (exact->parsed()) return run_command(exact_case, exact_out, exact_sets, true);
    if (plot->parsed()) return plot_command(plot_dir, plot_out);
  } catch (const barimpact::InputError& e) {
    fmt::print(stderr, "barimpact: error: {}\n", e.what());
    return exit_bad_input;
  } catch (const std::bad_alloc&) {
    fmt::print(stderr, "barimpact: error: out of memory (reduce bar.elements or raise output.every)\n");
    return 1;
  } catch (const std::exception& e) {
    fmt::print(stderr, "barimpact: internal error: {}\n", e.what());
    return 1;
  }
  return 0;
}
