// The HDF5 module's entry points (internal to src/run): results_h5.cpp is
// built as a module of its own, loaded (dlopen) by results_h5_loader.cpp
// the first time a run writes or reads a results.h5, so that a process
// that never does loads neither HDF5 nor the libraries it pulls in.
#pragma once

#include <array>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "barimpact/run/results_h5.hpp"

namespace barimpact::detail {

/// What a results.h5 holds of a run beside its result: the case's text and
/// its units.
struct Hdf5Case {
  std::string toml;
  std::string units;
};

/// A results.h5 being written (the module's side). Failures: a
/// std::system_error naming the file with the system's reason where the
/// file system refused a write, else Hdf5Error. Destroying it closes the
/// file and every handle of it (a file not finished is not whole).
class Hdf5Results {
 public:
  virtual ~Hdf5Results() = default;
  /// Appends one snapshot: its u, v, sigma and eps_p, `nodes` values each.
  virtual void append(const std::array<const double*, 4>& values, std::size_t nodes) = 0;
  /// Writes the case, the history and the fields' times `t`, rows and
  /// bodies, then closes the file whole.
  virtual void finish(const Hdf5Case& c, const RunResult& result, const std::vector<double>& t) = 0;
};

struct Hdf5Module {
  /// A new file at `path` (replaced if it exists), its fields gzipped at
  /// `compression`, chunked for `snapshots` of them.
  std::unique_ptr<Hdf5Results> (*create)(const std::filesystem::path& path, int compression, std::size_t snapshots);
  /// read_results_h5_history.
  HistoryColumns (*read_history)(const std::filesystem::path& path);
};

/// The module's one exported symbol.
inline constexpr const char* hdf5_module_entry = "barimpact_hdf5_module";

/// A results.h5 written as a run goes (the library's side): the module's,
/// its failures as the library's (OutputError naming the file and the
/// system's reason for what the file system refused, else Hdf5Error); the
/// file removed unless finished.
class ResultsH5File {
 public:
  /// Creates `path` for the run of `c`, chunked for `snapshots` of them.
  ResultsH5File(std::filesystem::path path, const Case& c, std::size_t snapshots);
  ~ResultsH5File();
  ResultsH5File(const ResultsH5File&) = delete;
  ResultsH5File& operator=(const ResultsH5File&) = delete;

  void append(const std::array<const double*, 4>& values, std::size_t nodes);
  void finish(const Case& c, const RunResult& result, const std::vector<double>& t);

 private:
  std::filesystem::path path_;
  std::unique_ptr<Hdf5Results> file_;
  bool finished_ = false;
};

}  // namespace barimpact::detail

extern "C" const barimpact::detail::Hdf5Module* barimpact_hdf5_module();
