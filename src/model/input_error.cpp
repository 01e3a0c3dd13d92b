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

OutputError::OutputError(const std::filesystem::path& path, const std::string& reason)
    : OutputError(fmt::format("cannot write {}: {}", path.string(), reason), path, reason) {}

OutputError::OutputError(const std::string& what, const std::filesystem::path& path, const std::string& reason)
    : InputError(what), path_(path), reason_(reason) {}

}  // namespace barimpact
