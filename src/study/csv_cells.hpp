// The studies' CSV cells (sweep.csv, bearing.csv): numbers in their
// shortest exact form, "nan" for a missing one and "inf" for an infinite one
// (a refusal's blow count); text quoted, quotes doubled.
#pragma once

#include <fmt/format.h>

#include <cmath>
#include <string>

namespace barimpact::detail {

inline std::string csv_number(double v) {
  if (std::isnan(v)) return "nan";
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  return fmt::format("{}", v);
}

inline std::string csv_text(const std::string& s) {
  std::string out = "\"";
  for (char ch : s) out += ch == '"' ? std::string("\"\"") : std::string(1, ch);
  return out + "\"";
}

}  // namespace barimpact::detail
