// The HDF5 module's entry points (internal to src/run): results_h5.cpp is
// built as a module of its own, loaded (dlopen) by results_h5_loader.cpp
// the first time a run writes or reads a results.h5, so that a process
// that never does loads neither HDF5 nor the libraries it pulls in.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "barimpact/run/results_h5.hpp"

namespace barimpact::detail {

/// What a results.h5 holds of a run beside its result: the case's text,
/// its units and the fields' gzip level.
struct Hdf5Case {
  std::string toml;
  std::string units;
  int compression = 1;
};

struct Hdf5Module {
  /// The bytes of the file write_results_h5 writes at `path` (which names it
  /// in errors); throws Hdf5Error.
  std::vector<char> (*image)(const std::filesystem::path& path, const Hdf5Case& c, const RunResult& result,
                            const StreamedSnapshots* streamed);
  /// read_results_h5_history.
  HistoryColumns (*read_history)(const std::filesystem::path& path);
};

/// The module's one exported symbol.
inline constexpr const char* hdf5_module_entry = "barimpact_hdf5_module";

}  // namespace barimpact::detail

extern "C" const barimpact::detail::Hdf5Module* barimpact_hdf5_module();
