// barimpact: the command line, thin over the library.
//
//   barimpact run CASE.toml --out DIR [--set section.key=value]...
//
// Exit status: 0 done, 2 bad input (one line on stderr, nothing written),
// 3 the state became non-finite (rows so far kept, summary.json marks them
// incomplete), 1 anything else.
#include <fmt/format.h>
#include <CLI/CLI.hpp>

#include <cstdio>
#include <new>
#include <string_view>

#include "barimpact/case.hpp"
#include "barimpact/output.hpp"
#include "barimpact/simulate.hpp"

namespace {

constexpr int exit_bad_input = 2;
constexpr int exit_non_finite = 3;

int run_command(const std::string& case_path, const std::string& out_dir, const std::vector<std::string>& sets) {
  std::vector<barimpact::Case::Override> overrides;
  for (const auto& s : sets) overrides.push_back({s});
  const auto c = barimpact::Case::from_file(case_path, overrides);
  barimpact::RunDirectory dir(out_dir);
  const auto result = barimpact::run(c);
  dir.commit(c, result);
  fmt::print("{}", barimpact::summary_text(c, result.summary));
  fmt::print("  results in {}\n", dir.target().string());
  if (!result.summary.complete) {
    fmt::print(stderr, "barimpact: {} (results so far kept in {})\n", result.summary.message, dir.target().string());
    return exit_non_finite;
  }
  return 0;
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

  if (argc > 1 && argv[1][0] != '-' && std::string_view(argv[1]) != "run") {
    fmt::print(stderr, "barimpact: error: unknown command \"{}\" (commands: run; see barimpact --help)\n", argv[1]);
    return exit_bad_input;
  }
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
    if (run->parsed()) return run_command(case_path, out_dir, sets);
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
