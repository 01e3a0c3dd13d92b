// Convergence and work-precision studies: a sequence of runs of one case,
// refined in h and/or dt, or along a case key (k -> infinity), for one or
// several schemes, each measured against a reference: the exact solution
// the case admits (exact.hpp), the rigid obstacle's exact solution, or the
// finest run. The runs are independent and go to a pool of threads; a run
// that fails is recorded in its row, not fatal. With a runs directory, each
// run is kept there as it finishes (the files of `barimpact run`) and a
// rerun reads back the runs it finds for the same case instead of running
// them again: an interrupted study, rerun, ends as an uninterrupted one.
#pragma once

#include <atomic>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "barimpact/case/case.hpp"

namespace barimpact {

enum class Refine { both, h, dt, none };
enum class Reference { automatic, rigid, finest };

/// A case key and the values it takes along the study.
struct Variation {
  std::string key;                  ///< section.key
  std::vector<std::string> values;  ///< TOML values as written
  /// "key=v1,v2,..." or "key=a:b:n" (linear) or "key=log:a:b:n". Throws InputError.
  static Variation parse(const std::string& text);
};

struct StudyOptions {
  int levels = 4;  ///< with refinement and no variation
  Refine refine = Refine::both;
  int ratio = 2;                     ///< h and/or dt divided by ratio per level
  std::optional<Variation> vary;     ///< the levels are its values
  std::vector<std::string> schemes;  ///< empty: the case's scheme
  Reference reference = Reference::automatic;
  int jobs = 0;  ///< threads; 0: all cores
  /// Where each run is kept as runs/<scheme>-<level>/ (and read back from
  /// on a rerun); empty: nowhere.
  std::filesystem::path runs;
  /// When it becomes true, runs under way end after their step and are not
  /// kept, runs not begun are not run; their rows say "interrupted".
  const std::atomic<bool>* interrupt = nullptr;
};

/// One run of the study and what it measured.
struct StudyRun {
  std::string id;  ///< <scheme>-<level>: its directory under StudyOptions::runs
  std::string scheme;
  int level = 0;
  std::string value;  ///< the varied key's value (empty without variation)
  int elements = 0;
  double h = 0.0;
  double step = 0.0;
  std::string status;                 ///< complete, reference, non-finite, refused, interrupted
  std::vector<std::string> warnings;  ///< the run's health checks (health.hpp)
  std::string message;
  double error_U_max = 0.0;       ///< max_n |U - U_ref|
  double error_R_l1 = 0.0;        ///< sum_n |R - R_ref| dt
  double energy_error_end = 0.0;  ///< |E_total(end) - E_total(0)| / |E_total(0)|
  double first_contact = 0.0;     ///< start of the first contact episode (NaN: none)
  double lift_off = 0.0;          ///< end of the episode the body left from (observer.hpp's departure; NaN: none)
  int contact_episodes = 0;
  double cpu_seconds = 0.0;
  double order_U = 0.0;  ///< observed order against the previous level (NaN on level 0)
  double order_R = 0.0;
};

struct Study {
  std::string reference;  ///< what the errors are measured against, in words
  std::string abscissa;   ///< "h" or the varied key
  std::vector<StudyRun> runs;
};

/// The options as the command and the Python module take them, in words
/// (`barimpact converge`'s --levels, --ratio, ...): study_options reads them.
struct StudyArguments {
  int levels = 4;
  int ratio = 2;
  int jobs = 0;                       ///< 0: all cores
  std::optional<std::string> refine;  ///< both, h, dt, none; unset: both, or none with a variation
  std::optional<std::string> vary;    ///< key=v1,v2,... | key=a:b:n | key=log:a:b:n
  std::vector<std::string> schemes;   ///< names of scheme_names(); empty: the case's
  std::string reference = "auto";     ///< auto, rigid, finest
};

/// Reads the arguments into StudyOptions; throws InputError naming the
/// option (--refine, --vary, --schemes, --reference). Their ranges and how
/// they fit the case are check_study's.
[[nodiscard]] StudyOptions study_options(const StudyArguments& arguments);

/// Checks the options against the case; throws InputError naming the
/// option: --levels 2 .. 12 (a variation's values too), --ratio 2 .. 16,
/// --jobs (check_jobs), a level to change, a varied key the case has and the
/// study does not set itself (time.step under --refine both or dt, a bar's
/// elements under --refine both or h, time.step for the characteristic
/// scheme, which sets dt = h/c), a rigid reference the case admits.
void check_study(const Case& base, const StudyOptions& options);

/// Runs the study. Throws InputError for bad options (check_study), before any run.
/// Errors and orders are measured on complete runs only (NaN elsewhere).
/// With `options.runs`, a run's results the file system refuses (a full
/// disk) end the study: OutputError, once the runs under way are done.
[[nodiscard]] Study converge(const Case& base, const StudyOptions& options);

/// log(e_prev / e) / log(s / s_prev): the observed order between two levels
/// whose scale (1/h, or the varied value) went from s_prev to s. NaN when an
/// error is zero or not finite.
[[nodiscard]] double observed_order(double e_prev, double e, double s_prev, double s);

[[nodiscard]] std::string study_csv(const Study& study);
/// A Markdown table a person can paste into a paper; `command` is printed above it.
[[nodiscard]] std::string study_markdown(const Study& study, const std::string& command);

/// What `barimpact converge --out DIR` writes into DIR (its marker lists them).
[[nodiscard]] const std::vector<std::string>& convergence_entries();

/// All of `barimpact converge --out dir` but its figures: checks the options
/// (a refusal writes nothing), prepares `dir` by the output rule (new, empty
/// or a study's; `force` as --force), runs or resumes the study with its runs
/// kept in dir/runs/ (options.runs is set so), removes the runs barimpact
/// wrote there for an earlier, other study (a run of the user's stays), and
/// writes convergence.csv and convergence.md (`command` above its table).
[[nodiscard]] Study write_convergence(const Case& base, StudyOptions options, const std::filesystem::path& dir,
                                      bool force, const std::string& command);

}  // namespace barimpact
