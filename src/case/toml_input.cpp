#include "toml_input.hpp"

#include <fmt/format.h>

#include <cstddef>
#include <sstream>

#include "barimpact/case/case.hpp"

namespace barimpact {

namespace {

// toml++ 3.3 asks whether a non-ASCII character is whitespace with a table
// that reaches __builtin_unreachable for most code points (U+00A1..U+0499,
// U+2C5E..U+3057, U+FB26..U+FEFE; tomlplusplus#190, #295): undefined
// behaviour wherever the parser meets one outside a string value or a
// comment: in a key (even quoted: keys are recorded for error messages), in
// a bare value, between tokens, and after a backslash in a multi-line basic
// string. The case and sweep keys are ASCII and TOML allows nothing else
// there, so those places are refused here, before toml++ sees the text.
//
// A small reader of TOML's layout finds the string values and comments; where
// the text stops making sense to it (invalid TOML, which toml++ refuses too)
// it stops trusting quotes and '#', and every later non-ASCII byte is refused.
class NonAsciiGuard {
 public:
  NonAsciiGuard(std::string_view text, std::string_view origin) : t_(text), origin_(origin) {}

  void check() {
    if (t_.starts_with("\xEF\xBB\xBF")) i_ = 3;  // toml++ skips a byte order mark
    while (!done()) {
      blanks();
      const char c = peek();
      if (c == '\n' || c == '\r') {
        ++i_;
      } else if (c == '#') {
        comment();
      } else if (c == '[') {
        const bool array = peek(1) == '[';
        i_ += array ? 2 : 1;
        if (!key() || peek() != ']' || (array && peek(1) != ']')) return rest_ascii();
        i_ += array ? 2 : 1;
        if (!line_end()) return rest_ascii();
      } else {
        if (!key() || peek() != '=') return rest_ascii();
        ++i_;
        if (!value() || !line_end()) return rest_ascii();
      }
    }
  }

 private:
  [[nodiscard]] bool done() const { return i_ >= t_.size(); }
  [[nodiscard]] char peek(std::size_t k = 0) const { return i_ + k < t_.size() ? t_[i_ + k] : '\0'; }
  [[nodiscard]] bool starts(std::string_view s) const { return !done() && t_.substr(i_).starts_with(s); }
  static bool ascii(char c) { return static_cast<unsigned char>(c) < 0x80; }
  static bool bare_key(char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' || c == '-';
  }
  static bool digit(char c) { return c >= '0' && c <= '9'; }

  [[noreturn]] void fail(std::string_view where) const {
    std::size_t line = 1, column = 1;
    for (std::size_t k = 0; k < i_; ++k) {
      if (t_[k] == '\n') {
        line += 1;
        column = 1;
      } else if ((static_cast<unsigned char>(t_[k]) & 0xC0) != 0x80) {
        column += 1;  // characters, not UTF-8 continuation bytes
      }
    }
    throw InputError(fmt::format("{}:{}:{}: not valid TOML: a non-ASCII character {}", origin_, line, column, where));
  }

  void need_ascii(std::string_view where) const {
    if (!done() && !ascii(peek())) fail(where);
  }

  void blanks() {
    while (peek() == ' ' || peek() == '\t') ++i_;
  }

  void comment() {
    while (!done() && peek() != '\n') ++i_;
  }

  // Blanks, line breaks and comments, as inside an array.
  void gaps() {
    for (;;) {
      blanks();
      if (peek() == '\n' || peek() == '\r')
        ++i_;
      else if (peek() == '#')
        comment();
      else
        return;
    }
  }

  bool line_end() {
    blanks();
    if (peek() == '#') comment();
    if (peek() == '\r') ++i_;
    if (done()) return true;
    if (peek() != '\n') return false;
    ++i_;
    return true;
  }

  // A dotted key: every byte ASCII, quoted parts included.
  bool key() {
    for (;;) {
      blanks();
      const char q = peek();
      if (q == '"' || q == '\'') {
        ++i_;
        for (;;) {
          need_ascii("in a key");
          if (done() || peek() == '\n') return false;
          const char c = t_[i_++];
          if (c == q) break;
          if (c == '\\' && q == '"') {
            need_ascii("in a key");
            ++i_;
          }
        }
      } else if (bare_key(q)) {
        while (bare_key(peek())) ++i_;
      } else {
        need_ascii("in a key");
        return false;
      }
      blanks();
      need_ascii("after a key");
      if (peek() != '.') return true;
      ++i_;
    }
  }

  bool value() {
    blanks();
    if (starts("\"\"\"")) return multi_line_basic();
    if (starts("\'\'\'")) return multi_line_literal();
    const char c = peek();
    if (c == '"' || c == '\'') return single_line(c);
    if (c == '[') {
      ++i_;
      return array();
    }
    if (c == '{') {
      ++i_;
      return inline_table();
    }
    // A number, boolean, date or time: ASCII up to a value terminator.
    const std::size_t start = i_;
    for (;;) {
      need_ascii("outside a string or comment");
      const char b = peek();
      if (done() || b == '\n' || b == '\r' || b == ',' || b == ']' || b == '}' || b == '#') break;
      if (b == ' ' || b == '\t') {
        // "1979-05-27 07:32:00": a date and a time are one value.
        const bool date = i_ - start == 10 && t_[start + 4] == '-' && t_[start + 7] == '-';
        if (!(b == ' ' && date && digit(peek(1)))) break;
      }
      ++i_;
    }
    return i_ > start;
  }

  bool single_line(char q) {
    ++i_;
    while (!done()) {
      const char c = t_[i_++];
      if (c == '\n') return false;
      if (c == q) return true;
      if (c == '\\' && q == '"') ++i_;  // toml++ refuses a non-ASCII escape without classifying it
    }
    return false;
  }

  // Up to two more quotes belong to the string: """a""""" is a"".
  void closing_quotes(char q) {
    std::size_t n = 3;
    while (n < 5 && peek(n) == q) ++n;
    i_ += n;
  }

  bool multi_line_basic() {
    i_ += 3;
    while (!done()) {
      if (starts("\"\"\"")) {
        closing_quotes('"');
        return true;
      }
      if (peek() != '\\') {
        ++i_;
        continue;
      }
      ++i_;
      need_ascii("after a backslash");
      const char e = peek();
      if (e == ' ' || e == '\t' || e == '\r' || e == '\n') {
        // A line-ending backslash: toml++ then classifies the first character
        // after the whitespace and line breaks.
        while (peek() == ' ' || peek() == '\t' || peek() == '\r' || peek() == '\n') ++i_;
        need_ascii("after a line-ending backslash");
      } else {
        ++i_;
      }
    }
    return false;
  }

  bool multi_line_literal() {
    i_ += 3;
    while (!done()) {
      if (starts("\'\'\'")) {
        closing_quotes('\'');
        return true;
      }
      ++i_;
    }
    return false;
  }

  bool array() {
    for (;;) {
      gaps();
      if (peek() == ']') {
        ++i_;
        return true;
      }
      if (!value()) return false;
      gaps();
      if (peek() == ',') {
        ++i_;
      } else if (peek() == ']') {
        ++i_;
        return true;
      } else {
        return false;
      }
    }
  }

  bool inline_table() {
    blanks();
    if (peek() == '}') {
      ++i_;
      return true;
    }
    for (;;) {
      if (!key() || peek() != '=') return false;
      ++i_;
      if (!value()) return false;
      blanks();
      if (peek() == ',') {
        ++i_;
      } else if (peek() == '}') {
        ++i_;
        return true;
      } else {
        return false;
      }
    }
  }

  // Past what this reader understands, trust nothing.
  void rest_ascii() {
    for (; !done(); ++i_) need_ascii("after text that is not valid TOML");
  }

  std::string_view t_;
  std::string_view origin_;
  std::size_t i_ = 0;
};

}  // namespace

std::string toml_value_text(const toml::node& node) {
  std::string out;
  if (const auto* array = node.as_array()) {
    for (const auto& e : *array) out += (out.empty() ? "[ " : ", ") + toml_value_text(e);
    return out.empty() ? "[]" : out + " ]";
  }
  if (const auto* table = node.as_table()) {
    for (auto&& [key, value] : *table) {
      const std::string_view k = key.str();
      const bool bare = !k.empty() && k.find_first_not_of(
                                          "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                                          "0123456789_-") == std::string_view::npos;
      out += (out.empty() ? "{ " : ", ") + (bare ? std::string(k) : toml_value_text(toml::value<std::string>(k))) +
             " = " + toml_value_text(value);
    }
    return out.empty() ? "{}" : out + " }";
  }
  std::ostringstream text;  // a single value: printed without the formatter's column count
  node.visit([&](auto&& v) { text << v; });
  return text.str();
}

toml::table parse_toml(std::string_view text, std::string_view origin) {
  NonAsciiGuard(text, origin).check();
  try {
    return toml::parse(text, origin);
  } catch (const toml::parse_error& e) {
    throw InputError(fmt::format("{}:{}:{}: not valid TOML: {}", origin, e.source().begin.line, e.source().begin.column,
                                 e.description()));
  }
}

std::string_view toml_type_name(const toml::node& node) {
  switch (node.type()) {
    case toml::node_type::string:
      return "a string";
    case toml::node_type::integer:
      return "an integer";
    case toml::node_type::floating_point:
      return "a float";
    case toml::node_type::boolean:
      return "a boolean";
    case toml::node_type::array:
      return "an array";
    case toml::node_type::table:
      return "a table";
    default:
      return "a date or time";
  }
}

}  // namespace barimpact
