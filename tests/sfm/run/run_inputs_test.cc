// What a run resolves before anything heavy runs (sfm/run/run_inputs.h): here, the matchers
// --matcher auto tries and in which order.
#include "sfm/run/run_inputs.h"

#include <gtest/gtest.h>

#include "tests/test_support.h"

namespace comic::sfm {
namespace {

ReconstructionRunOptions ExampleOptions() {
  ReconstructionRunOptions options;
  options.frames = test::ExampleDir() + "/image_l";
  return options;
}

TEST(RunInputs, AutoOnAVideoTriesVerifiedPatchesThenDescriptors) {
  const RunInputs inputs = ResolveRunInputs(ExampleOptions());
  ASSERT_TRUE(frontend::IsVideo(inputs.pairing));
  ASSERT_EQ(inputs.matchers.size(), 2u);
  EXPECT_FALSE(inputs.matchers[0].image_set.has_value());
  EXPECT_EQ(inputs.matchers[0].tracker.verify_min_gap, 1);  // every pair verified
  ASSERT_TRUE(inputs.matchers[1].image_set.has_value());
  EXPECT_GT(inputs.matchers[1].image_set->window, 0);  // a window of frames, not every pair
}

TEST(RunInputs, AGivenVerifyMinGapIsKept) {
  ReconstructionRunOptions options = ExampleOptions();
  options.tracker.Give("verify-min-gap", [](frontend::TrackerOptions& o) { o.verify_min_gap = 3; });
  const RunInputs inputs = ResolveRunInputs(options);
  ASSERT_EQ(inputs.matchers.size(), 2u);
  EXPECT_EQ(inputs.matchers[0].tracker.verify_min_gap, 3);
}

TEST(RunInputs, AutoOnAnImageSetTriesThePatchSetUpThenDescriptors) {
  ReconstructionRunOptions options = ExampleOptions();
  options.matching = "exhaustive";
  const RunInputs inputs = ResolveRunInputs(options);
  ASSERT_FALSE(frontend::IsVideo(inputs.pairing));
  ASSERT_EQ(inputs.matchers.size(), 2u);
  EXPECT_FALSE(inputs.matchers[0].image_set.has_value());
  ASSERT_TRUE(inputs.matchers[1].image_set.has_value());
  EXPECT_EQ(inputs.matchers[1].image_set->window, 0);  // every pair
}

TEST(RunInputs, AMatcherOrAMatchWindowGivenIsTheOnlyOneTried) {
  for (const char* matcher : {"patches", "descriptors"}) {
    ReconstructionRunOptions options = ExampleOptions();
    options.matcher = matcher;
    const RunInputs inputs = ResolveRunInputs(options);
    ASSERT_EQ(inputs.matchers.size(), 1u) << matcher;
    EXPECT_EQ(inputs.matchers[0].image_set.has_value(), std::string(matcher) == "descriptors");
    EXPECT_EQ(inputs.matchers[0].tracker.verify_min_gap, inputs.tracker.verify_min_gap);
  }
  ReconstructionRunOptions options = ExampleOptions();
  options.tracker.Give("match-window", [](frontend::TrackerOptions& o) { o.match_window = 3; });
  const RunInputs inputs = ResolveRunInputs(options);
  ASSERT_EQ(inputs.matchers.size(), 1u);
  EXPECT_FALSE(inputs.matchers[0].image_set.has_value());
  EXPECT_EQ(inputs.matchers[0].tracker.match_window, 3);
}

}  // namespace
}  // namespace comic::sfm
