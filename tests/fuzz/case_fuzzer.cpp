// Fuzz target: a case file's text through Case::from_string.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "fuzz_target.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  barimpact::fuzz::expect_parsed_or_refused([&] {
    const auto c = barimpact::Case::from_string(text, {}, "fuzz.toml");
    barimpact::fuzz::expect_round_trip(c);
  });
  return 0;
}
