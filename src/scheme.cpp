#include "barimpact/scheme.hpp"

#include <fmt/format.h>

#include "barimpact/paper_scheme.hpp"

namespace barimpact {

std::vector<std::string_view> scheme_names() {
  return {"paper"};
}

std::unique_ptr<Scheme> make_scheme(const Case& c) {
  if (c.time.scheme == "paper") return std::make_unique<PaperScheme>(c);
  throw InputError(fmt::format("time.scheme: unknown scheme \"{}\"", c.time.scheme));
}

}  // namespace barimpact
