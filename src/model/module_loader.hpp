// The library's modules (internal to src/): code built as a module of its
// own, with the libraries it links, that the library loads (dlopen) only
// when a process needs it, so that the others load neither: results.h5's
// HDF5 module (run/results_h5_loader.cpp), signal matching's fitting
// module (study/least_squares_loader.cpp).
#pragma once

#include <fmt/format.h>

#include <string>
#include <string_view>

namespace barimpact::detail {

/// A module's entry, `entry` in the module file `file_name`, from the first
/// place it is found: $BARIMPACT_MODULE_DIR if set, beside the program (or the Python module) holding
/// the library, in its build tree's python/barimpact, in the Python package
/// an installed command finds, then in the install prefix's package.
/// Loaded once per process (never closed). Null if there is none, with
/// `why` saying what was tried.
void* find_module_entry(const char* file_name, const char* entry, std::string& why);

/// What the module's entry gives (its table of functions), else Error, one
/// line: "<user> needs the <module> <file_name> (why)".
template <class Module, class Error>
const Module* load_module(const char* file_name, const char* entry, std::string_view user, std::string_view module) {
  std::string why;
  if (auto found = reinterpret_cast<const Module* (*)()>(find_module_entry(file_name, entry, why))) return found();
  throw Error(fmt::format("{} needs the {} {} ({})", user, module, file_name, why));
}

}  // namespace barimpact::detail
