// AddColmapDbFlags: the export flags comic_sfm --colmap-db and comic_export_colmap share, bound to
// sfm::ColmapDatabaseOptions, whose Check() names the bad flag.
#include "apps/common/colmap_db_flags.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "io/core/error.h"

namespace {

using comic::apps::ArgParser;
using ColmapDbFlags = comic::sfm::ColmapDatabaseOptions;

void Parse(ArgParser& parser, std::vector<std::string> args) {
  args.insert(args.begin(), "prog");
  std::vector<char*> argv;
  for (std::string& arg : args) argv.push_back(arg.data());
  parser.Parse(static_cast<int>(argv.size()), argv.data());
}

std::string CheckMessage(const std::vector<std::string>& args) {
  ColmapDbFlags flags;
  ArgParser parser("prog", "", "");
  comic::apps::AddColmapDbFlags(parser, &flags);
  Parse(parser, args);
  try {
    flags.Check();
  } catch (const comic::Error& e) {
    EXPECT_EQ(e.kind(), comic::ErrorKind::kInvalidArgument);
    return e.what();
  }
  return "";
}

TEST(ColmapDbFlags, DefaultsAreTheExportsAndFlagsReachThem) {
  const comic::sfm::ColmapExportOptions defaults;
  ColmapDbFlags flags;
  ArgParser parser("prog", "", "");
  comic::apps::AddColmapDbFlags(parser, &flags);
  Parse(parser, {});
  EXPECT_EQ(flags.export_options.pair_window, defaults.pair_window);
  EXPECT_EQ(flags.export_options.two_view.max_error_px, defaults.two_view.max_error_px);
  EXPECT_EQ(flags.colmap_threads, -1);

  ColmapDbFlags set;
  ArgParser set_parser("prog", "", "");
  comic::apps::AddColmapDbFlags(set_parser, &set);
  Parse(set_parser, {"--colmap-db", "a.db", "--overwrite", "--window", "3", "--max-error", "1.5",
                     "--min-inliers", "20", "--colmap-threads", "2"});
  EXPECT_EQ(set.colmap_db, "a.db");
  EXPECT_TRUE(set.overwrite);
  EXPECT_EQ(set.export_options.pair_window, 3);
  EXPECT_EQ(set.export_options.two_view.max_error_px, 1.5);
  EXPECT_EQ(set.export_options.two_view.min_num_inliers, 20);
  EXPECT_EQ(set.colmap_threads, 2);
  EXPECT_EQ(CheckMessage({"--colmap-db", "a.db", "--overwrite", "--colmap-threads", "2"}), "");
}

TEST(ColmapDbFlags, CheckNamesTheBadFlag) {
  EXPECT_EQ(CheckMessage({"--overwrite"}), "--overwrite needs --colmap-db");
  EXPECT_EQ(CheckMessage({"--colmap-threads", "0"}), "--colmap-threads must be -1 or >= 1, got 0");
  EXPECT_NE(CheckMessage({"--window", "0"}), "");
}

}  // namespace
