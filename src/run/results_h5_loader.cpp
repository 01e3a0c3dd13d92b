#include <fmt/format.h>

#include <string>
#include <system_error>
#include <utility>
#include <vector>

#include "barimpact/model/input_error.hpp"

#include "../model/module_loader.hpp"

#include "results_h5_module.hpp"

namespace barimpact {

namespace fs = std::filesystem;

namespace {

// Loaded the first time a results.h5 is written or read; a failure is
// reported each time (a thrown static initialisation is tried again).
const detail::Hdf5Module& hdf5_module() {
  static const detail::Hdf5Module* module = detail::load_module<detail::Hdf5Module, Hdf5Error>(
      BARIMPACT_HDF5_MODULE, detail::hdf5_module_entry, "results.h5", "HDF5 module");
  return *module;
}

}  // namespace

namespace detail {

namespace {

// What the file system refused, as the library reports it: the file and the system's reason.
template <class Work>
void refused_as_output(const fs::path& path, Work&& work) {
  try {
    work();
  } catch (const std::system_error& e) {
    throw OutputError(path, e.code().message());
  }
}

}  // namespace

ResultsH5File::ResultsH5File(fs::path path, const Case& c, std::size_t snapshots) : path_(std::move(path)) {
  refused_as_output(path_, [&] { file_ = hdf5_module().create(path_, c.output.compression, snapshots); });
}

ResultsH5File::~ResultsH5File() {
  file_.reset();  // every HDF5 handle closed before the file goes
  if (!finished_) {
    std::error_code ec;
    fs::remove(path_, ec);
  }
}

void ResultsH5File::append(const std::array<const double*, 4>& values, std::size_t nodes) {
  refused_as_output(path_, [&] { file_->append(values, nodes); });
}

void ResultsH5File::finish(const Case& c, const RunResult& result, const std::vector<double>& t) {
  refused_as_output(path_, [&] { file_->finish({c.to_toml(), c.units}, result, t); });
  finished_ = true;
}

}  // namespace detail

void write_results_h5(const fs::path& path, const Case& c, const RunResult& result) {
  const Fields& f = result.fields;
  detail::ResultsH5File out(path, c, f.count());
  for (std::size_t s = 0, n = f.nodes(); s < f.count(); ++s)
    out.append({f.u.data() + s * n, f.v.data() + s * n, f.sigma.data() + s * n, f.eps_p.data() + s * n}, n);
  out.finish(c, result, f.t);
}

HistoryColumns read_results_h5_history(const fs::path& path) {
  return hdf5_module().read_history(path);
}

}  // namespace barimpact
