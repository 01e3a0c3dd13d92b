// What every fuzz target asserts about the input layer (case files, --set
// overrides, sweep files): any input either parses or is refused with
// barimpact::InputError whose what() is one non-empty line (the command
// line prints it and exits with status 2).
//
// Everything else is a finding and aborts: a crash, a sanitizer report, a
// leak, a hang, and any other exception, std::exception or not. No standard
// exception is an acceptable answer to bad input: std::bad_alloc means the
// input was not bounded before memory was spent on it, std::out_of_range,
// std::invalid_argument, std::length_error, std::ios_base::failure, a
// toml::parse_error or mu::ParserError escaping means a check is missing (the
// command line would exit 1, "internal error", instead of naming the key).
//
// A case that parses must also survive its own resolved form: to_toml() is
// promised to reproduce the case exactly, so it is parsed again and compared.
#pragma once

#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>
#include <string_view>
#include <typeinfo>

#include "barimpact/case/case.hpp"

namespace barimpact::fuzz {

[[noreturn]] inline void finding(std::string_view what, std::string_view detail) {
  std::fprintf(stderr, "fuzz finding: %.*s: %.*s\n", static_cast<int>(what.size()), what.data(),
               static_cast<int>(detail.size()), detail.data());
  std::abort();
}

// Runs `parse`; InputError with a one-line message is the only acceptable failure.
template <class F>
void expect_parsed_or_refused(F&& parse) {
  try {
    parse();
  } catch (const InputError& e) {
    const std::string_view what = e.what();
    if (what.empty()) finding("InputError with an empty message", "");
    if (what.find_first_of("\n\r") != std::string_view::npos) finding("InputError message is not one line", what);
  } catch (const std::exception& e) {
    finding(typeid(e).name(), e.what());
  } catch (...) {
    finding("a non-standard exception", "");
  }
}

// The resolved case reads back as the same case.
inline void expect_round_trip(const Case& c) {
  const std::string resolved = c.to_toml();
  try {
    const Case again = Case::from_string(resolved, {}, "resolved");
    if (again.to_toml() != resolved) finding("resolved case reads back differently", resolved);
    if (again.step_count() != c.step_count()) finding("resolved case has another step count", resolved);
  } catch (const InputError& e) {
    finding("resolved case is refused", std::string(e.what()) + "\n" + resolved);
  }
}

}  // namespace barimpact::fuzz
