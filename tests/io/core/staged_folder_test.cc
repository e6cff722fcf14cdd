#include "io/core/staged_folder.h"

#include <gtest/gtest.h>

#include <filesystem>

#include "io/core/error.h"
#include "io/core/file_utils.h"
#include "tests/test_support.h"

namespace comic::io {
namespace {

namespace fs = std::filesystem;

int CountEntries(const std::string& folder) {
  int n = 0;
  for ([[maybe_unused]] const auto& entry : fs::directory_iterator(folder)) ++n;
  return n;
}

TEST(StagedFolder, NothingExistsUntilCommitThenEverything) {
  test::ScopedTempDir dir;
  const std::string target = dir.File("out/sfm");
  {
    StagedFolder staged(target);
    EXPECT_FALSE(PathExists(dir.File("out")));  // not even the parent
    EXPECT_EQ(staged.path().find(dir.path()), 0u);
    WriteFileAtomically(JoinPaths(staged.path(), "report.json"), "{}\n");
    EnsureWritableDirectory(JoinPaths(staged.path(), "harris"));
    WriteFileAtomically(JoinPaths(staged.path(), "harris/cameras.txt"), "c\n");
    EXPECT_FALSE(PathExists(target));
    EXPECT_EQ(staged.ToTargetPaths("log: " + staged.path() + "/colmap/log.txt"),
              "log: " + target + "/colmap/log.txt");
    staged.Commit();
  }
  EXPECT_EQ(ReadFileToString(JoinPaths(target, "report.json")), "{}\n");
  EXPECT_EQ(ReadFileToString(JoinPaths(target, "harris/cameras.txt")), "c\n");
  EXPECT_EQ(CountEntries(dir.path()), 1);  // out/ only: no staging folder left
}

TEST(StagedFolder, WithoutCommitTheFileSystemIsAsItWas) {
  test::ScopedTempDir dir;
  {
    StagedFolder staged(dir.File("out"));
    WriteFileAtomically(JoinPaths(staged.path(), "half.txt"), "x");
    EXPECT_EQ(CountEntries(dir.path()), 1);  // the hidden staging folder
  }
  EXPECT_EQ(CountEntries(dir.path()), 0);
}

TEST(StagedFolder, CommitMergesIntoAnExistingFolder) {
  test::ScopedTempDir dir;
  const std::string target = dir.File("out");
  EnsureWritableDirectory(JoinPaths(target, "harris"));
  WriteFileAtomically(JoinPaths(target, "keep.txt"), "old");
  WriteFileAtomically(JoinPaths(target, "report.json"), "old");
  WriteFileAtomically(JoinPaths(target, "harris/old.txt"), "old");
  StagedFolder staged(target);
  WriteFileAtomically(JoinPaths(staged.path(), "report.json"), "new");
  EnsureWritableDirectory(JoinPaths(staged.path(), "harris"));
  WriteFileAtomically(JoinPaths(staged.path(), "harris/new.txt"), "new");
  staged.Commit();
  EXPECT_EQ(ReadFileToString(JoinPaths(target, "keep.txt")), "old");
  EXPECT_EQ(ReadFileToString(JoinPaths(target, "report.json")), "new");
  EXPECT_EQ(ReadFileToString(JoinPaths(target, "harris/old.txt")), "old");
  EXPECT_EQ(ReadFileToString(JoinPaths(target, "harris/new.txt")), "new");
  EXPECT_EQ(CountEntries(dir.path()), 1);
}

TEST(StagedFolder, RefusesATargetThatIsAFileOrUnderOne) {
  test::ScopedTempDir dir;
  WriteFileAtomically(dir.File("file"), "x");
  for (const std::string& target : {dir.File("file"), dir.File("file/sub")}) {
    try {
      StagedFolder staged(target);
      FAIL() << "no error for " << target;
    } catch (const Error& e) {
      EXPECT_EQ(e.kind(), ErrorKind::kIo);
      EXPECT_NE(std::string(e.what()).find("is not a folder"), std::string::npos) << e.what();
    }
  }
  EXPECT_EQ(CountEntries(dir.path()), 1);
}

}  // namespace
}  // namespace comic::io
