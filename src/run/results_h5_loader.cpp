#include <dlfcn.h>
#include <fmt/format.h>

#include <string>
#include <system_error>
#include <utility>
#include <vector>

#include "barimpact/model/input_error.hpp"

#include "results_h5_module.hpp"

namespace barimpact {

namespace fs = std::filesystem;

namespace {

// Where the module may be, relative to the file holding this code (the
// command, the Python module, a test): beside it (the Python package),
// python/barimpact below it (a build tree's command) or beside it (a build
// tree's tests/ and bench/), the package from an installed command's bin/
// (as the command finds it for its figures); then the install prefix's
// package, by absolute path (other programs). No path of the build tree is
// compiled in: an installed library must not reach back into it.
std::vector<fs::path> module_candidates() {
  std::vector<fs::path> dirs;
  Dl_info info{};
  if (dladdr(reinterpret_cast<void*>(&module_candidates), &info) != 0 && info.dli_fname != nullptr) {
    // The main program's name is as it was started (relative to a working
    // directory the process may since have left): its own link names it whole.
    fs::path file(info.dli_fname);
    std::error_code ec;
    if (file.is_relative()) file = fs::read_symlink("/proc/self/exe", ec);
    const fs::path here = file.parent_path();
    // Debian's pip names the package's place dist-packages.
    std::string dist = BARIMPACT_PYTHON_FROM_BIN;
    if (const auto at = dist.rfind("site-packages"); at != std::string::npos) dist.replace(at, 13, "dist-packages");
    dirs = {here, here / "python" / "barimpact", here.parent_path() / "python" / "barimpact",
            here / BARIMPACT_PYTHON_FROM_BIN / "barimpact", here / dist / "barimpact"};
  }
  dirs.emplace_back(BARIMPACT_MODULE_INSTALL_DIR);
  for (auto& d : dirs) d /= BARIMPACT_HDF5_MODULE;
  return dirs;
}

const detail::Hdf5Module* load_module() {
  std::string tried;
  for (const fs::path& file : module_candidates()) {
    if (std::error_code ec; !fs::exists(file, ec)) continue;
    void* handle = dlopen(file.c_str(), RTLD_NOW | RTLD_LOCAL);  // never closed: loaded once per process
    if (handle == nullptr) {
      tried = dlerror();
      continue;
    }
    using Entry = const detail::Hdf5Module* (*)();
    if (auto entry = reinterpret_cast<Entry>(dlsym(handle, detail::hdf5_module_entry))) return entry();
    tried = fmt::format("{}: no {}", file.string(), detail::hdf5_module_entry);
  }
  throw Hdf5Error(
      fmt::format("results.h5 needs the HDF5 module {} ({})", BARIMPACT_HDF5_MODULE,
                  tried.empty() ? std::string("not found beside the program or its Python package") : tried));
}

// Loaded the first time a results.h5 is written or read; a failure is
// reported each time (a thrown static initialisation is tried again).
const detail::Hdf5Module& hdf5_module() {
  static const detail::Hdf5Module* module = load_module();
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
