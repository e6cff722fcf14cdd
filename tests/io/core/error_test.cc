#include "io/core/error.h"

#include <gtest/gtest.h>

#include <string>

namespace comic {
namespace {

TEST(Error, KeepsItsKindAndMessage) {
  const Error error(ErrorKind::kIo, "out.db: disk full");
  EXPECT_EQ(error.kind(), ErrorKind::kIo);
  EXPECT_STREQ(error.what(), "out.db: disk full");
}

// Issue 29: a message quoting a file's NUL byte was cut there (what() is a C string).
TEST(Error, ShowsNulBytesInsteadOfEndingTheMessageThere) {
  const char text[] = "calib.txt: bad number '7\0x' at";
  const Error error(ErrorKind::kInvalidData, std::string(text, sizeof(text) - 1));
  EXPECT_STREQ(error.what(), "calib.txt: bad number '7\\x00x' at");
  try {
    COMIC_CHECK(false, kInvalidData, "a" << '\0' << "b");
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(), "a\\x00b");
  }
}

}  // namespace
}  // namespace comic
