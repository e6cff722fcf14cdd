#include "io/core/staged_files.h"

#include <gtest/gtest.h>

#include <filesystem>

#include "io/core/error.h"
#include "io/core/file_utils.h"
#include "tests/test_support.h"

namespace comic::io {
namespace {

int CountEntries(const std::string& folder) {
  int n = 0;
  for ([[maybe_unused]] const auto& entry : std::filesystem::directory_iterator(folder)) ++n;
  return n;
}

TEST(StagedFiles, AllAppearAtCommit) {
  test::ScopedTempDir dir;
  StagedFiles files;
  WriteFileAtomically(files.Stage(dir.File("a.json")), "a");
  WriteFileAtomically(files.Stage(dir.File("b.txt")), "b");
  EXPECT_FALSE(PathExists(dir.File("a.json")));
  EXPECT_FALSE(PathExists(dir.File("b.txt")));
  files.Commit();
  EXPECT_EQ(ReadFileToString(dir.File("a.json")), "a");
  EXPECT_EQ(ReadFileToString(dir.File("b.txt")), "b");
  EXPECT_EQ(CountEntries(dir.path()), 2);
}

TEST(StagedFiles, AFailedSecondOutputLeavesNoFirst) {
  test::ScopedTempDir dir;
  {
    StagedFiles files;
    files.Stage(dir.File("overlay.png.txt"));
    files.WriteFile(dir.File("overlay.png.txt"), "first");
    // /proc takes no new files: refused when staged (or, as root, when written).
    try {
      files.Stage("/proc/features.json");
      files.WriteFile("/proc/features.json", "second");
      FAIL() << "no error";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("/proc/features.json"), std::string::npos) << e.what();
    }
  }
  EXPECT_EQ(CountEntries(dir.path()), 0);
}

TEST(StagedFiles, CommitNeedsEveryFileWritten) {
  test::ScopedTempDir dir;
  StagedFiles files;
  WriteFileAtomically(files.Stage(dir.File("a.txt")), "a");
  files.Stage(dir.File("never.txt"));
  try {
    files.Commit();
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("never.txt"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(PathExists(dir.File("a.txt")));
}

TEST(StagedFiles, WriteErrorsNameTheTargetNotTheTempFile) {
  test::ScopedTempDir dir;
  StagedFiles files;
  files.Stage(dir.File("a.json"));
  try {
    files.Write(dir.File("a.json"), [](const std::string& temp) {
      throw Error(ErrorKind::kIo, temp + ": write failed (disk full?)");
    });
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), dir.File("a.json") + ": write failed (disk full?)");
  }
  EXPECT_THROW(files.WriteFile(dir.File("not_staged.json"), "x"), Error);
}

TEST(StagedFiles, RefusesAnExistingFileWithoutOverwrite) {
  test::ScopedTempDir dir;
  WriteFileAtomically(dir.File("x.db"), "old");
  StagedFiles files;
  EXPECT_THROW(files.Stage(dir.File("x.db"), /*overwrite=*/false), Error);
  EXPECT_EQ(ReadFileToString(dir.File("x.db")), "old");
}

}  // namespace
}  // namespace comic::io
