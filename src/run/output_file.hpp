// The one way barimpact writes a file: every write checked (a short one
// continued, an interrupted one retried), close() flushing and closing
// explicitly and checking both, and a destructor that never throws and
// never reports. A file not closed whole is removed again, so that nothing
// half-written keeps a name. Every failure is an OutputError naming the
// file and the system's reason ("No space left on device").
#pragma once

#include <fmt/format.h>

#include <cstddef>
#include <filesystem>
#include <string_view>
#include <utility>

namespace barimpact::detail {

class OutputFile {
 public:
  /// Creates `path`, or truncates it.
  explicit OutputFile(std::filesystem::path path);
  /// Closes the file, and removes it unless close() succeeded; silent.
  ~OutputFile();
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;

  template <class... T>
  void print(fmt::format_string<T...> format, T&&... args) {
    fmt::format_to(fmt::appender(buffer_), format, std::forward<T>(args)...);
    if (buffer_.size() >= flush_size) flush();
  }
  void write(std::string_view bytes);
  /// Writes what is buffered and closes the file: it is whole.
  void close();

 private:
  static constexpr std::size_t flush_size = 64 * 1024;
  void flush();
  void write_out(const char* data, std::size_t size);

  std::filesystem::path path_;
  int fd_ = -1;
  bool closed_ = false;
  fmt::memory_buffer buffer_;
};

/// Writes `text` to `staged` (a hidden name beside `target`), then renames
/// it over `target`: a reader, or an interruption, never sees half of it.
/// Throws OutputError naming `target`; `staged` is gone by then.
void replace_file(const std::filesystem::path& staged, const std::filesystem::path& target, std::string_view text);

}  // namespace barimpact::detail
