// A fresh directory under the system's temporary one for the running test,
// named by the process and the test, removed with everything in it at the end.
#pragma once

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>

namespace barimpact::testing {

class ScratchDirectory {
 public:
  explicit ScratchDirectory(std::string_view stem)
      : path_(std::filesystem::temp_directory_path() /
              fmt::format("{}-{}-{}", stem, ::getpid(),
                          ::testing::UnitTest::GetInstance()->current_test_info()->name())) {
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~ScratchDirectory() { std::filesystem::remove_all(path_); }
  ScratchDirectory(const ScratchDirectory&) = delete;
  ScratchDirectory& operator=(const ScratchDirectory&) = delete;

  [[nodiscard]] const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

}  // namespace barimpact::testing
