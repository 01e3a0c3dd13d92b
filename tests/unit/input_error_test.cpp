// Bad input's one exception (input_error.hpp): its message stays one line
// whatever it quotes, and an output error names the file and the reason.
#include "barimpact/model/input_error.hpp"

#include <gtest/gtest.h>

#include <string>

namespace barimpact {
namespace {

// Newlines and carriage returns as \n and \r, other control characters
// (and DEL) as \xNN; tabs and other text as they are.
TEST(InputError, ControlCharactersAreEscapedToKeepOneLine) {
  const InputError e(std::string("key \"a\nb\r\x01\x7f\"\tok \xC3\xA9"));
  EXPECT_EQ(std::string(e.what()), "key \"a\\nb\\r\\x01\\x7F\"\tok \xC3\xA9");
  EXPECT_EQ(std::string(InputError("plain").what()), "plain");
}

TEST(MemoryRefusal, IsBadInputWithItsOneLine) {
  const MemoryRefusal e("bar.elements: the run needs about 41 GB");
  const InputError& as_input = e;
  EXPECT_STREQ(as_input.what(), "bar.elements: the run needs about 41 GB");
}

TEST(OutputError, NamesTheFileAndTheSystemsReason) {
  const OutputError e("/tmp/out/history.csv", "No space left on device");
  EXPECT_EQ(std::string(e.what()), "cannot write /tmp/out/history.csv: No space left on device");
  EXPECT_EQ(e.path(), "/tmp/out/history.csv");
  EXPECT_EQ(e.reason(), "No space left on device");
  const OutputError own("--out o: full", "/tmp/out/x", "Disk quota exceeded");
  EXPECT_EQ(std::string(own.what()), "--out o: full");
  EXPECT_EQ(own.reason(), "Disk quota exceeded");
  // Caught as bad input: every command ends on it the same way.
  EXPECT_THROW(throw OutputError("/x", "y"), InputError);
}

}  // namespace
}  // namespace barimpact
