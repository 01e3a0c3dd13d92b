#include "barimpact/schemes/simd.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <atomic>
#include <cstdlib>
#include <string>

#include "barimpact/model/input_error.hpp"

namespace barimpact {

namespace {

constexpr SimdPath all_paths[] = {SimdPath::scalar, SimdPath::sse2, SimdPath::avx2};

bool runs_here(SimdPath path) {
  switch (path) {
    case SimdPath::scalar:
      return true;
    case SimdPath::sse2:
#if defined(BARIMPACT_SIMD_X86)
      return true;  // part of x86-64
#else
      return false;
#endif
    case SimdPath::avx2:
#if defined(BARIMPACT_SIMD_X86)
      return __builtin_cpu_supports("avx2");  // the processor's and the system's (XSAVE) support
#else
      return false;
#endif
  }
  return false;
}

std::string supported_names() {
  std::vector<std::string_view> names;
  for (SimdPath p : supported_simd_paths()) names.push_back(to_string(p));
  return fmt::format("{}", fmt::join(names, ", "));
}

SimdPath checked(SimdPath path, std::string_view source) {
  if (!runs_here(path))
    throw InputError(fmt::format("{}: this processor cannot run the {} path (it runs: {})", source, to_string(path),
                                 supported_names()));
  return path;
}

// BARIMPACT_SIMD, read once; else the widest path.
SimdPath chosen_path() {
  const char* env = std::getenv("BARIMPACT_SIMD");
  if (env == nullptr || *env == '\0') return supported_simd_paths().back();
  const std::string name = env;
  for (SimdPath p : all_paths)
    if (to_string(p) == name) return checked(p, fmt::format("BARIMPACT_SIMD={}", name));
  throw InputError(fmt::format("BARIMPACT_SIMD={}: must be one of scalar, sse2, avx2 (this processor runs: {})", name,
                               supported_names()));
}

std::atomic<int> forced{-1};

}  // namespace

std::string_view to_string(SimdPath path) {
  switch (path) {
    case SimdPath::scalar:
      return "scalar";
    case SimdPath::sse2:
      return "sse2";
    case SimdPath::avx2:
      return "avx2";
  }
  return "?";
}

std::vector<SimdPath> supported_simd_paths() {
  std::vector<SimdPath> out;
  for (SimdPath p : all_paths)
    if (runs_here(p)) out.push_back(p);
  return out;
}

SimdPath simd_path() {
  if (const int f = forced.load(); f >= 0) return static_cast<SimdPath>(f);
  static const SimdPath chosen = chosen_path();  // a bad BARIMPACT_SIMD throws on every call
  return chosen;
}

void force_simd_path(std::optional<SimdPath> path) {
  if (path) (void)checked(*path, "force_simd_path");
  forced.store(path ? static_cast<int>(*path) : -1);
}

}  // namespace barimpact
