// Fuzz target: a pile record file's text through PileRecord::from_string
// (the record's CSV file is not read).
#include <cstddef>
#include <cstdint>
#include <string>

#include "barimpact/pda/record.hpp"
#include "fuzz_target.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  barimpact::fuzz::expect_parsed_or_refused([&] {
    const auto r = barimpact::PileRecord::from_string(text, ".", "fuzz.toml");
    (void)r.depth_at(r.travel_time());
  });
  return 0;
}
