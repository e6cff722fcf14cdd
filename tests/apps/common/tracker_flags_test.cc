// TrackerFlags: comic_sfm's and comic_export_colmap's tracker flags, one definition and one set
// of defaults (sfm::SequenceReconstructionOptions' tracker).
#include "apps/common/tracker_flags.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "io/core/error.h"
#include "sfm/sequence_reconstruction.h"

namespace {

using comic::apps::ArgParser;
using comic::apps::TrackerFlags;

void Parse(ArgParser& parser, std::vector<std::string> args) {
  args.insert(args.begin(), "prog");
  std::vector<char*> argv;
  for (std::string& arg : args) argv.push_back(arg.data());
  parser.Parse(static_cast<int>(argv.size()), argv.data());
}

TEST(TrackerFlags, DefaultsAreTheReconstructionsTracker) {
  const comic::frontend::TrackerOptions expected =
      comic::sfm::SequenceReconstructionOptions().tracker;
  TrackerFlags flags;
  ArgParser parser("prog", "", "");
  comic::apps::AddTrackerFlags(parser, &flags);
  Parse(parser, {});
  const comic::frontend::TrackerOptions options =
      comic::apps::ToTrackerSettings(flags, parser).ToTrackerOptions();
  EXPECT_EQ(options.max_features, 2000);
  EXPECT_EQ(options.max_features, expected.max_features);
  EXPECT_EQ(options.prediction, comic::frontend::MotionPrediction::kConstantVelocity);
  EXPECT_EQ(options.unpredicted_radius, expected.unpredicted_radius);
  EXPECT_EQ(options.matcher.radius, expected.matcher.radius);
  EXPECT_EQ(options.matcher.max_cost, expected.matcher.max_cost);
  EXPECT_EQ(options.coarse_radius, expected.coarse_radius);
  EXPECT_EQ(options.match_window, expected.match_window);
  EXPECT_EQ(options.conflict_rule, expected.conflict_rule);
  EXPECT_EQ(options.verify_min_gap, expected.verify_min_gap);
  EXPECT_EQ(options.match_turned_180, expected.match_turned_180);
}

TEST(TrackerFlags, FlagsReachTheOptions) {
  TrackerFlags flags;
  ArgParser parser("prog", "", "");
  comic::apps::AddTrackerFlags(parser, &flags);
  Parse(parser, {"--max-features", "100", "--search-radius", "12.5", "--prediction",
                 "coarse-to-fine", "--match-window", "3", "--track-conflicts", "drop", "--max-cost",
                 "250", "--verify-min-gap", "2", "--match-turned"});
  const comic::frontend::TrackerOptions options =
      comic::apps::ToTrackerSettings(flags, parser).ToTrackerOptions();
  EXPECT_EQ(options.max_features, 100);
  EXPECT_EQ(options.matcher.radius, 12.5);
  EXPECT_EQ(options.prediction, comic::frontend::MotionPrediction::kCoarseToFine);
  EXPECT_EQ(options.match_window, 3);
  EXPECT_EQ(options.conflict_rule, comic::frontend::TrackConflictRule::kDrop);
  EXPECT_EQ(options.matcher.max_cost, 250.0);
  EXPECT_EQ(options.verify_min_gap, 2);
  EXPECT_TRUE(options.match_turned_180);
}

TEST(TrackerFlags, BadNamesAndValuesThrowInvalidArgument) {
  for (const std::vector<std::string>& args : {std::vector<std::string>{"--prediction", "psychic"},
                                               {"--track-conflicts", "merge"},
                                               {"--search-radius", "0"}}) {
    TrackerFlags flags;
    ArgParser parser("prog", "", "");
    comic::apps::AddTrackerFlags(parser, &flags);
    Parse(parser, args);
    try {
      comic::apps::ToTrackerSettings(flags, parser).ToTrackerOptions();
      ADD_FAILURE() << args.front() << " " << args.back() << " was accepted";
    } catch (const comic::Error& e) {
      EXPECT_EQ(e.kind(), comic::ErrorKind::kInvalidArgument) << e.what();
    }
  }
}

}  // namespace
