// barimpact: the command line, thin over the library.
//
//   barimpact run CASE.toml --out DIR [--set section.key=value]...
//   barimpact exact CASE.toml --out DIR [--set ...]   (the exact solution, same files)
//   barimpact plot DIR [--out FIGURES]      (runs the Python package's plots)
//   barimpact sweep SWEEP.toml --out DIR [--jobs N] [--no-batch] [--ranks P]   (also under mpirun -n P)
//   barimpact bearing CASE.toml --out DIR --capacity FROM:TO:COUNT [--toe-share S] [--set K=V ...] [--jobs N]
//   barimpact drive CASE.toml --out DIR [--set K=V ...] [--jobs N] [--no-plot]
//   barimpact inspector CASE.toml --out DIR --stroke FROM:TO:COUNT [--depth D] [--set K=V ...] [--no-plot]
//   barimpact hammers
//   [--no-plot] barimpact converge CASE.toml --out DIR [--levels N] [--refine both|h|dt|none] [--ratio R]
//                      [--vary key=spec] [--schemes a,b] [--reference auto|rigid|finest] [--jobs N]
//
// Exit status: 0 done, 2 bad input or results the file system refused (a
// full disk; one line on stderr, nothing half-written left),
// 3 the state became non-finite (rows so far kept, summary.json marks them
// incomplete; for converge and sweep: no run produced a result), 4 warnings
// under --strict (results written), 130 / 143 interrupted by SIGINT / SIGTERM
// (results so far written), 1 anything else.
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <CLI/CLI.hpp>

#include <unistd.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <new>
#include <optional>
#include <string_view>
#include <system_error>

#include <fcntl.h>
#include <sys/prctl.h>
#include <sys/wait.h>

#include <chrono>
#include <exception>
#include <filesystem>
#include <functional>
#include <memory>
#include <mutex>
#include <sstream>
#include <thread>

#include "barimpact/case/case.hpp"
#include "barimpact/case/units.hpp"
#include "barimpact/hopkinson/analysis.hpp"
#include "barimpact/pda/case_method.hpp"
#include "barimpact/run/check.hpp"
#include "barimpact/run/figure_names.hpp"
#include "barimpact/run/output.hpp"
#include "barimpact/run/output_directory.hpp"
#include "barimpact/study/bearing.hpp"
#include "barimpact/study/convergence.hpp"
#include "barimpact/study/drive.hpp"
#include "barimpact/study/executor.hpp"
#include "barimpact/study/match.hpp"
#include "barimpact/study/sweep.hpp"

#ifdef BARIMPACT_HAVE_MPI
#include <mpi.h>
#endif
#include "barimpact/exact/tabulate.hpp"
#include "barimpact/model/setup_polling.hpp"
#include "barimpact/run/simulate.hpp"
#include "barimpact/schemes/simd.hpp"
#include "barimpact/study/paper_batch.hpp"
#include "huge_heap.hpp"

namespace {

constexpr int exit_bad_input = 2;
constexpr int exit_non_finite = 3;
constexpr int exit_warnings = 4;

// SIGINT and SIGTERM end the step under way once the work that polls for
// them has begun (a run's time loop, a study's cases): the command then
// writes what it has and exits 128 + the signal's number (it is not killed
// by it). Before that (reading, building the line, factoring, check), which
// writes nothing and does not poll, the handler ends the process at once
// with the same status: within a second whatever the case's size.
std::atomic<bool> interrupted{false};
std::atomic<bool> polling{false};
volatile std::sig_atomic_t received_signal = 0;
static_assert(std::atomic<bool>::is_always_lock_free, "set and read from a signal handler");

extern "C" void on_signal(int signal) {
  received_signal = signal;
  interrupted.store(true);
  if (!polling.load()) _exit(128 + signal);  // async-signal-safe; nothing to write yet
}

void install_signal_handlers() {
  struct sigaction action {};
  action.sa_handler = on_signal;
  sigemptyset(&action.sa_mask);
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
}

// From here a signal is polled for: the work under way ends, then what is
// done is written.
void poll_signals() {
  polling.store(true);
}

int exit_interrupted() {
  return 128 + static_cast<int>(received_signal);
}

// --force and --strict, as every command that writes results takes them.
struct WriteFlags {
  bool force = false;
  bool strict = false;
};

void add_write_flags(CLI::App* command, WriteFlags& flags) {
  command->add_flag("--force", flags.force,
                    "Write into a directory that holds other files (or the working directory): barimpact's files "
                    "go beside them, nothing else is touched; never the home directory, / or a parent of the "
                    "working directory");
  command->add_flag("--strict", flags.strict, "Exit 4 when the run's health checks give any warning");
}

void print_warnings(const std::vector<std::string>& warnings, const std::string& prefix = "") {
  for (const auto& w : warnings) fmt::print(stderr, "barimpact: warning: {}{}\n", prefix, w);
}

// A study's warnings, one line each with the run's id, the first 20 of them
// (a large sweep would bury the terminal); the CSV's warnings column has all.
template <class Rows>
void print_study_warnings(const Rows& rows) {
  constexpr std::size_t shown = 20;
  std::size_t printed = 0;
  for (const auto& r : rows)
    for (const auto& w : r.warnings)
      if (printed++ < shown) fmt::print(stderr, "barimpact: warning: {}: {}\n", r.id, w);
  if (printed > shown) fmt::print(stderr, "barimpact: warning: ... {} more\n", printed - shown);
}

// The case read and fitted to its scheme, refused beyond the memory before
// fitting builds its line (its snapshots streamed, as run writes them).
barimpact::FittedCase read_case(const std::string& case_path, const std::vector<std::string>& sets) {
  std::vector<barimpact::Case::Override> overrides;
  for (const auto& s : sets) overrides.push_back({s});
  auto read = barimpact::Case::from_file(case_path, overrides);
  (void)barimpact::check_resources(read, true);
  return barimpact::fit_scheme(std::move(read));
}

int run_command(const std::string& case_path, const std::string& out_dir, const std::vector<std::string>& sets,
                bool exact, const WriteFlags& flags) {
  auto fitted = read_case(case_path, sets);
  const barimpact::Case c = fitted.c;  // what the results are of: time.step as the scheme fitted it
  const std::string too_large = barimpact::check_resources(c, true);
  const barimpact::CommandInputs inputs{{c.source}, {}};
  // The output rule before any work; the staging directory only once the
  // scheme is made (a signal while it is made leaves nothing behind).
  (void)barimpact::check_output_directory(out_dir, flags.force, "--out", inputs);
  const bool repeated = !exact && barimpact::repeats_blows(c);  // several blows: run() makes each its scheme
  std::unique_ptr<barimpact::Scheme> scheme;
  if (!exact && !repeated) scheme = barimpact::make_scheme(fitted);
  barimpact::RunDirectory dir(out_dir, flags.force, exact ? "exact" : "run", true, inputs);
  dir.expect(barimpact::run_outputs(c));  // a clash refused now, not after the run
  barimpact::RunOptions options;
  options.interrupt = &interrupted;
  options.loop_begins = poll_signals;
  if (!repeated) options.fields = &dir.stream_fields(c);  // else the last blow's, held
  if (!too_large.empty()) print_warnings({too_large});
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
  const auto result = exact      ? barimpact::run_exact(c, options)
                      : repeated ? barimpact::run(std::move(fitted), options)
                                 : barimpact::run_scheme(c, *scheme, c.step_count(), options);
  if (reported) fmt::print(stderr, "\r\033[K");
  dir.commit(c, result);
  if (exact) fmt::print("exact solution: {}\n", result.summary.message);
  fmt::print("{}", barimpact::summary_text(c, result.summary));
  fmt::print("  results in {}\n", dir.target().string());
  print_warnings(result.summary.warnings);
  if (result.summary.status == barimpact::RunStatus::interrupted) {
    fmt::print(stderr, "barimpact: {} (results so far kept in {})\n", result.summary.message, dir.target().string());
    return exit_interrupted();
  }
  if (!result.summary.complete) {
    fmt::print(stderr, "barimpact: {} (results so far kept in {})\n", result.summary.message, dir.target().string());
    return exit_non_finite;
  }
  if (interrupted.load()) return exit_interrupted();  // after the last step: the results are whole, and written
  if (flags.strict && !result.summary.warnings.empty()) return exit_warnings;
  return 0;
}

// The directory holding the Python package (figures), found beside this
// executable: python/ in a build tree, BARIMPACT_PYTHON_FROM_BIN once
// installed (a prefix, or a virtual environment's bin/). Empty if neither.
std::filesystem::path python_package_dir() {
  std::error_code ec;
  const auto exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (ec) return {};
  // Debian's pip names the same place dist-packages (and puts bin/ under <prefix>/local).
  std::string dist = BARIMPACT_PYTHON_FROM_BIN;
  if (const auto at = dist.rfind("site-packages"); at != std::string::npos) dist.replace(at, 13, "dist-packages");
  for (const auto& dir :
       {exe.parent_path() / "python", exe.parent_path() / BARIMPACT_PYTHON_FROM_BIN, exe.parent_path() / dist})
    if (std::filesystem::is_regular_file(dir / "barimpact" / "__init__.py", ec)) return dir.lexically_normal();
  return {};
}

// The interpreter for the figures: a virtual environment's own when the
// command was installed into one (its packages and the system's), else the
// one it was built for, else Debian's.
std::string python_interpreter() {
  std::error_code ec;
  const auto bin = std::filesystem::read_symlink("/proc/self/exe", ec).parent_path();
  if (!ec && std::filesystem::exists(bin.parent_path() / "pyvenv.cfg", ec) &&
      std::filesystem::exists(bin / "python3", ec))
    return (bin / "python3").string();
  if (std::filesystem::exists(BARIMPACT_PYTHON, ec)) return BARIMPACT_PYTHON;
  return "/usr/bin/python3";
}

// PYTHONPATH for the child: the package's directory first.
std::string python_path() {
  std::string path = python_package_dir().string();
  if (const char* old = std::getenv("PYTHONPATH"); old != nullptr && *old != '\0')
    path += (path.empty() ? "" : ":") + std::string(old);
  return path;
}

// A failure the figures' child has already reported in its one line: the
// command ends with its exit status, adding nothing.
struct Reported {
  int status;
};

// Runs the Python package (figures) as a child; false if it is not there or
// fails. Its own refusal (exit 2: the disk refused a figure, which it names)
// ends the command with exit 2 (Reported); a figure it could not write whole
// is not left behind.
bool run_python(std::vector<std::string> args) {
  if (python_package_dir().empty()) return false;
  const std::string path = python_path();
  args.insert(args.begin(), {python_interpreter(), "-m", "barimpact"});
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
  if (pid <= 0 || waitpid(pid, &status, 0) != pid || !WIFEXITED(status)) return false;
  if (WEXITSTATUS(status) == exit_bad_input) throw Reported{exit_bad_input};
  return WEXITSTATUS(status) == 0;
}

// How a study (converge, sweep) of many runs ended, and its exit status:
// interrupted first (a rerun finishes it), then no result at all (3), then
// warnings under --strict (4).
struct StudyEnd {
  const char* runs;    // "runs" or "cases"
  const char* report;  // the file whose rows say more
  std::size_t total;
  long results, stopped, warned;
};

int study_exit(const StudyEnd& e, const WriteFlags& flags) {
  if (interrupted.load() && e.stopped == 0) return exit_interrupted();  // after the last run: all written
  if (e.warned > 0)
    fmt::print(stderr, "barimpact: warning: {} of {} {} have warnings (the warnings column of {})\n", e.warned, e.total,
               e.runs, e.report);
  if (e.stopped > 0) {
    fmt::print(stderr, "barimpact: interrupted: {} {} not done; rerun the same command to finish them\n", e.stopped,
               e.runs);
    return exit_interrupted();
  }
  if (e.results == 0) {
    fmt::print(stderr, "barimpact: no {} produced a result; see the status and message columns of {}\n",
               e.runs == std::string_view("runs") ? "run" : "case", e.report);
    return exit_non_finite;
  }
  return flags.strict && e.warned > 0 ? exit_warnings : 0;
}

struct ConvergeArgs {
  std::string case_path, out, schemes;
  std::vector<std::string> sets;
  barimpact::StudyArguments arguments;
  std::string command;
  WriteFlags flags;
};

int converge_command(ConvergeArgs& a) {
  std::vector<barimpact::Case::Override> overrides;
  for (const auto& s : a.sets) overrides.push_back({s});
  const auto c = barimpact::fit_scheme(barimpact::Case::from_file(a.case_path, overrides)).c;
  std::stringstream list(a.schemes);
  for (std::string s; std::getline(list, s, ',');) a.arguments.schemes.push_back(s);
  auto o = barimpact::study_options(a.arguments);
  o.interrupt = &interrupted;
  const std::filesystem::path dir(a.out);
  poll_signals();  // between runs and in their time loops
  const auto study = barimpact::write_convergence(c, o, dir, a.flags.force, a.command);
  fmt::print("{}\n", barimpact::study_markdown(study, a.command));
  auto count = [&](auto&& pred) { return std::count_if(study.runs.begin(), study.runs.end(), pred); };
  const auto stopped = count([](const auto& r) { return r.status == "interrupted"; });
  const auto results = count([](const auto& r) { return r.status == "complete" || r.status == "reference"; });
  const auto warned = count([](const auto& r) { return !r.warnings.empty(); });
  const bool plotted = stopped == 0 && results > 0 && run_python({"converge-plot", dir.string()});
  fmt::print("results in {}{}\n", dir.string(), plotted ? " (with convergence and work-precision plots)" : "");
  if (stopped == 0 && results > 0 && !plotted && !interrupted.load())
    fmt::print(stderr, "barimpact: note: plots skipped (the Python module is not built here)\n");
  if (results < static_cast<long>(study.runs.size()) && stopped == 0)
    fmt::print(stderr, "barimpact: {} of {} runs did not complete; see their rows\n",
               static_cast<long>(study.runs.size()) - results, study.runs.size());
  print_study_warnings(study.runs);
  return study_exit({"runs", "convergence.csv", study.runs.size(), results, stopped, warned}, a.flags);
}

#ifdef BARIMPACT_HAVE_MPI
// Under mpirun: rank 0 hands out case indices, a SIMD batch at a time, to
// whichever rank asks (dynamic load balancing) and gathers their rows; every
// rank runs cases, rank 0 in a second thread (its main thread makes every
// MPI call, MPI_THREAD_FUNNELED, and polls with short sleeps instead of
// spinning on a core the cases need).
constexpr int tag_request = 1, tag_case = 2, tag_row = 3, tag_stop = 4;

// A signal reaches one rank (the one a user or a batch system signalled)
// or every rank (mpirun passes its SIGINT or SIGTERM on as SIGTERM): the
// rank that has it passes it on, another rank to rank 0 and rank 0 to all,
// so that every rank ends its runs within a few milliseconds of polling and
// exits 128 + that signal (mpirun reports a rank's status; its own, when it
// was the one signalled, is Open MPI's: 1).
class SignalRelay {
 public:
  SignalRelay(int rank, int size) : rank_(rank), size_(size) {}
  /// Passes a signal this rank received on, once; from the main thread.
  void poll() {
    if (passed_ || !interrupted.load()) return;
    passed_ = true;
    int signal = received_signal;
    for (int r = rank_ == 0 ? 1 : 0; r < (rank_ == 0 ? size_ : 1); ++r)
      MPI_Send(&signal, 1, MPI_INT, r, tag_stop, MPI_COMM_WORLD);
  }
  /// Takes a stop from `source`: this rank is interrupted as that one was.
  void receive(int source) {
    int signal = 0;
    MPI_Recv(&signal, 1, MPI_INT, source, tag_stop, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    if (!interrupted.load()) received_signal = signal;
    interrupted.store(true);
    passed_ = rank_ != 0;  // rank 0 passes it on to the others
  }

 private:
  int rank_, size_;
  bool passed_ = false;
};

// Rank 0 hands out chunks of cases to the other ranks until each has been
// told there are none left, and gathers their rows.
template <class Take>
void serve_ranks(int active, Take& take, std::vector<barimpact::SweepRow>& rows, std::mutex& mutex,
                 SignalRelay& relay) {
  while (active > 0) {
    relay.poll();
    MPI_Status status;
    int arrived = 0;
    MPI_Iprobe(MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, &arrived, &status);
    if (!arrived) {
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
      continue;
    }
    if (status.MPI_TAG == tag_stop) {
      relay.receive(status.MPI_SOURCE);
    } else if (status.MPI_TAG == tag_request) {
      int dummy = 0;
      MPI_Recv(&dummy, 1, MPI_INT, status.MPI_SOURCE, tag_request, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
      std::vector<long long> chunk;
      for (std::size_t i : take()) chunk.push_back(static_cast<long long>(i));
      if (chunk.empty()) --active;
      MPI_Send(chunk.data(), static_cast<int>(chunk.size()), MPI_LONG_LONG, status.MPI_SOURCE, tag_case,
               MPI_COMM_WORLD);
    } else {
      int length = 0;
      MPI_Get_count(&status, MPI_CHAR, &length);
      std::string text(static_cast<std::size_t>(length), '\0');
      MPI_Recv(text.data(), length, MPI_CHAR, status.MPI_SOURCE, tag_row, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
      std::lock_guard lock(mutex);
      rows.push_back(barimpact::row_from_json(text));
    }
  }
}

// Runs `indices` in a second thread while this (MPI's) thread relays
// signals with short sleeps; in this one without MPI_THREAD_FUNNELED.
std::vector<barimpact::SweepRow> run_relaying(const barimpact::SweepPlan& plan, const std::filesystem::path& dir,
                                              const std::vector<std::size_t>& indices,
                                              const barimpact::SweepOptions& one, SignalRelay& relay, bool threads) {
  if (!threads) return barimpact::run_sweep(plan, dir, indices, one);
  std::vector<barimpact::SweepRow> rows;
  std::exception_ptr error;
  std::atomic<bool> finished{false};
  std::thread worker([&] {
    try {
      rows = barimpact::run_sweep(plan, dir, indices, one);
    } catch (...) {
      error = std::current_exception();
    }
    finished.store(true);
  });
  while (!finished.load()) {
    relay.poll();
    int arrived = 0;
    MPI_Iprobe(0, tag_stop, MPI_COMM_WORLD, &arrived, MPI_STATUS_IGNORE);
    if (arrived) relay.receive(0);
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  worker.join();
  if (error) std::rethrow_exception(error);
  return rows;
}

// Another rank runs the chunks rank 0 hands out, sending each row back.
void run_handed_out(const barimpact::SweepPlan& plan, const std::filesystem::path& dir,
                    const barimpact::SweepOptions& one, SignalRelay& relay, bool threads) {
  while (true) {
    relay.poll();
    int dummy = 0;
    MPI_Send(&dummy, 1, MPI_INT, 0, tag_request, MPI_COMM_WORLD);
    long long chunk[barimpact::PaperBatch::width];
    MPI_Status status;
    MPI_Recv(chunk, static_cast<int>(barimpact::PaperBatch::width), MPI_LONG_LONG, 0, tag_case, MPI_COMM_WORLD,
             &status);
    int count = 0;
    MPI_Get_count(&status, MPI_LONG_LONG, &count);
    if (count == 0) break;
    std::vector<std::size_t> indices(chunk, chunk + count);
    for (const auto& row : run_relaying(plan, dir, indices, one, relay, threads)) {
      const std::string text = barimpact::row_to_json(row);
      MPI_Send(text.data(), static_cast<int>(text.size()), MPI_CHAR, 0, tag_row, MPI_COMM_WORLD);
    }
  }
}

// A rank failing once the cases are handed out cannot tell the others, who
// wait on it: it ends them all (the runs written stay; rerunning resumes).
[[noreturn]] void abort_sweep(int rank) {
  try {
    throw;
  } catch (const std::exception& e) {
    fmt::print(stderr, "barimpact: error: rank {}: {} (the sweep is stopped; rerun it to resume)\n", rank, e.what());
  } catch (...) {
    fmt::print(stderr, "barimpact: error: rank {}: unknown failure (the sweep is stopped; rerun it to resume)\n", rank);
  }
  MPI_Abort(MPI_COMM_WORLD, 1);
  std::abort();  // MPI_Abort does not return
}

std::vector<barimpact::SweepRow> mpi_sweep(const barimpact::SweepPlan& plan, const std::filesystem::path& dir,
                                           const std::vector<std::size_t>& todo, const barimpact::SweepOptions& o,
                                           int rank, int size, bool threads) {
  std::vector<barimpact::SweepRow> rows;
  barimpact::SweepOptions one = o;
  one.jobs = 1;  // a rank is a core
  SignalRelay relay(rank, size);
  if (rank == 0) {
    std::mutex mutex;  // guards next and rows
    std::size_t next = 0;
    auto take = [&] {
      std::lock_guard lock(mutex);
      std::vector<std::size_t> chunk;
      while (next < todo.size() && chunk.size() < barimpact::PaperBatch::width) chunk.push_back(todo[next++]);
      return chunk;
    };
    std::exception_ptr local_error;  // rethrown once the other ranks are served
    auto run_here = [&] {
      try {
        for (auto chunk = take(); !chunk.empty(); chunk = take()) {
          auto done = barimpact::run_sweep(plan, dir, chunk, one);
          std::lock_guard lock(mutex);
          rows.insert(rows.end(), done.begin(), done.end());
        }
      } catch (...) {
        local_error = std::current_exception();
      }
    };
    // Without MPI_THREAD_FUNNELED from the library, rank 0 only dispatches.
    std::thread local = threads ? std::thread(run_here) : std::thread();
    int active = size - 1;
    try {
      serve_ranks(active, take, rows, mutex, relay);
    } catch (...) {
      abort_sweep(rank);
    }
    if (local.joinable()) local.join();
    if (local_error) std::rethrow_exception(local_error);
  } else {
    try {
      run_handed_out(plan, dir, one, relay, threads);
    } catch (...) {
      abort_sweep(rank);
    }
  }
  return rows;
}
#endif

#ifdef BARIMPACT_HAVE_MPI
int report(const std::exception_ptr& failure);

// A distributed sweep: every rank's checks and rank 0's directory first,
// then the worst exit status among the ranks reaches all of them
// (MPI_Allreduce), so that a refusal on any rank ends every rank, each with
// that status, and none is left waiting at a collective (the failing rank
// says why). Returns an exit status for a rank other than 0, else nullopt
// with `outcome` filled.
std::optional<int> mpi_sweep_command(const std::string& sweep_path, const std::filesystem::path& dir,
                                     const barimpact::SweepOptions& o, const WriteFlags& flags, int rank, int size,
                                     bool threads, barimpact::SweepOutcome& outcome) {
  std::optional<barimpact::SweepPlan> plan;
  barimpact::SweepStart start;
  std::exception_ptr failure;
  try {
    barimpact::check_jobs(o.jobs);
    if (o.batch) (void)barimpact::simd_path();
    plan = barimpact::SweepPlan::from_file(sweep_path);
    if (rank == 0) {  // the other ranks only run the points rank 0 hands out
      barimpact::prepare_sweep(dir, o, flags.force, plan->inputs());
      start = barimpact::resume_sweep(*plan, dir);
    }
  } catch (...) {
    failure = std::current_exception();
  }
  int status = 0, worst = 0;
  if (failure) {
    try {
      std::rethrow_exception(failure);
    } catch (const barimpact::InputError&) {
      status = exit_bad_input;
    } catch (...) {
      status = 1;
    }
  }
  MPI_Allreduce(&status, &worst, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
  if (worst != 0) {
    // The failing rank says why before any rank exits: mpirun ends every
    // rank once one has exited with an error, which could cut the line.
    if (failure) (void)report(failure);
    std::fflush(stderr);
    MPI_Barrier(MPI_COMM_WORLD);
    return failure ? status : worst;
  }
  poll_signals();  // between cases and in their time loops
  const auto done = mpi_sweep(*plan, dir, start.todo, o, rank, size, threads);
  if (rank != 0) return interrupted.load() ? exit_interrupted() : 0;
  outcome = barimpact::finish_sweep(*plan, dir, std::move(start), done);
  return std::nullopt;
}
#endif

int sweep_command(const std::string& sweep_path, const std::string& out_dir, const barimpact::SweepOptions& o,
                  const WriteFlags& flags) {
  int size = 1;
  const std::filesystem::path dir(out_dir);
  barimpact::SweepOutcome outcome;
#ifdef BARIMPACT_HAVE_MPI
  int rank = 0, provided = 0;
  const bool distributed = std::getenv("OMPI_COMM_WORLD_SIZE") != nullptr;
  if (distributed) {
    MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided);
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    MPI_Comm_size(MPI_COMM_WORLD, &size);
  }
  struct Finalize {
    bool on;
    ~Finalize() {
      if (on) MPI_Finalize();
    }
  } finalize{distributed};
  if (size > 1) {
    if (const auto status =
            mpi_sweep_command(sweep_path, dir, o, flags, rank, size, provided >= MPI_THREAD_FUNNELED, outcome))
      return *status;
  } else
#endif
  {
    barimpact::check_jobs(o.jobs);
    if (o.batch) (void)barimpact::simd_path();
    const auto plan = barimpact::SweepPlan::from_file(sweep_path);
    poll_signals();  // between cases and in their time loops
    outcome = barimpact::write_sweep(plan, dir, o, flags.force);
  }
  const auto& rows = outcome.rows;
  auto count = [&](auto&& pred) { return std::count_if(rows.begin(), rows.end(), pred); };
  const auto complete = count([](const auto& r) { return r.status == "complete"; });
  const auto stopped = count([](const auto& r) { return r.status == "interrupted"; });
  const auto warned = count([](const auto& r) { return !r.warnings.empty(); });
  fmt::print("{} cases: {} run{} ({} in SIMD batches{}), {} resumed, {} not complete; sweep.csv in {}\n", rows.size(),
             outcome.run - static_cast<std::size_t>(stopped), size > 1 ? fmt::format(" on {} ranks", size) : "",
             outcome.batched,
             outcome.batched > 0 ? fmt::format(", {}", barimpact::to_string(barimpact::simd_path())) : "",
             outcome.resumed, static_cast<long>(rows.size()) - complete, out_dir);
  print_study_warnings(rows);
  return study_exit({"cases", "sweep.csv", rows.size(), complete, stopped, warned}, flags);
}

// A pile study's command line (bearing, drive, inspector): its case, --out,
// --set for every run, --jobs, --no-plot and the write flags.
struct PileStudyArgs {
  std::string case_path, out;
  std::vector<std::string> sets;
  bool no_plot = false;
  barimpact::SweepOptions options;
  WriteFlags flags;
};

struct BearingArgs : PileStudyArgs {
  std::string capacity;
  std::optional<double> toe_share;
};

// How a pile study's runs ended, and its figure drawn by the Python package
// (`figure`: its plot subcommand) when every run is done and one completed.
struct PileStudyEnd {
  std::vector<barimpact::SweepRow> runs;
  long complete = 0, stopped = 0, warned = 0;
  bool plotted = false;
};

template <class Row>
PileStudyEnd end_pile_study(const std::vector<Row>& rows, const PileStudyArgs& a, const char* figure) {
  PileStudyEnd e;
  for (const auto& r : rows) {
    e.runs.push_back(r.run);
    e.complete += r.run.status == "complete" ? 1 : 0;
    e.stopped += r.run.status == "interrupted" ? 1 : 0;
    e.warned += r.run.warnings.empty() ? 0 : 1;
  }
  e.plotted = !a.no_plot && e.stopped == 0 && e.complete > 0 && run_python({figure, a.out});
  return e;
}

std::vector<barimpact::Case::Override> overrides(const std::vector<std::string>& sets) {
  std::vector<barimpact::Case::Override> o;
  for (const auto& s : sets) o.push_back({s});
  return o;
}

int bearing_command(const BearingArgs& a) {
  barimpact::BearingOptions o;
  barimpact::parse_capacity(a.capacity, o);
  o.toe_share = a.toe_share;
  o.sets = overrides(a.sets);
  const barimpact::BearingPlan plan(a.case_path, o);
  poll_signals();  // between capacities and in their time loops
  const auto rows = barimpact::write_bearing(plan, a.out, a.options, a.flags.force);
  const PileStudyEnd e = end_pile_study(rows, a, "bearing-plot");
  // The capacities in newtons, or kip under [units] system = "US".
  const bool us = plan.sweep().case_at(plan.sweep().points().front()).units == "US";
  const double scale = us ? 1.0 / barimpact::units::kip : 1.0;
  fmt::print("{} capacities from {:.4g} to {:.4g} {} (toe share {:.3g}): {} complete; bearing.csv{} in {}\n",
             rows.size(), scale * o.from, scale * o.to, us ? "kip" : "N", plan.toe_share(), e.complete,
             e.plotted ? " and bearing.png" : "", a.out);
  print_study_warnings(e.runs);
  return study_exit({"cases", "bearing.csv", rows.size(), e.complete, e.stopped, e.warned}, a.flags);
}

// The drive's outcome in one line: how deep, in how many blows and minutes, the largest stresses.
void print_drive(const barimpact::DrivePlan& plan, const std::vector<barimpact::DriveRow>& rows, bool plotted,
                 const std::string& out) {
  const auto t = barimpact::drive_totals(plan, rows);
  const barimpact::units::Display* d = barimpact::units::display(plan.base().units);
  // A depth or stress with its display unit (m and MPa, ft and ksi), bare under "none".
  // SI depths as the case gives them (12 m); in ft to 4 digits (2 m is 6.562 ft).
  const int digits = d && d->system == "US" ? 4 : 6;
  auto depth = [&](double v) {
    return d ? fmt::format("{:.{}g} {}", d->depth(v), digits, d->depth.name) : fmt::format("{:g}", v);
  };
  auto stress = [&](double v) {
    return d ? fmt::format("{:.4g} {}", d->stress(v), d->stress.name) : fmt::format("{:.4g}", v);
  };
  // The refusal is a count per 250 mm in the case; under "US" also per ft.
  const double refusal = plan.drive().refusal;
  const std::string criterion = d && d->system == "US" ? fmt::format("{:g} blows per 250 mm, {:.3g} blows/ft", refusal,
                                                                     refusal / 0.25 * d->count_length)
                                                       : fmt::format("{:g} blows per 250 mm", refusal);
  const std::string reached = t.refusal_depth
                                  ? fmt::format("refusal ({}) at {}", criterion, depth(*t.refusal_depth))
                                  : fmt::format("driven to {}", depth(rows.empty() ? 0.0 : rows.back().depth));
  fmt::print(
      "{} depths: {}; {:.0f} blows, {:.1f} min at {:g} blows/min; max compression {} at {}, max "
      "tension {} at {}; drive.csv, summary.json{} in {}\n",
      rows.size(), reached, t.total_blows, t.driving_time, plan.drive().blow_rate, stress(t.max_compression),
      depth(t.max_compression_depth), stress(t.max_tension), depth(t.max_tension_depth),
      plotted ? " and drive.png" : "", out);
}

int drive_command(const PileStudyArgs& a) {
  const barimpact::DrivePlan plan(a.case_path, overrides(a.sets));
  poll_signals();  // between depths and in their time loops
  const auto rows = barimpact::write_drive(plan, a.out, a.options, a.flags.force);
  const PileStudyEnd e = end_pile_study(rows, a, "drive-plot");
  print_drive(plan, rows, e.plotted, a.out);
  print_study_warnings(e.runs);
  return study_exit({"depths", "drive.csv", rows.size(), e.complete, e.stopped, e.warned}, a.flags);
}

struct InspectorArgs : PileStudyArgs {
  std::string stroke;
  std::optional<double> depth;
};

int inspector_command(const InspectorArgs& a) {
  const barimpact::InspectorPlan plan(a.case_path, a.stroke, a.depth, overrides(a.sets));
  poll_signals();  // between strokes and in their time loops
  const auto rows = barimpact::write_inspector(plan, a.out, a.options, a.flags.force);
  const PileStudyEnd e = end_pile_study(rows, a, "inspector-plot");
  fmt::print("{} strokes: {} complete; inspector.csv{} in {}\n", rows.size(), e.complete,
             e.plotted ? " and inspector.png" : "", a.out);
  print_study_warnings(e.runs);
  return study_exit({"strokes", "inspector.csv", rows.size(), e.complete, e.stopped, e.warned}, a.flags);
}

// hammers: the shipped table, one hammer a line.
int hammers_command() {
  fmt::print("{:<18} {:<10} {:>9} {:>8} {:>11} {:>6}  source\n", "name", "kind", "ram (kg)", "stroke", "energy (kJ)",
             "eff.");
  for (const auto& h : barimpact::shipped_hammers()) {
    const double stroke = h.stroke > 0 ? h.stroke : h.energy / (h.ram_mass * 9.81);
    fmt::print("{:<18} {:<10} {:>9.0f} {:>6.3f} m {:>11.1f} {:>6.2f}  {}\n", h.name, barimpact::to_string(h.kind),
               h.ram_mass, stroke, 1e-3 * h.ram_mass * 9.81 * stroke, h.efficiency, h.source);
  }
  return 0;
}

// hopkinson: the analysis first (a signal it refuses writes nothing), then
// hopkinson.csv, summary.json and the figures, moved into place together.
int hopkinson_command(const std::string& setup_path, const std::string& out, bool no_plot, const WriteFlags& flags) {
  const auto setup = barimpact::HopkinsonSetup::from_file(setup_path);
  const auto result = barimpact::analyse_hopkinson(setup);
  barimpact::RunDirectory dir(out, flags.force, "hopkinson", true, barimpact::hopkinson_inputs(setup));
  bool plotted = false;
  dir.commit([&](const std::filesystem::path& staging) {
    barimpact::write_text(staging / "hopkinson.csv", barimpact::hopkinson_csv(result));
    barimpact::write_text(staging / "summary.json", barimpact::hopkinson_summary_json(result));
    plotted = !no_plot && run_python({"hopkinson-plot", staging.string(), "--as", out});
  });
  const auto& a = result.alignment;
  fmt::print(
      "hopkinson: {} rows over {:.4g} from the incident foot (by {}; t = {:.6g} in its record, t = 0 at the "
      "specimen below)\n",
      result.columns.front().values.size(), a.incident.end - a.incident.start, a.method, a.foot);
  fmt::print("  peak stress (3-wave) {:.4g} at t = {:.4g}; peak strain rate (3-wave) {:.4g}\n",
             result.peak_stress_3w.value, result.peak_stress_3w.t, result.peak_strain_rate_3w.value);
  if (result.equilibrium_from)
    fmt::print(
        "  equilibrium (|2 (F_front - F_back) / (F_front + F_back)| < 0.05) from t = {:.4g} to the peak (first "
        "at {:.4g})\n",
        *result.equilibrium_from, result.equilibrium_first.value_or(*result.equilibrium_from));
  if (result.fit.modulus > 0) {
    fmt::print("  fit (3-wave): modulus {:.4g}", result.fit.modulus);
    if (result.fit.yield_stress) fmt::print(", yield stress (0.2% offset) {:.4g}", *result.fit.yield_stress);
    if (result.fit.hardening_modulus) fmt::print(", hardening modulus {:.4g}", *result.fit.hardening_modulus);
    fmt::print("\n");
  }
  if (!a.dispersion_note.empty()) fmt::print("  dispersion: {}\n", a.dispersion_note);
  fmt::print("  hopkinson.csv, summary.json{} in {}\n", plotted ? " and figures" : "", dir.target().string());
  print_warnings(result.warnings);
  if (flags.strict && !result.warnings.empty()) return exit_warnings;
  return 0;
}

// pda: the analysis first (a record it refuses writes nothing), then pda.csv,
// summary.json and the figures, moved into place together.
int pda_command(const std::string& record_path, const std::string& out, bool no_plot, const WriteFlags& flags) {
  const auto record = barimpact::PileRecord::from_file(record_path);
  const auto r = barimpact::analyse_pda(record);
  barimpact::RunDirectory dir(out, flags.force, "pda", true, barimpact::pda_inputs(record));
  dir.expect(barimpact::pda_files());
  bool plotted = false;
  dir.commit([&](const std::filesystem::path& staging) {
    barimpact::write_text(staging / "pda.csv", barimpact::pda_csv(r));
    barimpact::write_text(staging / "summary.json", barimpact::pda_summary_json(r));
    plotted = !no_plot && run_python({"pda-plot", staging.string(), "--as", out});
  });
  fmt::print("pda: {} samples; t1 = {:.6g} s, t2 = {:.6g} s (2L/c = {:.4g} s), F / (Z v) at t1 = {:.3f}\n",
             r.signals.t.size(), r.t1, r.t2, r.record.travel_time(), r.ratio_at_impact);
  fmt::print("  FMX {:.4g} kN, VMX {:.4g} m/s, EMX {:.4g} kJ, DMX {:.4g} mm\n", 1e-3 * r.fmx, r.vmx, 1e-3 * r.emx,
             1e3 * r.dmx);
  fmt::print("  CSX {:.4g} MPa, TSX {:.4g} MPa\n", 1e-6 * r.csx, 1e-6 * r.tsx);
  fmt::print("  RMX {:.4g} kN at t = {:.6g} s, RSP {:.4g} kN (J_c = {:g})\n", 1e-3 * r.rmx, r.rmx_time, 1e-3 * r.rsp,
             r.record.damping);
  if (r.bta_depth)
    fmt::print("  BTA {:.3f} at {:.3g} m below the gauges\n", r.bta, *r.bta_depth);
  else
    fmt::print("  BTA 1 (no drop of the wave up above 1% of the wave down)\n");
  fmt::print("  pda.csv, summary.json{} in {}\n", plotted ? " and figures" : "", dir.target().string());
  return 0;
}

// match: the fit first (a record it refuses writes nothing), then match.csv,
// soil.csv, static.csv, summary.json and the figures, moved into place together.
int match_command(const std::string& record_path, const std::string& out, bool no_plot, int jobs,
                  const WriteFlags& flags) {
  const auto record = barimpact::PileRecord::from_file(record_path);
  barimpact::check_jobs(jobs);
  barimpact::RunDirectory dir(out, flags.force, "match", true, barimpact::pda_inputs(record));
  dir.expect(barimpact::match_files());  // before the fit
  poll_signals();                        // the fit stops at its next iteration: nothing is written
  const auto r = barimpact::match_pile(record, jobs, &interrupted);
  if (r.interrupted || interrupted.load()) return exit_interrupted();
  bool plotted = false;
  dir.commit([&](const std::filesystem::path& staging) {
    barimpact::write_text(staging / "match.csv", barimpact::match_csv(r));
    barimpact::write_text(staging / "soil.csv", barimpact::soil_csv(r));
    barimpact::write_text(staging / "static.csv", barimpact::static_csv(r));
    barimpact::write_text(staging / "summary.json", barimpact::match_summary_json(r));
    plotted = !no_plot && run_python({"match-plot", staging.string(), "--as", out});
  });
  const auto& s = r.soil;
  fmt::print("match: {} samples from t = {:.6g} s to t2 + {:.4g} s; {} starts, {} iterations, {} blows in {:.3g} s\n",
             r.computed.size(), r.pda.t_foot, r.window, r.starts.size(), r.iterations, r.evaluations, r.seconds);
  fmt::print("  capacity {:.4g} kN: shaft {:.4g} kN, toe {:.4g} kN (Case method RMX {:.4g} kN)\n", 1e-3 * s.capacity(),
             1e-3 * s.shaft_total(), 1e-3 * s.toe, 1e-3 * r.pda.rmx);
  fmt::print("  quakes {:.3g} mm (shaft), {:.3g} mm (toe); dampings {:.3g} s/m (shaft), {:.3g} s/m (toe), {}\n",
             1e3 * s.shaft_quake, 1e3 * s.toe_quake, s.shaft_damping, s.toe_damping,
             s.law == barimpact::DampingLaw::smith ? "Smith" : "viscous");
  fmt::print(
      "  match quality {:.3g}% (rms force difference over the largest force); the starts' capacities span {:.3g} kN\n",
      100.0 * r.quality, 1e-3 * r.spread());
  fmt::print("  static load test: the capacity reached at {:.3g} mm\n", 1e3 * r.static_test.s_c);
  fmt::print("  match.csv, soil.csv, static.csv, summary.json{} in {}\n", plotted ? " and figures" : "",
             dir.target().string());
  const auto warnings = r.warnings();
  print_warnings(warnings);
  return flags.strict && !warnings.empty() ? exit_warnings : 0;
}

// Validates a case and reports what to know before running it (run/check.hpp).
int check_command(const std::string& case_path, const std::vector<std::string>& sets) {
  const auto c = read_case(case_path, sets).c;
  const auto k = barimpact::check_case(c);  // refuses what exceeds the memory, as run does
  fmt::print("{}: valid\n{}", case_path, barimpact::check_text(c, k));
  if (const auto w = barimpact::output_size_warning(c, k.resources); !w.empty()) print_warnings({w});
  if (!k.trouble.empty()) {
    fmt::print(stderr, "barimpact: {} (in the first {} steps)\n", k.trouble, k.timed_steps);
    return exit_non_finite;
  }
  return 0;
}

// The figures are drawn by the Python package (matplotlib): hand over to it.
int plot_command(const std::string& run_dir, const std::string& figures, bool force) {
  // The figures' directory follows the output rule too.
  const std::filesystem::path target =
      figures.empty() ? std::filesystem::path(run_dir) / "figures" : std::filesystem::path(figures);
  const auto holds = [&](std::string_view name) {
    return std::filesystem::is_regular_file(std::filesystem::path(run_dir) / name);
  };
  // A study's or analysis's table: its figures are drawn where the command draws them, in DIR.
  constexpr std::array<std::string_view, 7> tables_drawn_in_place{
      "hopkinson.csv", "pda.csv", "match.csv", "bearing.csv", "drive.csv", "inspector.csv", "convergence.csv"};
  const bool tables = std::any_of(tables_drawn_in_place.begin(), tables_drawn_in_place.end(), holds);
  if (!holds(barimpact::history_file(barimpact::OutputFormat::csv)) &&
      !holds(barimpact::history_file(barimpact::OutputFormat::hdf5)) && !holds("sweep.csv") && !tables)
    throw barimpact::InputError(fmt::format(
        "plot: {} holds no history.csv, results.h5, sweep.csv or a study's table (hopkinson.csv, pda.csv, match.csv, "
        "bearing.csv, drive.csv, inspector.csv, convergence.csv): give a directory written by barimpact",
        run_dir));
  // The rule first, then what plotting needs. The Python package makes the
  // figures' directory, and lists DIR/figures in the run's marker, once it
  // has read the results: results it cannot read leave nothing behind.
  const barimpact::CommandInputs reads{{}, {run_dir}};
  if (!tables) (void)barimpact::check_output_directory(target, force, "--out", reads);
  if (python_package_dir().empty())
    throw barimpact::InputError(
        "plot: the Python package barimpact is not installed beside this command (python/ in a build tree, " +
        std::string(BARIMPACT_PYTHON_FROM_BIN) + " from its bin/)");
  setenv("PYTHONPATH", python_path().c_str(), 1);
  std::vector<std::string> args{python_interpreter(), "-m", "barimpact", "plot", run_dir};
  if (!figures.empty()) {
    args.emplace_back("--out");
    args.push_back(figures);
  }
  if (force) args.emplace_back("--force");  // the package applies the same rule again
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  execv(argv[0], argv.data());
  fmt::print(stderr, "barimpact: error: plot: cannot start {} ({})\n", args.front(), std::strerror(errno));
  return exit_bad_input;
}

// ---- The commands' options: each adds its subcommand and returns what it
// runs once parsed (its arguments live as long as that action).

struct Command {
  CLI::App* app;
  std::function<int()> action;
};

const std::string jobs_help = "Threads, 1 .. 1024 (default, or 0: all cores)";

void add_sets(CLI::App* command, std::vector<std::string>& sets, const std::string& help) {
  command->add_option("--set", sets, help)->take_all()->allow_extra_args(false);
}

// run and exact: the same files, from the scheme or from the exact solution.
Command add_run(CLI::App& app, bool exact) {
  struct Args {
    std::string case_path, out;
    std::vector<std::string> sets;
    WriteFlags flags;
  };
  auto a = std::make_shared<Args>();
  auto* c = exact ? app.add_subcommand("exact", "Tabulate the exact solution the case admits (same files as run)")
                  : app.add_subcommand("run",
                                       "Run one case and write history.csv, fields.csv (or results.h5: "
                                       "output.format), case.toml, summary.json");
  c->add_option("case", a->case_path, "Case file (TOML)")->required();
  c->add_option("--out", a->out, "Output directory: a new or empty one, or one barimpact wrote (replaced)")->required();
  add_write_flags(c, a->flags);
  add_sets(c, a->sets,
           exact ? "Override a case key: section.key=value"
                 : "Override a case key: section.key=value (value read as TOML, a bare word as a string)");
  return {c, [a, exact] { return run_command(a->case_path, a->out, a->sets, exact, a->flags); }};
}

Command add_check(CLI::App& app) {
  struct Args {
    std::string case_path;
    std::vector<std::string> sets;
  };
  auto a = std::make_shared<Args>();
  auto* c = app.add_subcommand(
      "check", "Validate a case without running it: steps, stable step, penalty time constants, a time estimate");
  c->add_option("case", a->case_path, "Case file (TOML)")->required();
  add_sets(c, a->sets, "Override a case key: section.key=value");
  return {c, [a] { return check_command(a->case_path, a->sets); }};
}

// The first `name` on PATH that can be run; empty when there is none.
std::string on_path(const std::string& name) {
  const char* path = std::getenv("PATH");
  std::stringstream dirs(path != nullptr ? path : "");
  std::error_code ec;
  for (std::string dir; std::getline(dirs, dir, ':');) {
    const auto file = std::filesystem::path(dir.empty() ? "." : dir) / name;
    if (::access(file.c_str(), X_OK) == 0 && !std::filesystem::is_directory(file, ec)) return file.string();
  }
  return {};
}

// Waits for `child`, passing this process's SIGINT or SIGTERM on to it
// once; then 128 + that signal, else the child's exit status.
int wait_passing_signal(pid_t child) {
  bool passed = false;
  int status = 0;
  for (;;) {
    const pid_t done = waitpid(child, &status, WNOHANG);
    if (done == child) break;
    if (done < 0 && errno != EINTR) throw std::system_error(errno, std::generic_category(), "--ranks: waitpid");
    if (interrupted.load() && !passed) {
      ::kill(child, static_cast<int>(received_signal));
      passed = true;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  if (interrupted.load()) return exit_interrupted();
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

// sweep --ranks N: this command's sweep (`args`) under `mpiexec -n N`,
// mpiexec from PATH. Open MPI's mpirun exits 1 when it is itself
// signalled, whatever its ranks return: a SIGINT or SIGTERM here is passed
// on to it (its ranks end their runs and write what is done) and the
// command exits 128 + the signal, else with mpiexec's status.
int launch_ranks(int ranks, std::vector<std::string> args) {
#if !defined(BARIMPACT_MPI_PROGRAM) && !defined(BARIMPACT_HAVE_MPI)
  throw barimpact::InputError(fmt::format("--ranks {}: this barimpact is built without MPI", ranks));
#endif
  if (ranks < 1)
    throw barimpact::InputError(fmt::format("--ranks {}: the number of MPI ranks must be at least 1", ranks));
  if (std::getenv("OMPI_COMM_WORLD_SIZE") != nullptr)
    throw barimpact::InputError(fmt::format("--ranks {}: the sweep is under mpirun already", ranks));
  const std::string mpiexec = on_path("mpiexec");
  if (mpiexec.empty())
    throw barimpact::InputError(
        fmt::format("--ranks {}: no mpiexec on PATH (install Open MPI, or run the sweep without --ranks)", ranks));
  args.insert(args.begin(), {mpiexec, "-n", std::to_string(ranks),
                             std::filesystem::read_symlink("/proc/self/exe").string(), "sweep"});
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  poll_signals();  // a signal from here on is passed on to mpiexec
  std::fflush(stdout);
  const pid_t parent = getpid(), pid = fork();
  if (pid < 0) throw std::system_error(errno, std::generic_category(), "--ranks: fork");
  if (pid == 0) {
    // A group of its own, so that a signal to this command's group (Ctrl-C)
    // reaches mpirun once, passed on: a second one makes it kill its ranks
    // before they write what is done. No terminal input (read from a
    // background group, it would stop mpirun); ended with this process.
    setpgid(0, 0);
    prctl(PR_SET_PDEATHSIG, SIGTERM);
    if (getppid() != parent) _exit(exit_bad_input);
    if (const int null = open("/dev/null", O_RDONLY); null >= 0) dup2(null, STDIN_FILENO);
    execv(argv[0], argv.data());
    fmt::print(stderr, "barimpact: error: --ranks {}: cannot start {}: {}\n", ranks, mpiexec, std::strerror(errno));
    _exit(exit_bad_input);
  }
  return wait_passing_signal(pid);
}

Command add_sweep(CLI::App& app) {
  struct Args {
    std::string file, out;
    barimpact::SweepOptions options;
    bool no_batch = false;
    WriteFlags flags;
    std::optional<int> ranks;
    // The sweep's own arguments, as a rank runs it (without --ranks).
    [[nodiscard]] std::vector<std::string> sweep_arguments() const {
      std::vector<std::string> args{file, "--out", out, "--jobs", std::to_string(options.jobs)};
      for (auto [flag, on] : {std::pair{"--no-batch", no_batch}, {"--force", flags.force}, {"--strict", flags.strict}})
        if (on) args.emplace_back(flag);
      return args;
    }
  };
  auto a = std::make_shared<Args>();
  auto* c = app.add_subcommand("sweep", "Run every case of a sweep file (runs/<id>/ and sweep.csv); resumes");
  c->add_option("sweep", a->file, "Sweep file (TOML)")->required();
  c->add_option("--out", a->out, "Output directory: a new or empty one, or a sweep's (rerunning resumes)")->required();
  add_write_flags(c, a->flags);
  c->add_option("--jobs", a->options.jobs, jobs_help);
  c->add_flag("--no-batch", a->no_batch, "Run every case alone (no SIMD batches)");
  c->add_option("--ranks", a->ranks,
                "Run the sweep on N MPI ranks: mpiexec -n N of this command, mpiexec from PATH (a signal to this "
                "process ends it with 130/143)");
  return {c, [a] {
            if (a->ranks) return launch_ranks(*a->ranks, a->sweep_arguments());
            a->options.batch = !a->no_batch;
            a->options.interrupt = &interrupted;
            return sweep_command(a->file, a->out, a->options, a->flags);
          }};
}

// A pile study's subcommand: its case and own options (`extra`), then --out,
// --set, --jobs, --no-plot and the write flags; run on central differences
// (Smith's soil), a signal ending it between runs.
template <class Args, class Extra>
Command add_pile_study(CLI::App& app, const char* name, const char* help, const char* case_help, const char* each,
                       Extra extra, int (*command)(const Args&)) {
  auto a = std::make_shared<Args>();
  auto* c = app.add_subcommand(name, help);
  c->add_option("case", a->case_path, case_help)->required();
  c->add_option("--out", a->out,
                fmt::format("Output directory: a new or empty one, or one barimpact {} wrote (resumes)", name))
      ->required();
  extra(c, *a);
  c->add_option("--set", a->sets,
                fmt::format("Override a key of the case for every {}: section.key=value (repeatable)", each));
  c->add_option("--jobs", a->options.jobs, jobs_help);
  c->add_flag("--no-plot", a->no_plot, fmt::format("Skip {}.png", name));
  add_write_flags(c, a->flags);
  return {c, [a, command] {
            a->options.interrupt = &interrupted;
            a->options.batch = false;  // Smith's soil runs on central differences
            return command(*a);
          }};
}

Command add_bearing(CLI::App& app) {
  return add_pile_study<BearingArgs>(
      app, "bearing", "Bearing graph of a pile-driving case: the blow count against the static capacity (bearing.csv)",
      "Case file (TOML) with Smith's soil", "capacity",
      [](CLI::App* c, BearingArgs& a) {
        c->add_option("--capacity", a.capacity, "FROM:TO:COUNT static capacities R_toe + R_shaft, in N")->required();
        c->add_option("--toe-share", a.toe_share, "R_toe / capacity, 0 .. 1 (default: the case's)");
      },
      bearing_command);
}

Command add_drive(CLI::App& app) {
  return add_pile_study<PileStudyArgs>(
      app, "drive",
      "Drivability of a pile case with [drive]: blow counts, stresses and capacity against depth (drive.csv)",
      "Case file (TOML) with [drive] and [[layer]]", "depth", [](CLI::App*, PileStudyArgs&) {}, drive_command);
}

Command add_inspector(CLI::App& app) {
  return add_pile_study<InspectorArgs>(
      app, "inspector", "Inspector's chart: blow count and stresses against the hammer's stroke (inspector.csv)",
      "Case file (TOML) with a [hammer] and Smith's soil or [drive]", "stroke",
      [](CLI::App* c, InspectorArgs& a) {
        c->add_option("--stroke", a.stroke, "FROM:TO:COUNT strokes, in m")->required();
        c->add_option("--depth", a.depth, "The penetration (m) of a [drive] case's profile to chart at");
      },
      inspector_command);
}

Command add_hammers(CLI::App& app) {
  auto* c = app.add_subcommand("hammers", "List the hammers barimpact ships ([hammer] model = \"NAME\")");
  return {c, [] { return hammers_command(); }};
}

Command add_hopkinson(CLI::App& app) {
  struct Args {
    std::string setup, out;
    bool no_plot = false;
    WriteFlags flags;
  };
  auto a = std::make_shared<Args>();
  auto* c = app.add_subcommand(
      "hopkinson", "Analyse a split Hopkinson bar test's gauge signals (hopkinson.csv, summary.json, figures)");
  c->add_option("setup", a->setup, "Setup file (TOML): bars, specimen, the two gauges' signals")->required();
  c->add_option("--out", a->out, "Output directory: a new or empty one, or one barimpact wrote (replaced)")->required();
  c->add_flag("--no-plot", a->no_plot, "Skip the figures");
  add_write_flags(c, a->flags);
  return {c, [a] { return hopkinson_command(a->setup, a->out, a->no_plot, a->flags); }};
}

Command add_pda(CLI::App& app) {
  struct Args {
    std::string record, out;
    bool no_plot = false;
    WriteFlags flags;
  };
  auto a = std::make_shared<Args>();
  auto* c = app.add_subcommand(
      "pda",
      "Analyse a measured blow on a pile: the waves, the Case method, energy, stresses, BTA (pda.csv, summary.json)");
  c->add_option("record", a->record, "Record file (TOML): the pile below the gauges, the CSV record and its columns")
      ->required();
  c->add_option("--out", a->out, "Output directory: a new or empty one, or one barimpact wrote (replaced)")->required();
  c->add_flag("--no-plot", a->no_plot, "Skip the figures");
  add_write_flags(c, a->flags);
  return {c, [a] { return pda_command(a->record, a->out, a->no_plot, a->flags); }};
}

Command add_match(CLI::App& app) {
  struct Args {
    std::string record, out;
    bool no_plot = false;
    int jobs = 0;
    WriteFlags flags;
  };
  auto a = std::make_shared<Args>();
  auto* c = app.add_subcommand("match",
                               "Signal matching: the soil resistance whose computed force at the gauges matches the "
                               "record's ([match]; match.csv, soil.csv, static.csv, summary.json)");
  c->add_option("record", a->record, "Record file (TOML): the pile below the gauges, the CSV record, [match]")
      ->required();
  c->add_option("--out", a->out, "Output directory: a new or empty one, or one barimpact wrote (replaced)")->required();
  c->add_flag("--no-plot", a->no_plot, "Skip the figures");
  c->add_option("--jobs", a->jobs, "Threads for the fit's blows (0: all cores)");
  add_write_flags(c, a->flags);
  return {c, [a] { return match_command(a->record, a->out, a->no_plot, a->jobs, a->flags); }};
}

// converge records the command line that made it (convergence.md).
Command add_converge(CLI::App& app, int argc, char** argv) {
  auto a = std::make_shared<ConvergeArgs>();
  auto* c =
      app.add_subcommand("converge", "Convergence and work-precision study of a case (convergence.csv/.md, plots)");
  c->add_option("case", a->case_path, "Case file (TOML)")->required();
  c->add_option("--out", a->out, "Output directory: a new or empty one, or a study's (rerunning resumes)")->required();
  add_write_flags(c, a->flags);
  add_sets(c, a->sets, "Override a case key: section.key=value");
  auto& study = a->arguments;
  c->add_option("--levels", study.levels, "Refinement levels, 2 .. 12 (default 4)");
  c->add_option("--refine", study.refine, "both (h and dt together, default), h, dt, or none")
      ->check(CLI::IsMember({"both", "h", "dt", "none"}));
  c->add_option("--ratio", study.ratio, "Refinement ratio per level, 2 .. 16 (default 2)");
  c->add_option("--vary", study.vary,
                "A key along the levels: key=v1,v2,... | key=a:b:n | key=log:a:b:n (wins over the study's own "
                "time.step or elements: refused where --refine refines them too)");
  c->add_option("--schemes", a->schemes, "Compare schemes: a,b,c (default: the case's)");
  c->add_option("--reference", study.reference, "auto (exact if the case admits one, else finest), rigid, finest")
      ->check(CLI::IsMember({"auto", "rigid", "finest"}));
  c->add_option("--jobs", study.jobs, jobs_help);
  return {c, [a, argc, argv] {
            a->command = "barimpact";
            for (int i = 1; i < argc; ++i) {
              const std::string arg = argv[i];
              a->command += " " + (arg.find_first_of(" *;()") == std::string::npos ? arg : "'" + arg + "'");
            }
            return converge_command(*a);
          }};
}

Command add_plot(CLI::App& app) {
  struct Args {
    std::string dir, out;
    bool force = false;
  };
  auto a = std::make_shared<Args>();
  auto* c = app.add_subcommand("plot", "Draw the figures of a run or sweep directory (PNG and SVG) with matplotlib");
  c->add_option("dir", a->dir, "A directory written by barimpact run or sweep")->required();
  c->add_option("--out", a->out, "Where the figures go (default: DIR/figures), by the output rule of run");
  c->add_flag("--force", a->force,
              "Write the figures beside other files (never in $HOME, / or a parent of the working directory)");
  return {c, [a] { return plot_command(a->dir, a->out, a->force); }};
}

std::string version_text() {
  std::vector<std::string_view> paths;
  for (auto p : barimpact::supported_simd_paths()) paths.push_back(barimpact::to_string(p));
  try {
    return fmt::format("barimpact 0.1.0\nbatch kernels: {} (this processor runs: {}; BARIMPACT_SIMD forces one)",
                       barimpact::to_string(barimpact::simd_path()), fmt::join(paths, ", "));
  } catch (const barimpact::InputError& e) {
    return fmt::format("barimpact 0.1.0\nbatch kernels: {}", e.what());
  }
}

// An unknown first word gets the command list, not CLI11's "extra arguments".
bool known_command(int argc, char** argv, const std::vector<Command>& commands) {
  if (argc < 2 || argv[1][0] == '-') return true;
  return std::any_of(commands.begin(), commands.end(), [&](const Command& c) { return c.app->get_name() == argv[1]; });
}

// The error's one line and exit status (see the header).
int report(const std::exception_ptr& failure) {
  try {
    std::rethrow_exception(failure);
  } catch (const Reported& r) {
    return r.status;
  } catch (const barimpact::Interrupted&) {
    return exit_interrupted();  // a study's set-up: nothing run yet, nothing to say
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
}

}  // namespace

#ifdef BARIMPACT_MPI_PROGRAM
// Under mpirun (Open MPI sets OMPI_COMM_WORLD_SIZE) a sweep runs as the MPI
// build of this command, beside it, so that no other process loads MPI's
// libraries. Returns only when that program cannot be run.
int exec_mpi_program(char** argv) {
  std::error_code ec;
  const auto program = std::filesystem::read_symlink("/proc/self/exe", ec).parent_path() / BARIMPACT_MPI_PROGRAM;
  if (!ec) execv(program.c_str(), argv);
  fmt::print(stderr, "barimpact: error: a sweep under mpirun runs {}: {}\n", program.string(),
             ec ? ec.message() : std::strerror(errno));
  return 1;
}
#endif

int main(int argc, char** argv) {
  barimpact_cli::prefer_huge_pages();
#ifdef BARIMPACT_MPI_PROGRAM
  if (argc > 1 && std::string_view(argv[1]) == "sweep" && std::getenv("OMPI_COMM_WORLD_SIZE") != nullptr)
    return exec_mpi_program(argv);
#endif
  CLI::App app{"barimpact: a visco-elastic bar hitting obstacles (Do, Raupp & Feijoo 1979)"};
  app.require_subcommand(1);
  app.set_version_flag("--version", version_text);
  const std::vector<Command> commands{add_run(app, false), add_check(app),   add_run(app, true),
                                      add_sweep(app),      add_bearing(app), add_drive(app),
                                      add_inspector(app),  add_hammers(app), add_hopkinson(app),
                                      add_pda(app),        add_match(app),   add_converge(app, argc, argv),
                                      add_plot(app)};
  if (!known_command(argc, argv, commands)) {
    fmt::print(stderr,
               "barimpact: error: unknown command \"{}\" (commands: run, check, exact, sweep, converge, bearing, "
               "drive, inspector, hammers, hopkinson, pda, match, plot; see barimpact --help)\n",
               argv[1]);
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
  install_signal_handlers();
  try {
    for (const auto& c : commands)
      if (c.app->parsed()) return c.action();
  } catch (...) {
    return report(std::current_exception());
  }
  return 0;
}
