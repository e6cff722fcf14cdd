// Feature masks (issue 47): on a mask covering the left half of a frame, the features kept are
// exactly those farther than the margin from it, in their order, under either convention; the
// count of dropped features and the hash follow the masks.
#include "frontend/feature_masks.h"

#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <vector>

#include "io/core/error.h"

namespace comic::frontend {
namespace {

constexpr int kWidth = 100;
constexpr int kHeight = 80;

// Non-zero on columns [0, 50): the left half.
cv::Mat LeftHalf() {
  cv::Mat mask(kHeight, kWidth, CV_8UC1, cv::Scalar(0));
  mask.colRange(0, 50).setTo(255);
  return mask;
}

// One feature per half pixel along a row of the frame (every position rounds to a pixel of it).
FeatureSet Row(float y) {
  FeatureSet features;
  for (float x = 0.0f; x <= kWidth - 1; x += 0.5f) {
    Feature feature;
    feature.x = x;
    feature.y = y;
    features.push_back(feature);
  }
  return features;
}

std::vector<float> Xs(const FeatureSet& features) {
  std::vector<float> xs;
  for (const Feature& feature : features) xs.push_back(feature.x);
  return xs;
}

// The xs of Row() at least `first` (a feature is at its rounded pixel: 51.5 rounds to 52).
std::vector<float> XsFrom(float first) {
  std::vector<float> xs;
  for (float x = 0.0f; x <= kWidth - 1; x += 0.5f) {
    if (x >= first) xs.push_back(x);
  }
  return xs;
}

std::vector<float> XsBelow(float last) {
  std::vector<float> xs;
  for (float x = 0.0f; x <= kWidth - 1; x += 0.5f) {
    if (x < last) xs.push_back(x);
  }
  return xs;
}

TEST(FeatureMasks, KeepsExactlyTheFeaturesBeyondTheMarginOfTheMask) {
  const FeatureMasks masks({LeftHalf()}, FeatureMaskOptions());  // non-zero dropped, 2 px
  // Columns 0-49 masked, 50 and 51 within 2 px: the first pixel kept is 52 (x >= 51.5 rounds to
  // 52; std::lround rounds halves away from zero).
  for (float y : {0.0f, 40.0f, 79.0f}) {
    SCOPED_TRACE(y);
    EXPECT_EQ(Xs(masks.Keep(0, Row(y))), XsFrom(51.5f));
  }
  EXPECT_TRUE(masks.Drops(0, 51.4, 10.0));
  EXPECT_FALSE(masks.Drops(0, 51.5, 10.0));
  EXPECT_FALSE(masks.Drops(0, -3.0, 10.0));  // outside the mask: kept
  // No kept feature inside the dilated mask, and every feature outside it kept.
  const FeatureSet all = Row(33.0f);
  const FeatureSet kept = masks.Keep(0, all);
  size_t outside = 0;
  for (const Feature& feature : all) outside += !masks.Drops(0, feature.x, feature.y);
  EXPECT_EQ(kept.size(), outside);
  for (const Feature& feature : kept) {
    EXPECT_EQ(masks.DroppedRegion(0).at<uint8_t>(33, static_cast<int>(std::lround(feature.x))), 0);
  }

  FeatureMaskOptions no_margin;
  no_margin.margin_px = 0;
  EXPECT_EQ(Xs(FeatureMasks({LeftHalf()}, no_margin).Keep(0, Row(5.0f))), XsFrom(49.5f));
}

TEST(FeatureMasks, ColmapConventionDropsTheZeroPixels) {
  FeatureMaskOptions colmap;
  colmap.drop_nonzero = false;
  const FeatureMasks masks({LeftHalf()}, colmap);
  // Columns 50-99 are zero: dropped with 48 and 49 (within 2 px); x < 47.5 rounds to 47 at most.
  EXPECT_EQ(Xs(masks.Keep(0, Row(40.0f))), XsBelow(47.5f));
}

// OpenCV's elliptic 5x5 kernel: every pixel within 2 px, and those 2 px one way and 1 the other.
TEST(FeatureMasks, TheMarginIsADisc) {
  cv::Mat dot(kHeight, kWidth, CV_8UC1, cv::Scalar(0));
  dot.at<uint8_t>(40, 50) = 1;
  const FeatureMasks masks({dot}, FeatureMaskOptions());
  EXPECT_TRUE(masks.Drops(0, 52, 40));
  EXPECT_TRUE(masks.Drops(0, 50, 38));
  EXPECT_TRUE(masks.Drops(0, 51, 41));
  EXPECT_TRUE(masks.Drops(0, 52, 41));
  EXPECT_FALSE(masks.Drops(0, 53, 40));
  EXPECT_FALSE(masks.Drops(0, 52, 42));  // 2.8 px away
}

TEST(FeatureMasks, FilterCountsWhatItDropsPerFrame) {
  cv::Mat empty(kHeight, kWidth, CV_8UC1, cv::Scalar(0));
  const FeatureMasks masks({LeftHalf(), empty}, FeatureMaskOptions());
  std::atomic<int64_t> dropped(0);
  const DetectionFilter filter = masks.Filter(&dropped);
  EXPECT_EQ(filter(1, Row(3.0f)).size(), Row(3.0f).size());  // frame 1 has an empty mask
  EXPECT_EQ(dropped.load(), 0);
  const FeatureSet kept = filter(0, Row(3.0f));
  EXPECT_EQ(dropped.load(), static_cast<int64_t>(Row(3.0f).size() - kept.size()));
  EXPECT_EQ(kept.size(), XsFrom(51.5f).size());
}

TEST(FeatureMasks, HashFollowsTheDroppedRegions) {
  cv::Mat empty(kHeight, kWidth, CV_8UC1, cv::Scalar(0));
  FeatureMaskOptions colmap;
  colmap.drop_nonzero = false;
  FeatureMaskOptions wide;
  wide.margin_px = 3;
  const uint64_t hash = FeatureMasks({LeftHalf()}, FeatureMaskOptions()).Hash();
  EXPECT_EQ(FeatureMasks({LeftHalf().clone()}, FeatureMaskOptions()).Hash(), hash);
  EXPECT_NE(FeatureMasks({LeftHalf()}, colmap).Hash(), hash);
  EXPECT_NE(FeatureMasks({LeftHalf()}, wide).Hash(), hash);
  EXPECT_NE(FeatureMasks({empty}, FeatureMaskOptions()).Hash(), hash);
  EXPECT_NE(FeatureMasks({LeftHalf(), empty}, FeatureMaskOptions()).Hash(), hash);
}

TEST(FeatureMasks, RefusesMasksOfMixedSizesOrTypesAndANegativeMargin) {
  EXPECT_THROW(FeatureMasks({LeftHalf(), cv::Mat(10, 10, CV_8UC1)}, {}), Error);
  EXPECT_THROW(FeatureMasks({cv::Mat(10, 10, CV_32FC1)}, {}), Error);
  FeatureMaskOptions negative;
  negative.margin_px = -1;
  EXPECT_THROW(FeatureMasks({LeftHalf()}, negative), Error);
}

}  // namespace
}  // namespace comic::frontend
