// barimpact: the command line, thin over the library.
//
//   barimpact run CASE.toml --out DIR [--set section.key=value]...
//   barimpact exact CASE.toml --out DIR [--set ...]   (the exact solution, same files)
//   barimpact plot DIR [--out FIGURES]      (runs the Python package's plots)
//   barimpact converge CASE.toml --out DIR [--levels N] [--refine both|h|dt|none] [--ratio R]
//                      [--vary key=spec] [--schemes a,b] [--reference auto|rigid|finest] [--jobs N]
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

#include <sys/wait.h>

#include <filesystem>
#include <sstream>

#include "barimpact/case.hpp"
#include "barimpact/convergence.hpp"
#include "barimpact/output.hpp"
#include "barimpact/scheme.hpp"
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

// Runs the Python package (figures) as a child; false if it is not there or fails.
bool run_python(std::vector<std::string> args) {
  if (!std::filesystem::exists(std::filesystem::path(BARIMPACT_PYTHON_DIR) / "barimpact" / "__init__.py")) return false;
  std::string path = BARIMPACT_PYTHON_DIR;
  if (const char* old = std::getenv("PYTHONPATH"); old != nullptr && *old != '\0') path += std::string(":") + old;
  args.insert(args.begin(), {BARIMPACT_PYTHON, "-m", "barimpact"});
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  std::fflush(stdout);
  const pid_t pid = fork();
  if (pid == 0) {
    setenv("PYTHONPATH", path.c_str(), 1);
    execv(argv[0], argv.data());
    _exit(127);
  }
  int status = 0;
  return pid > 0 && waitpid(pid, &status, 0) == pid && WIFEXITED(status) && WEXITSTATUS(status) == 0;
}

struct ConvergeArgs {
  std::string case_path, out, refine, vary, schemes, reference = "auto";
  std::vector<std::string> sets;
  barimpact::StudyOptions options;
  bool refine_given = false;
  std::string command;
};

int converge_command(ConvergeArgs& a) {
  std::vector<barimpact::Case::Override> overrides;
  for (const auto& s : a.sets) overrides.push_back({s});
  const auto c = barimpact::Case::from_file(a.case_path, overrides);
  auto& o = a.options;
  if (a.refine_given) {
    o.refine = a.refine == "h"      ? barimpact::Refine::h
               : a.refine == "dt"   ? barimpact::Refine::dt
               : a.refine == "none" ? barimpact::Refine::none
                                    : barimpact::Refine::both;
  }
  if (!a.vary.empty()) {
    o.vary = barimpact::Variation::parse(a.vary);
    if (!a.refine_given) o.refine = barimpact::Refine::none;
  }
  if (!a.schemes.empty()) {
    std::stringstream list(a.schemes);
    const auto known = barimpact::scheme_names();
    for (std::string s; std::getline(list, s, ',');) {
      if (std::find(known.begin(), known.end(), s) == known.end())
        throw barimpact::InputError(
            fmt::format("--schemes: unknown scheme \"{}\" (known: {})", s, fmt::join(known, ", ")));
      o.schemes.push_back(s);
    }
  }
  o.reference = a.reference == "rigid"    ? barimpact::Reference::rigid
                : a.reference == "finest" ? barimpact::Reference::finest
                                          : barimpact::Reference::automatic;
  barimpact::RunDirectory dir(a.out);
  const auto study = barimpact::converge(c, o);
  const std::string markdown = barimpact::study_markdown(study, a.command);
  bool plotted = false;
  dir.commit([&](const std::filesystem::path& staging) {
    barimpact::write_text(staging / "convergence.csv", barimpact::study_csv(study));
    barimpact::write_text(staging / "convergence.md", markdown);
    plotted = run_python({"converge-plot", staging.string()});
  });
  fmt::print("{}\n", markdown);
  fmt::print("results in {}{}\n", dir.target().string(), plotted ? " (with convergence and work-precision plots)" : "");
  if (!plotted) fmt::print(stderr, "barimpact: note: plots skipped (the Python module is not built here)\n");
  const auto failed = std::count_if(study.runs.begin(), study.runs.end(),
                                    [](const auto& r) { return r.status != "complete" && r.status != "reference"; });
  if (failed > 0)
    fmt::print(stderr, "barimpact: {} of {} runs did not complete; see their rows\n", failed, study.runs.size());
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

  const std::vector<std::string_view> commands{"run", "exact", "converge", "plot"};
  if (argc > 1 && argv[1][0] != '-' && std::find(commands.begin(), commands.end(), argv[1]) == commands.end()) {
    fmt::print(
        stderr,
        "barimpact: error: unknown command \"{}\" (commands: run, exact, converge, plot; see barimpact --help)\n",
        argv[1]);
    return exit_bad_input;
  }
  std::string exact_case, exact_out;
  std::vector<std::string> exact_sets;
  auto* exact = app.add_subcommand("exact", "Tabulate the exact solution the case admits (same files as run)");
  exact->add_option("case", exact_case, "Case file (TOML)")->required();
  exact->add_option("--out", exact_out, "Output directory (replaced when complete)")->required();
  exact->add_option("--set", exact_sets, "Override a case key: section.key=value")->take_all()->allow_extra_args(false);

  ConvergeArgs conv_args;
  auto* conv =
      app.add_subcommand("converge", "Convergence and work-precision study of a case (convergence.csv/.md, plots)");
  conv->add_option("case", conv_args.case_path, "Case file (TOML)")->required();
  conv->add_option("--out", conv_args.out, "Output directory (replaced when complete)")->required();
  conv->add_option("--set", conv_args.sets, "Override a case key: section.key=value")
      ->take_all()
      ->allow_extra_args(false);
  conv->add_option("--levels", conv_args.options.levels, "Refinement levels (default 4)")->check(CLI::Range(2, 12));
  conv->add_option("--refine", conv_args.refine, "both (h and dt together, default), h, dt, or none")
      ->check(CLI::IsMember({"both", "h", "dt", "none"}));
  conv->add_option("--ratio", conv_args.options.ratio, "Refinement ratio per level (default 2)")
      ->check(CLI::Range(2, 16));
  conv->add_option("--vary", conv_args.vary, "A key along the levels: key=v1,v2,... | key=a:b:n | key=log:a:b:n");
  conv->add_option("--schemes", conv_args.schemes, "Compare schemes: a,b,c (default: the case's)");
  conv->add_option("--reference", conv_args.reference,
                   "auto (exact if the case admits one, else finest), rigid, finest")
      ->check(CLI::IsMember({"auto", "rigid", "finest"}));
  conv->add_option("--jobs", conv_args.options.jobs, "Threads (default: all cores)")->check(CLI::Range(1, 1024));

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
    if (conv->parsed()) {
      conv_args.refine_given = conv->count("--refine") > 0;
      conv_args.command = "barimpact";
      for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        conv_args.command += " " + (arg.find_first_of(" *;()") == std::string::npos ? arg : "'" + arg + "'");
      }
      return converge_command(conv_args);
    }
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
