#include "barimpact/model/input_error.hpp"

#include <fmt/format.h>

namespace barimpact {

namespace {

// `what` with its control characters escaped: one line, whatever input it quotes.
std::string one_line(const std::string& what) {
  std::string out;
  out.reserve(what.size());
  for (const char c : what) {
    const auto u = static_cast<unsigned char>(c);
    if (c == '\n')
      out += "\\n";
    else if (c == '\r')
      out += "\\r";
    else if ((u < 0x20 && c != '\t') || u == 0x7F)
      out += fmt::format("\\x{:02X}", u);
    else
      out += c;
  }
  return out;
}

}  // namespace

InputError::InputError(const std::string& what) : std::runtime_error(one_line(what)) {}

}  // namespace barimpact
