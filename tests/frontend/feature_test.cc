#include "frontend/feature.h"

#include <gtest/gtest.h>

namespace comic::frontend {
namespace {

Feature At(float x, float y, float response) {
  Feature f;
  f.x = x;
  f.y = y;
  f.response = response;
  return f;
}

TEST(Feature, SortByResponseIsStrongestFirstWithDeterministicTies) {
  FeatureSet features = {At(5, 1, 1.0f), At(1, 2, 3.0f), At(9, 0, 1.0f), At(2, 1, 1.0f)};
  SortByResponse(&features);
  ASSERT_EQ(features.size(), 4u);
  EXPECT_EQ(features[0].response, 3.0f);
  // Ties on response: by y, then x.
  EXPECT_EQ(features[1].y, 0.0f);
  EXPECT_EQ(features[2].x, 2.0f);
  EXPECT_EQ(features[3].x, 5.0f);
}

TEST(Feature, PatchFitsUsesRoundedCentreAndRadius) {
  const cv::Size size(100, 50);
  EXPECT_TRUE(PatchFits(At(11, 11, 0), size));
  EXPECT_FALSE(PatchFits(At(10.4f, 20, 0), size));  // rounds to 10: left edge at -1
  EXPECT_TRUE(PatchFits(At(10.6f, 20, 0), size));   // rounds to 11
  EXPECT_TRUE(PatchFits(At(88, 38, 0), size));      // right edge at 99, bottom at 49
  EXPECT_FALSE(PatchFits(At(89, 20, 0), size));
  EXPECT_FALSE(PatchFits(At(50, 39, 0), size));
}

TEST(Feature, SideMaskPresence) {
  Feature f;
  EXPECT_FALSE(f.HasSideMask());
  f.side_mask.assign(kPatchSize * kPatchSize, PatchSide::kPlus);
  EXPECT_TRUE(f.HasSideMask());
}

}  // namespace
}  // namespace comic::frontend
