// The one door through which the library reads TOML text (case files, --set
// values, sweep files), with the workarounds for Debian's toml++ 3.3 that
// keep every input either parsed or refused with InputError.
//
// Internal to src/: include it instead of <toml++/toml.h>.
#pragma once

// Debian's shared libtomlplusplus is built without assertions, and under GCC
// TOML_ASSERT_ASSUME is then nothing: a malformed table header such as "[#"
// breaks one of its preconditions (tomlplusplus#301) and is reported as a
// parse error. The fuzz build compiles toml++ from its headers; it keeps that
// behaviour instead of aborting in the assertion.
#if defined(TOML_HEADER_ONLY) && TOML_HEADER_ONLY && !defined(TOML_ASSERT)
#define TOML_ASSERT(expr) static_cast<void>(0)
#endif
#include <toml++/toml.h>

#include <string>
#include <string_view>

namespace barimpact {

/// Parses TOML text; throws InputError "origin:line:column: not valid TOML: ..."
/// (one line) for text toml++ rejects or must not be shown.
[[nodiscard]] toml::table parse_toml(std::string_view text, std::string_view origin);

/// What a value is, for messages: "a string", "an integer", "a float", ...
[[nodiscard]] std::string_view toml_type_name(const toml::node& node);

/// A value as TOML text ("[ 0.5, 'x' ]", "{ a = 1 }"), written without
/// toml++'s formatter, which sizes float arrays with size_t(log10(|x|)),
/// undefined for |x| < 1 (tomlplusplus#276).
[[nodiscard]] std::string toml_value_text(const toml::node& node);

}  // namespace barimpact
