#include "io/core/input_file.h"

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "io/core/error.h"
#include "io/core/file_utils.h"
#include "tests/test_support.h"

namespace comic::io {
namespace {

using comic::test::ScopedTempDir;

TEST(InputFile, StreamPathsAreTheShellsDescriptors) {
  EXPECT_TRUE(IsStreamPath("/dev/fd/63"));
  EXPECT_TRUE(IsStreamPath("/proc/self/fd/3"));
  EXPECT_TRUE(IsStreamPath("/dev/stdin"));
  EXPECT_FALSE(IsStreamPath("/tmp/fifo"));
  EXPECT_FALSE(IsStreamPath("fd/63"));
}

// A named FIFO blocks open() until a writer comes: refused from stat alone, at once.
TEST(InputFile, AFifoIsRefusedWithoutOpeningIt) {
  ScopedTempDir dir;
  const std::string fifo = dir.File("calib.txt");
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0644), 0);
  try {
    CheckInputFile(fifo);
    FAIL() << "not refused";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::kInvalidData);
    EXPECT_EQ(std::string(e.what()), fifo +
                                         ": not a regular file (a FIFO); refusing to read it, "
                                         "which could block forever");
  }
  EXPECT_THROW(ReadFileToString(fifo), Error);
  EXPECT_THROW(CheckInputFile("/dev/null"), Error);  // a device
  EXPECT_THROW(CheckInputFile(dir.File("missing")), Error);
  EXPECT_THROW(CheckInputFile(dir.path()), Error);
}

// Process substitution hands over a pipe as /dev/fd/N: read, once.
TEST(InputFile, APipeAsDevFdIsReadOnce) {
  int ends[2];
  ASSERT_EQ(::pipe(ends), 0);
  const std::string text = "700 700 613 185\n";
  ASSERT_EQ(::write(ends[1], text.data(), text.size()), static_cast<ssize_t>(text.size()));
  ::close(ends[1]);
  const std::string path = "/dev/fd/" + std::to_string(ends[0]);
  EXPECT_NO_THROW(CheckInputFile(path));
  EXPECT_EQ(ReadFileToString(path), text);
  ::close(ends[0]);
}

}  // namespace
}  // namespace comic::io
