// comic_sfm's COLMAP flags end to end: --colmap-db (+ --overwrite) writes the run's tracks as a
// COLMAP database and prints the mapper command; --compare-colmap runs COLMAP's mapper on the same
// tracks and writes the side-by-side table.
#include <gtest/gtest.h>

#include <filesystem>

#include "io/colmap/colmap_database.h"
#include "io/core/file_utils.h"
#include "tests/test_support.h"

namespace {

using comic::test::AppPath;
using comic::test::RunCommand;
using comic::test::ScopedTempDir;

bool ColmapOnPath() { return RunCommand("command -v colmap").exit_code == 0; }

std::string Example() {
  const std::string example = comic::test::ExampleDir();
  return example + "/image_l --gt " + example + "/poses.txt --quiet";
}

TEST(ComicSfmColmap, HelpDocumentsTheColmapOptions) {
  const auto result = RunCommand(AppPath("comic_sfm") + " --help");
  EXPECT_EQ(result.exit_code, 0);
  for (const char* option :
       {"--colmap-db", "--overwrite", "--compare-colmap", "--colmap-threads"}) {
    EXPECT_NE(result.output.find(option), std::string::npos) << option;
  }
}

TEST(ComicSfmColmap, BadColmapFlagsFailBeforeAnyWork) {
  ScopedTempDir dir;
  comic::io::WriteFileAtomically(dir.File("existing.db"), "keep me\n");
  const std::string out = " --output " + dir.File("out");
  struct Case {
    std::string args;
    int exit_code;
    std::string message;
  };
  const std::vector<Case> cases = {
      {Example() + out + " --overwrite", 2, "--overwrite needs --colmap-db"},
      {Example() + out + " --colmap-db " + dir.File("a.db") + " --compare", 2,
       "not with --compare"},
      {Example() + out + " --colmap-db " + dir.File("a.db") + " --resize-height 185", 2,
       "--resize-height 0"},
      {Example() + out + " --colmap-db " + dir.File("existing.db"), 1, "already exists"},
      {Example() + out + " --colmap-db /nonexistent/dir/a.db", 1, "does not exist"},
      {Example() + out + " --compare-colmap --colmap-threads 0", 2, "--colmap-threads"},
  };
  for (const Case& c : cases) {
    const auto result = RunCommand(AppPath("comic_sfm") + " " + c.args);
    EXPECT_EQ(result.exit_code, c.exit_code) << c.args << "\n" << result.output;
    EXPECT_NE(result.output.find(c.message), std::string::npos) << c.args << "\n" << result.output;
    EXPECT_EQ(comic::test::CountLines(result.output), 1) << result.output;
  }
  EXPECT_EQ(comic::io::ReadFileToString(dir.File("existing.db")), "keep me\n");
  EXPECT_FALSE(comic::io::PathExists(dir.File("a.db")));
}

TEST(ComicSfmColmap, WritesTheDatabaseAndComparesWithColmap) {
  const bool colmap = ColmapOnPath();
  ScopedTempDir dir;
  const std::string db = dir.File("kitti.db");
  comic::io::WriteFileAtomically(db, "old\n");
  const auto result = RunCommand(
      AppPath("comic_sfm") + " " + Example() + " --output " + dir.File("out") + " --colmap-db " +
      db + " --overwrite --colmap-threads 2" + (colmap ? " --compare-colmap" : ""));
  ASSERT_EQ(result.exit_code, 0) << result.output;
  EXPECT_NE(result.output.find("run COLMAP on it with:\n  mkdir -p "), std::string::npos)
      << result.output;
  // Into colmap/sparse beside the database, never over comic_sfm's own sparse/0 (issue 29).
  EXPECT_NE(result.output.find("--output_path " + dir.File("colmap/sparse") + " "),
            std::string::npos)
      << result.output;
  EXPECT_NE(result.output.find("--Mapper.ba_refine_focal_length 0"), std::string::npos);
  comic::io::ColmapDatabase database = comic::io::ColmapDatabase::Open(db);
  EXPECT_EQ(database.NumImages(), 12u);
  EXPECT_TRUE(database.ReadCamera(1).prior_focal_length);  // calib.txt beside poses.txt
  EXPECT_GT(database.NumVerifiedImagePairs(), 30u);
  if (!colmap) GTEST_SKIP() << "colmap is not installed: --compare-colmap not run";

  const std::string table = comic::io::ReadFileToString(dir.File("out/colmap_compare.md"));
  EXPECT_NE(table.find("| comic-sfm | 12/12 |"), std::string::npos) << table;
  EXPECT_NE(table.find("| COLMAP 3.8 mapper | 1"), std::string::npos) << table;  // 11 or 12
  EXPECT_NE(table.find("| comic-sfm read by COLMAP | 12/12 |"), std::string::npos) << table;
  EXPECT_EQ(comic::test::CountLines(table), 5) << table;  // header, rule, three rows
  EXPECT_TRUE(comic::io::IsRegularFile(dir.File("out/colmap_compare.csv")));
  const std::string json = comic::io::ReadFileToString(dir.File("out/colmap_compare.json"));
  EXPECT_NE(json.find("colmap_mapper_command"), std::string::npos);
  EXPECT_TRUE(comic::io::IsRegularFile(dir.File("out/colmap/database.db")));

  // A second comparison into the same --output is refused up front.
  const auto again = RunCommand(AppPath("comic_sfm") + " " + Example() + " --output " +
                                dir.File("out") + " --compare-colmap");
  EXPECT_EQ(again.exit_code, 1) << again.output;
  EXPECT_NE(again.output.find("earlier --compare-colmap"), std::string::npos) << again.output;
}

// A database inside a new --output: written with the outputs (the folder did not exist, and the
// check used to refuse the database's missing folder before the run).
TEST(ComicSfmColmap, DatabaseInsideANewOutputFolder) {
  ScopedTempDir dir;
  const std::string out = dir.File("out/x");
  const auto result = RunCommand(AppPath("comic_sfm") + " " + Example() + " --output " + out +
                                 " --colmap-db " + out + "/tracks.db");
  ASSERT_EQ(result.exit_code, 0) << result.output;
  comic::io::ColmapDatabase database = comic::io::ColmapDatabase::Open(out + "/tracks.db");
  EXPECT_EQ(database.NumImages(), 12u);
  EXPECT_TRUE(comic::io::IsRegularFile(out + "/sparse/0/images.bin"));
  // Nothing of the staging folder is left beside it.
  size_t entries = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir.File("out"))) {
    EXPECT_EQ(entry.path().filename(), "x");
    ++entries;
  }
  EXPECT_EQ(entries, 1u);
}

}  // namespace
