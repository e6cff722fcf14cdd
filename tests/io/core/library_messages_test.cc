#include "io/core/library_messages.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <stdexcept>

namespace comic::io {
namespace {

TEST(LibraryMessages, CapturesWhatIsWrittenToStderrAsOneLine) {
  const std::string captured = CaptureLibraryMessages([] {
    std::fprintf(stderr, "libpng error: Read Error\n");
    std::fprintf(stderr, "second\x01line\n");
  });
  EXPECT_EQ(captured, "libpng error: Read Error second\\x01line");
  EXPECT_EQ(CaptureLibraryMessages([] {}), "");
  EXPECT_EQ(
      CaptureLibraryMessages([] { std::fprintf(stderr, "[mjpeg @ 0x55eafc5bb040] overread 8\n"); }),
      "[mjpeg] overread 8");
}

TEST(LibraryMessages, RestoresStderrWhenTheBodyThrows) {
  EXPECT_THROW(CaptureLibraryMessages([] {
                 std::fprintf(stderr, "lost\n");
                 throw std::runtime_error("x");
               }),
               std::runtime_error);
  // stderr works again: a new capture sees only its own words.
  EXPECT_EQ(CaptureLibraryMessages([] { std::fprintf(stderr, "again\n"); }), "again");
}

TEST(LibraryMessages, TellsCorruptionFromHarmlessWarnings) {
  EXPECT_TRUE(MessageReportsCorruptData("Premature end of JPEG file"));
  EXPECT_TRUE(MessageReportsCorruptData("Corrupt JPEG data: 12 extraneous bytes"));
  EXPECT_TRUE(MessageReportsCorruptData("libpng error: Read Error"));
  EXPECT_TRUE(MessageReportsCorruptData("[mjpeg @ 0x55] overread 8"));
  EXPECT_FALSE(MessageReportsCorruptData("libpng warning: iCCP: known incorrect sRGB profile"));
  EXPECT_FALSE(MessageReportsCorruptData(""));
}

}  // namespace
}  // namespace comic::io
