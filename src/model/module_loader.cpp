#include "module_loader.hpp"

#include <dlfcn.h>
#include <fmt/format.h>

#include <cstdlib>
#include <filesystem>
#include <system_error>
#include <vector>

namespace barimpact::detail {

namespace fs = std::filesystem;

namespace {

// Where a module may be, relative to the file holding this code (the
// command, the Python module, a test): beside it (the Python package),
// python/barimpact below it (a build tree's command) or beside it (a build
// tree's tests/ and bench/), the package from an installed command's bin/
// (as the command finds it for its figures); then the install prefix's
// package, by absolute path (other programs). No path of the build tree is
// compiled in: an installed library must not reach back into it.
std::vector<fs::path> module_dirs() {
  std::vector<fs::path> dirs;
  Dl_info info{};
  if (dladdr(reinterpret_cast<void*>(&module_dirs), &info) != 0 && info.dli_fname != nullptr) {
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
  // First of all: a program using an install moved from its configured
  // prefix names the package's directory itself.
  if (const char* dir = std::getenv("BARIMPACT_MODULE_DIR"); dir != nullptr && *dir != '\0')
    dirs.insert(dirs.begin(), fs::path(dir));
  return dirs;
}

}  // namespace

void* find_module_entry(const char* file_name, const char* entry, std::string& why) {
  why.clear();
  for (const fs::path& dir : module_dirs()) {
    const fs::path file = dir / file_name;
    if (std::error_code ec; !fs::exists(file, ec)) continue;
    void* handle = dlopen(file.c_str(), RTLD_NOW | RTLD_LOCAL);  // never closed: loaded once per process
    if (handle == nullptr) {
      why = dlerror();
      continue;
    }
    if (void* found = dlsym(handle, entry)) return found;
    why = fmt::format("{}: no {}", file.string(), entry);
  }
  if (why.empty()) why = "not found beside the program or its Python package";
  return nullptr;
}

}  // namespace barimpact::detail
