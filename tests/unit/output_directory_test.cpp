#include "barimpact/run/output_directory.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <sys/mount.h>
#include <unistd.h>

#include <cstdlib>
#include <fstream>

#include "../support/run_case.hpp"
#include "barimpact/run/output.hpp"
#include "barimpact/run/results_h5.hpp"

namespace barimpact {
namespace {

namespace fs = std::filesystem;

// A fresh directory per test, the working directory moved into it.
class OutputDirectory : public ::testing::Test {
 protected:
  void SetUp() override {
    old_cwd_ = fs::current_path();
    root_ = fs::temp_directory_path() / ("barimpact-outdir-" + std::to_string(::getpid()) + "-" +
                                         ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(root_);
    fs::create_directories(root_ / "cwd");
    fs::current_path(root_ / "cwd");
  }
  void TearDown() override {
    fs::current_path(old_cwd_);
    fs::remove_all(root_);
  }
  static void touch(const fs::path& p, const std::string& text = "x") { std::ofstream(p) << text; }
  fs::path root_, old_cwd_;
};

TEST_F(OutputDirectory, NewPathsAndEmptyDirectoriesAreCreated) {
  EXPECT_EQ(check_output_directory(root_ / "new", false), OutputMode::create);
  fs::create_directory(root_ / "empty");
  EXPECT_EQ(check_output_directory(root_ / "empty", false), OutputMode::create);
  EXPECT_EQ(check_output_directory("sub", false), OutputMode::create);  // inside the working directory
}

TEST_F(OutputDirectory, SomeoneElsesFilesAreRefusedWithoutForce) {
  fs::create_directory(root_ / "theirs");
  touch(root_ / "theirs" / "notes.txt");
  EXPECT_THROW((void)check_output_directory(root_ / "theirs", false), InputError);
  EXPECT_EQ(check_output_directory(root_ / "theirs", true), OutputMode::beside);
}

TEST_F(OutputDirectory, OnlyWhatTheMarkerListsCountsAsBarimpacts) {
  const fs::path d = root_ / "run";
  fs::create_directory(d);
  touch(d / "history.csv");
  write_output_marker(d, "run", {"history.csv"});
  EXPECT_TRUE(written_by_barimpact(d));
  EXPECT_EQ(check_output_directory(d, false), OutputMode::replace);
  touch(d / "notes.txt");
  EXPECT_FALSE(written_by_barimpact(d));
  EXPECT_THROW((void)check_output_directory(d, false), InputError);
  touch(d / output_marker, "not json");  // a marker barimpact did not write is no marker
  fs::remove(d / "notes.txt");
  EXPECT_FALSE(written_by_barimpact(d));
}

TEST_F(OutputDirectory, RootHomeAndParentsOfTheWorkingDirectoryAreRefusedEvenWithForce) {
  for (bool force : {false, true}) {
    EXPECT_THROW((void)check_output_directory("/", force), InputError);
    EXPECT_THROW((void)check_output_directory("..", force), InputError);
    EXPECT_THROW((void)check_output_directory(root_, force), InputError);
    EXPECT_THROW((void)check_output_directory(root_ / "cwd" / ".." / "..", force), InputError);
    const char* home = std::getenv("HOME");
    const std::string saved = home ? home : "";
    ::setenv("HOME", (root_ / "cwd" / "h").c_str(), 1);
    fs::create_directories(root_ / "cwd" / "h");
    EXPECT_THROW((void)check_output_directory(root_ / "cwd" / "h", force), InputError);
    EXPECT_THROW((void)check_output_directory(root_ / "cwd" / "h" / "", force), InputError);
    ::setenv("HOME", saved.c_str(), 1);
  }
  // The working directory itself: refused, or written beside with --force.
  EXPECT_THROW((void)check_output_directory(".", false), InputError);
  EXPECT_EQ(check_output_directory(".", true), OutputMode::beside);
}

TEST_F(OutputDirectory, ErrorsNameTheOptionAndTheRule) {
  fs::create_directory(root_ / "theirs");
  touch(root_ / "theirs" / "notes.txt");
  try {
    (void)check_output_directory(root_ / "theirs", false, "--out");
    FAIL();
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("--out"), std::string::npos);
    EXPECT_NE(what.find("notes.txt"), std::string::npos);
    EXPECT_NE(what.find("--force"), std::string::npos);
  }
}

TEST_F(OutputDirectory, StaleStagingOfDeadProcessesIsRemovedOnly) {
  auto staging = [&](const std::string& name) {
    fs::create_directory(root_ / name);
    touch(root_ / name / staging_flag);
  };
  staging(".out.partial-999999999");  // no such process
  staging(".out.partial-1");          // init: alive
  staging(".other.partial-999999999");
  fs::create_directory(root_ / ".out.old-999999999");  // no marker: not barimpact's old results
  touch(root_ / ".out.old-999999999" / "mine");
  remove_stale_staging(root_, "out");
  EXPECT_FALSE(fs::exists(root_ / ".out.partial-999999999"));
  EXPECT_TRUE(fs::exists(root_ / ".out.partial-1"));
  EXPECT_TRUE(fs::exists(root_ / ".other.partial-999999999"));
  EXPECT_TRUE(fs::exists(root_ / ".out.old-999999999" / "mine"));
  // Every name at once (a sweep's runs/); a user's look-alike files and directories stay.
  touch(root_ / ".notes.partial-999999999");
  fs::create_directory(root_ / ".draft.partial-77777777");
  touch(root_ / ".hidden");
  touch(root_ / ".a.partial-12x");
  remove_stale_staging(root_, "");
  EXPECT_FALSE(fs::exists(root_ / ".other.partial-999999999"));
  EXPECT_TRUE(fs::exists(root_ / ".notes.partial-999999999"));
  EXPECT_TRUE(fs::exists(root_ / ".draft.partial-77777777"));
  EXPECT_TRUE(fs::exists(root_ / ".hidden"));
  EXPECT_TRUE(fs::exists(root_ / ".a.partial-12x"));
  EXPECT_TRUE(fs::exists(root_ / ".out.partial-1"));
  remove_stale_staging(root_, "barimpact");  // names shorter than the prefix are passed over
}

TEST_F(OutputDirectory, ForceWritesBesideAndDeletesNothing) {
  const fs::path d = root_ / "theirs";
  fs::create_directory(d);
  touch(d / "notes.txt", "mine");
  touch(d / "history.csv", "an old file of the user's, replaced by name");
  const auto c = testing::example("paper-example1.toml", {"time.end=0.1", "output.fields_at=[]"});
  RunDirectory out(d, true);
  out.commit(c, run(c));
  EXPECT_EQ(directory_entries(d), (std::vector<std::string>{".barimpact", "case.toml", "fields.csv", "history.csv",
                                                            "notes.txt", "summary.json"}));
  std::ifstream notes(d / "notes.txt");
  std::string text;
  notes >> text;
  EXPECT_EQ(text, "mine");
  EXPECT_FALSE(written_by_barimpact(d));  // still the user's directory
}

// Issue 36: a directory holding only empty directories was taken for an
// empty one, and written into without --force.
TEST_F(OutputDirectory, EmptyDirectoriesOfTheUsersAreTheirs) {
  const fs::path d = root_ / "theirs";
  fs::create_directories(d / "a");
  fs::create_directories(d / "b" / "c");
  EXPECT_THROW((void)check_output_directory(d, false), InputError);
  EXPECT_EQ(check_output_directory(d, true), OutputMode::beside);
  // Inside a study's runs/ (listed, no marker of its own) only runs with a marker are barimpact's.
  const fs::path study = root_ / "study";
  fs::create_directories(study / "runs" / "r1");
  touch(study / "runs" / "r1" / "history.csv");
  write_output_marker(study / "runs" / "r1", "sweep", {"history.csv"});
  write_output_marker(study, "sweep", {"runs"});
  EXPECT_TRUE(written_by_barimpact(study));
  fs::create_directory(study / "runs" / "mine");
  EXPECT_FALSE(written_by_barimpact(study));
  EXPECT_THROW((void)check_output_directory(study, false), InputError);
}

// Issue 36: --force beside a directory named as a file barimpact writes (a
// study's convergence.md/) wrote three files before it failed.
TEST_F(OutputDirectory, AnEntryOfAnotherKindIsRefusedBeforeAnythingIsWritten) {
  const fs::path d = root_ / "theirs";
  fs::create_directories(d / "convergence.md");
  touch(d / "notes.txt");
  const std::vector<std::string> entries{"runs", "convergence.csv", "convergence.md"};
  try {
    prepare_output_directory(d, "converge", entries, true);
    ADD_FAILURE() << "accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("holds a directory convergence.md where barimpact writes a file"),
              std::string::npos)
        << e.what();
  }
  EXPECT_EQ(directory_entries(d), (std::vector<std::string>{"convergence.md", "notes.txt"}));
  fs::remove(d / "convergence.md");
  touch(d / "runs");
  EXPECT_THROW(prepare_output_directory(d, "converge", entries, true), InputError);
  EXPECT_EQ(directory_entries(d), (std::vector<std::string>{"notes.txt", "runs"}));
  fs::remove(d / "runs");
  fs::create_directory(d / "runs");  // a directory where one is written: fine
  EXPECT_NO_THROW(prepare_output_directory(d, "converge", entries, true));
}

// What the command reads: never written over, --force or not.
TEST_F(OutputDirectory, ADirectoryTheCommandReadsAndItsParentsAreRefusedEvenWithForce) {
  const fs::path run = root_ / "outer" / "run";
  fs::create_directories(run);
  touch(run / "history.csv");
  write_output_marker(run, "run", {"history.csv"});
  const CommandInputs reads{{}, {run}};
  for (bool force : {false, true}) {
    for (const auto& target : {run, root_ / "outer", root_ / "outer" / "run" / ".." / "run"}) {
      try {
        (void)check_output_directory(target, force, "--out", reads);
        ADD_FAILURE() << target << " accepted";
      } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("this command reads"), std::string::npos) << e.what();
      }
    }
  }
  EXPECT_EQ(check_output_directory(run / "figures", false, "--out", reads), OutputMode::create);  // inside it: fine
  EXPECT_EQ(check_output_directory(run, false), OutputMode::replace);  // read by no one: replaced
}

TEST_F(OutputDirectory, AnInputFileIsNeverReplacedNorTheDirectoryHoldingIt) {
  const fs::path run = root_ / "run";
  fs::create_directory(run);
  touch(run / "case.toml");
  write_output_marker(run, "run", {"case.toml"});
  const CommandInputs reads{{run / "case.toml"}, {}};
  EXPECT_THROW((void)check_output_directory(run / "case.toml", true, "--out", reads), InputError);
  for (bool force : {false, true}) EXPECT_THROW((void)check_output_directory(run, force, "--out", reads), InputError);
  // Beside the user's files it stays, by name.
  const CommandInputs theirs{{root_ / "cwd" / "case.toml"}, {}};
  touch(root_ / "cwd" / "case.toml");
  EXPECT_EQ(check_output_directory(".", true, "--out", theirs), OutputMode::beside);
  EXPECT_THROW(refuse_names_over_inputs(".", {"summary.json", "case.toml"}, theirs), InputError);
  EXPECT_NO_THROW(refuse_names_over_inputs(".", {"summary.json", "case.resolved.toml"}, theirs));
  fs::create_directories(root_ / "cwd" / "runs" / "a");
  const CommandInputs deep{{root_ / "cwd" / "runs" / "a" / "case.toml"}, {}};
  EXPECT_THROW(refuse_names_over_inputs(".", {"runs"}, deep), InputError);  // a study's runs/ holds it
  EXPECT_THROW(prepare_output_directory(".", "sweep", {"runs", "sweep.csv"}, true, "--out", deep), InputError);
  EXPECT_FALSE(fs::exists(root_ / "cwd" / output_marker));
}

TEST_F(OutputDirectory, TheCaseRunBesideItsResultsStaysAndTheResolvedOneGoesBesideIt) {
  const fs::path d = root_ / "cwd";
  touch(d / "case.toml", "# mine\n[time]\nend = 0.1\n");
  auto c = Case::from_file(d / "case.toml", {{"output.fields_at=[]"}});
  ASSERT_EQ(c.source, d / "case.toml");
  RunDirectory(d, true, "run", true, {{c.source}, {}}).commit(c, run(c));
  EXPECT_EQ(read_input_file(d / "case.toml", "case"), "# mine\n[time]\nend = 0.1\n");
  EXPECT_EQ(run_case_file(d), d / "case.resolved.toml");
  EXPECT_EQ(read_input_file(run_case_file(d), "case"), c.to_toml());
  ASSERT_TRUE(read_run_directory(d, c.to_toml()));
  // A later run whose input is elsewhere writes case.toml; the resolved case of before goes.
  fs::rename(d / "case.toml", root_ / "case.toml");
  c.source = root_ / "case.toml";
  RunDirectory(d, true, "run", true, {{c.source}, {}}).commit(c, run(c));
  EXPECT_FALSE(fs::exists(d / "case.resolved.toml"));
  EXPECT_EQ(run_case_file(d), d / "case.toml");
}

TEST_F(OutputDirectory, AnInputOfAnotherNameOfTheResultsIsRefusedAndNothingIsMoved) {
  const fs::path d = root_ / "cwd";
  touch(d / "summary.json", "my signal");
  const auto c = testing::example("paper-example1.toml", {"time.end=0.1", "output.fields_at=[]"});
  {
    RunDirectory out(d, true, "run", true, {{d / "summary.json"}, {}});
    EXPECT_THROW(out.commit(c, run(c)), InputError);
  }
  EXPECT_EQ(directory_entries(d), std::vector<std::string>{"summary.json"});
  EXPECT_EQ(read_input_file(d / "summary.json", "signal"), "my signal");
}

TEST_F(OutputDirectory, ARunDirectoryReadsBackBitForBit) {
  const auto c = testing::example("paper-example2.toml", {"output.fields_at=[]"});
  const auto result = run(c);
  RunDirectory out(root_ / "run");
  out.commit(c, result);
  const auto back = read_run_directory(root_ / "run", c.to_toml());
  ASSERT_TRUE(back);
  ASSERT_EQ(back->history.size(), result.history.size());
  for (std::size_t i = 0; i < result.history.size(); ++i) {
    EXPECT_EQ(back->history[i].U, result.history[i].U);
    EXPECT_EQ(back->history[i].D_visc, result.history[i].D_visc);
  }
  ASSERT_EQ(back->summary.contacts.size(), result.summary.contacts.size());
  EXPECT_EQ(back->summary.contacts.back().end, result.summary.contacts.back().end);
  EXPECT_EQ(back->summary.warnings, result.summary.warnings);
  EXPECT_FALSE(read_run_directory(root_ / "run", "another case"));
}

// output.format = "hdf5": results.h5 for history.csv and fields.csv, the
// marker listing it, and the history read back as written.
TEST_F(OutputDirectory, AnHdf5RunWritesResultsH5AndReadsBackBitForBit) {
  const auto c = testing::example("lines/saint-venant.toml", {"output.format=\"hdf5\"", "output.every=3"});
  ASSERT_EQ(c.output.format, OutputFormat::hdf5);
  const auto result = run(c);
  ASSERT_FALSE(result.columns.empty());
  RunDirectory out(root_ / "run");
  out.commit(c, result);
  EXPECT_EQ(directory_entries(root_ / "run"),
            (std::vector<std::string>{".barimpact", "case.toml", "results.h5", "summary.json"}));
  EXPECT_TRUE(written_by_barimpact(root_ / "run"));
  EXPECT_EQ(check_output_directory(root_ / "run", false), OutputMode::replace);

  const auto h = read_results_h5_history(root_ / "run" / "results.h5");
  ASSERT_EQ(h.names.size(), budget_columns.size() + result.columns.size());
  EXPECT_EQ(h.names.front(), "t");
  EXPECT_EQ(h.names.back(), result.columns.back());
  const auto back = read_run_directory(root_ / "run", c.to_toml());
  ASSERT_TRUE(back);
  EXPECT_EQ(back->columns, result.columns);
  ASSERT_EQ(back->history.size(), result.history.size());
  for (std::size_t k = 0; k < result.history.size(); ++k)
    for (const auto& b : budget_columns) ASSERT_EQ(back->history[k].*b.value, result.history[k].*b.value) << b.name;
  EXPECT_EQ(back->extra, result.extra);
  EXPECT_EQ(back->summary.contacts.size(), result.summary.contacts.size());
  // A file that is not one barimpact wrote: no run to resume.
  touch(root_ / "run" / "results.h5", "not hdf5");
  EXPECT_FALSE(read_run_directory(root_ / "run", c.to_toml()));
  EXPECT_THROW((void)read_results_h5_history(root_ / "run" / "results.h5"), std::runtime_error);
}

TEST_F(OutputDirectory, AResultsFileThatCannotBeWrittenIsOneLine) {
  const auto c =
      testing::example("paper-example1.toml", {"output.format=\"hdf5\"", "time.end=0.1", "output.fields_at=[]"});
  try {
    write_results_h5(root_ / "no" / "such" / "results.h5", c, run(c));
    FAIL() << "written";
  } catch (const OutputError& e) {  // the file system's refusal, by path and reason
    const std::string what = e.what();
    EXPECT_NE(what.find("results.h5: No such file or directory"), std::string::npos) << what;
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;
  }
}

// A small tmpfs mounted on `dir` for a test, unmounted with it; empty when
// it cannot be mounted (not root).
class SmallDisk {
 public:
  SmallDisk(const fs::path& dir, const char* size) : dir_(dir) {
    fs::create_directories(dir_);
    const std::string options = std::string("size=") + size;
    mounted_ = ::geteuid() == 0 && ::mount("tmpfs", dir_.c_str(), "tmpfs", 0, options.c_str()) == 0;
  }
  ~SmallDisk() {
    if (mounted_) ::umount2(dir_.c_str(), MNT_DETACH);
  }
  SmallDisk(const SmallDisk&) = delete;
  SmallDisk& operator=(const SmallDisk&) = delete;
  [[nodiscard]] bool mounted() const { return mounted_; }

 private:
  fs::path dir_;
  bool mounted_ = false;
};

// A full disk: one OutputError naming the file and the system's reason, the
// staging directory gone, a replaced file as it was (barimpact run's side:
// tests/cli/full_disk_test.sh).
TEST_F(OutputDirectory, AFullDiskIsOneRefusalAndLeavesNothingBehind) {
  const SmallDisk disk(root_ / "disk", "64k");
  if (!disk.mounted()) GTEST_SKIP() << "cannot mount a small tmpfs (needs root)";
  for (const char* format : {"csv", "hdf5"}) {
    const auto c = testing::example("paper-example1.toml", {fmt::format("output.format=\"{}\"", format)});
    try {
      RunDirectory out(root_ / "disk" / "run");
      out.commit(c, run(c));
      ADD_FAILURE() << format << ": written";
    } catch (const OutputError& e) {
      EXPECT_EQ(e.reason(), "No space left on device") << e.what();
      EXPECT_NE(std::string(e.what()).find((root_ / "disk" / "run").string()), std::string::npos) << e.what();
    }
    EXPECT_EQ(directory_entries(root_ / "disk"), std::vector<std::string>{}) << format;
  }
  write_text(root_ / "disk" / "table.csv", "kept\n");
  EXPECT_THROW(replace_text(root_ / "disk" / "table.csv", std::string(128 * 1024, 'x')), OutputError);
  EXPECT_EQ(directory_entries(root_ / "disk"), std::vector<std::string>{"table.csv"});
  std::ifstream table(root_ / "disk" / "table.csv");
  std::string text;
  table >> text;
  EXPECT_EQ(text, "kept");
}

}  // namespace
}  // namespace barimpact
