#include "output_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <system_error>

#include "barimpact/model/input_error.hpp"

namespace barimpact::detail {

namespace fs = std::filesystem;

namespace {

[[noreturn]] void refuse(const fs::path& path, int error) {
  throw OutputError(path, std::system_category().message(error));
}

}  // namespace

OutputFile::OutputFile(fs::path path) : path_(std::move(path)) {
  do {
    fd_ = ::open(path_.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
  } while (fd_ < 0 && errno == EINTR);
  if (fd_ < 0) refuse(path_, errno);
}

OutputFile::~OutputFile() {
  if (fd_ >= 0) ::close(fd_);
  if (!closed_) ::unlink(path_.c_str());
}

void OutputFile::write(std::string_view bytes) {
  if (buffer_.size() + bytes.size() < flush_size) {
    buffer_.append(bytes.data(), bytes.data() + bytes.size());
    return;
  }
  flush();
  write_out(bytes.data(), bytes.size());
}

void OutputFile::flush() {
  write_out(buffer_.data(), buffer_.size());
  buffer_.clear();
}

void OutputFile::write_out(const char* data, std::size_t size) {
  while (size > 0) {
    const ssize_t n = ::write(fd_, data, size);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) refuse(path_, n < 0 ? errno : EIO);
    data += n;
    size -= static_cast<std::size_t>(n);
  }
}

void OutputFile::close() {
  flush();
  const int fd = std::exchange(fd_, -1);
  // Linux releases the descriptor even when close is interrupted: not a failure.
  if (::close(fd) != 0 && errno != EINTR) refuse(path_, errno);
  closed_ = true;
}

void replace_file(const fs::path& staged, const fs::path& target, std::string_view text) {
  try {
    OutputFile out(staged);
    out.write(text);
    out.close();
  } catch (const OutputError& e) {
    throw OutputError(target, e.reason());
  }
  std::error_code ec;
  fs::rename(staged, target, ec);
  if (ec) {
    std::error_code ignored;
    fs::remove(staged, ignored);
    throw OutputError(target, ec.message());
  }
}

}  // namespace barimpact::detail
