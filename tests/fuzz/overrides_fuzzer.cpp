// Fuzz target: a case file's text, then --set overrides. The input is the
// case text, a line "%%", then one override (section.key=value) per line;
// without that line it is all case text and there are no overrides.
#include <cstddef>
#include <cstdint>
#include <string_view>
#include <vector>

#include "fuzz_target.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::string_view text(reinterpret_cast<const char*>(data), size);
  std::vector<barimpact::Case::Override> overrides;
  std::string_view rest;
  if (text.starts_with("%%\n")) {
    rest = text.substr(3);
    text = {};
  } else if (const auto at = text.find("\n%%\n"); at != std::string_view::npos) {
    rest = text.substr(at + 4);
    text = text.substr(0, at);
  }
  while (!rest.empty()) {
    const auto end = rest.find('\n');
    if (const auto line = rest.substr(0, end); !line.empty()) overrides.push_back({std::string(line)});
    rest = end == std::string_view::npos ? std::string_view{} : rest.substr(end + 1);
  }
  barimpact::fuzz::expect_parsed_or_refused([&] {
    const auto c = barimpact::Case::from_string(text, overrides, "fuzz.toml");
    barimpact::fuzz::expect_round_trip(c);
  });
  return 0;
}
