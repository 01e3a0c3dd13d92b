// The reader of a setup file's sections and keys (a Hopkinson setup, a pile
// record): every key checked against the file's contract, every refusal one
// line "origin:line: section.key rule".
//
// Internal to src/.
#pragma once

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "../case/quantity.hpp"
#include "../case/toml_input.hpp"
#include "barimpact/model/input_error.hpp"

namespace barimpact {

/// A section of a setup file's contract and its keys.
struct SectionKeys {
  std::string_view section;
  std::vector<std::string_view> keys;
};

/// Reads the keys of one parsed setup file; every message is "origin:line: section.key rule".
class SetupReader {
 public:
  SetupReader(toml::table root, std::string origin, std::vector<SectionKeys> contract)
      : root_(std::move(root)), origin_(std::move(origin)), contract_(std::move(contract)) {}

  [[noreturn]] void fail(std::string_view section, std::string_view key, std::string_view rule) const {
    throw InputError(fmt::format("{}: {}.{} {}", where(section, key), section, key, rule));
  }

  [[noreturn]] void fail_section(std::string_view section, std::string_view rule) const {
    const auto* t = root_.get(section);
    throw InputError(fmt::format("{}: [{}] {}", t ? located(*t) : origin_, section, rule));
  }

  void check_layout() const {
    std::vector<std::string_view> names;
    for (const auto& s : contract_) names.push_back(s.section);
    for (auto&& [name, value] : root_) {
      const std::string_view section = name.str();  // clang 14 cannot capture a structured binding
      const auto it =
          std::find_if(contract_.begin(), contract_.end(), [&](const SectionKeys& s) { return s.section == section; });
      if (it == contract_.end())
        throw InputError(
            fmt::format("{}: unknown section [{}] (known: {})", located(value), name.str(), fmt::join(names, ", ")));
      if (!value.is_table())
        throw InputError(
            fmt::format("{}: {} must be a section [{}], not a value", located(value), name.str(), name.str()));
      for (auto&& [key, v] : *value.as_table())
        if (std::find(it->keys.begin(), it->keys.end(), key.str()) == it->keys.end())
          throw InputError(fmt::format("{}: unknown key {}.{} (known in [{}]: {})", located(v), name.str(), key.str(),
                                       name.str(), fmt::join(it->keys, ", ")));
    }
  }

  [[nodiscard]] bool has(std::string_view section, std::string_view key) const { return node(section, key); }
  [[nodiscard]] bool has_section(std::string_view section) const { return root_.get(section) != nullptr; }

  [[nodiscard]] std::optional<double> number(std::string_view section, std::string_view key) const {
    const auto* n = node(section, key);
    if (n == nullptr) return std::nullopt;
    return one_number(section, key, *n);
  }

  /// A number in SI, or a text of a number and a unit of `d` ("210 GPa"), converted to SI.
  [[nodiscard]] std::optional<double> quantity(std::string_view section, std::string_view key, Dimension d) const {
    const auto* n = node(section, key);
    if (n == nullptr || !n->is_string()) return number(section, key);
    std::string why;
    const auto v = si_value(n->as_string()->get(), d, why);
    if (!v) fail(section, key, why);
    return v;
  }

  // A number > 0 (when given); with a dimension, also a number and a unit of it.
  [[nodiscard]] std::optional<double> positive(std::string_view section, std::string_view key,
                                               std::optional<Dimension> d = std::nullopt) const {
    const auto v = d ? quantity(section, key, *d) : number(section, key);
    if (v && !(*v > 0)) fail(section, key, fmt::format("must be > 0 (got {})", *v));
    return v;
  }

  [[nodiscard]] std::optional<std::string> word(std::string_view section, std::string_view key) const {
    const auto* n = node(section, key);
    if (n == nullptr) return std::nullopt;
    if (const auto* s = n->as_string()) return s->get();
    fail(section, key, fmt::format("must be a string (got {})", toml_type_name(*n)));
  }

  [[nodiscard]] std::optional<bool> boolean(std::string_view section, std::string_view key) const {
    const auto* n = node(section, key);
    if (n == nullptr) return std::nullopt;
    if (const auto* b = n->as_boolean()) return b->get();
    fail(section, key, fmt::format("must be true or false (got {})", toml_type_name(*n)));
  }

  // A string or a non-empty array of strings.
  [[nodiscard]] std::vector<std::string> words(std::string_view section, std::string_view key) const {
    const auto* n = node(section, key);
    std::vector<std::string> out;
    if (n == nullptr) return out;
    if (const auto* s = n->as_string()) return {s->get()};
    const auto* a = n->as_array();
    if (a == nullptr)
      fail(section, key, fmt::format("must be a string or an array of strings (got {})", toml_type_name(*n)));
    for (const auto& e : *a) {
      const auto* s = e.as_string();
      if (s == nullptr) fail(section, key, fmt::format("must be an array of strings (found {})", toml_type_name(e)));
      if (s->get().empty()) fail(section, key, "must not hold an empty name");
      out.push_back(s->get());
    }
    if (out.empty()) fail(section, key, "must name at least one");
    return out;
  }

  // [lo, hi] with lo < hi.
  [[nodiscard]] std::optional<std::pair<double, double>> range(std::string_view section, std::string_view key) const {
    const auto* n = node(section, key);
    if (n == nullptr) return std::nullopt;
    const auto* a = n->as_array();
    if (a == nullptr || a->size() != 2) fail(section, key, "must be [lo, hi], two numbers");
    const double lo = one_number(section, key, (*a)[0]);
    const double hi = one_number(section, key, (*a)[1]);
    if (!(lo < hi)) fail(section, key, fmt::format("must have lo < hi (got [{}, {}])", lo, hi));
    return std::pair{lo, hi};
  }

  [[nodiscard]] const std::string& origin() const { return origin_; }

 private:
  const toml::node* node(std::string_view section, std::string_view key) const {
    const auto* t = root_.get_as<toml::table>(section);
    return t ? t->get(key) : nullptr;
  }

  double one_number(std::string_view section, std::string_view key, const toml::node& n) const {
    double v = 0.0;
    if (const auto* i = n.as_integer())
      v = static_cast<double>(i->get());
    else if (const auto* f = n.as_floating_point())
      v = f->get();
    else
      fail(section, key, fmt::format("must be a number (got {})", toml_type_name(n)));
    if (!std::isfinite(v)) fail(section, key, fmt::format("must be a finite number (got {})", v));
    return v;
  }

  std::string where(std::string_view section, std::string_view key) const {
    if (const auto* n = node(section, key)) return located(*n);
    if (const auto* t = root_.get(section)) return located(*t);
    return origin_;
  }

  std::string located(const toml::node& n) const {
    const auto& src = n.source();
    return src.begin.line == 0 ? origin_ : fmt::format("{}:{}", origin_, src.begin.line);
  }

  toml::table root_;
  std::string origin_;
  std::vector<SectionKeys> contract_;
};

/// A CSV file's `delimiter` (one character) and `skip_rows` (lines before
/// the header) in `section`, when given.
inline void read_delimiter_and_skip_rows(const SetupReader& r, std::string_view s, char& delimiter, int& skip_rows) {
  if (const auto d = r.word(s, "delimiter")) {
    if (d->size() != 1 || *d == "\"" || *d == "\n" || *d == "\r")
      r.fail(s, "delimiter", fmt::format("must be one character such as \",\", \";\" or \"\\t\" (got \"{}\")", *d));
    delimiter = (*d)[0];
  }
  if (const auto k = r.number(s, "skip_rows")) {
    if (!(*k >= 0) || *k != std::floor(*k) || *k > 1e6)
      r.fail(s, "skip_rows", fmt::format("must be a whole number of lines >= 0 (got {})", *k));
    skip_rows = static_cast<int>(*k);
  }
}

}  // namespace barimpact
