#include "frontend/evaluation/region_labels.h"

#include <gtest/gtest.h>

#include "io/core/error.h"

namespace comic::frontend {
namespace {

RegionLabel At(const cv::Mat& labels, int x, int y) {
  return static_cast<RegionLabel>(labels.at<uint8_t>(y, x));
}

TEST(RegionLabels, BandOnBothSidesOfTheEdge) {
  // Object: pixels x, y in [20, 59].
  cv::Mat mask(80, 80, CV_8UC1, cv::Scalar(0));
  mask(cv::Rect(20, 20, 40, 40)).setTo(255);
  const cv::Mat labels = LabelRegion(mask, 3.0);
  EXPECT_EQ(At(labels, 40, 40), RegionLabel::kInterior);
  EXPECT_EQ(At(labels, 20, 40), RegionLabel::kBoundary);  // on the edge, inside
  EXPECT_EQ(At(labels, 22, 40), RegionLabel::kBoundary);  // 3 px from the outside pixel 19
  EXPECT_EQ(At(labels, 23, 40), RegionLabel::kInterior);  // 4 px
  EXPECT_EQ(At(labels, 17, 40), RegionLabel::kBoundary);  // outside, 3 px from pixel 20
  EXPECT_EQ(At(labels, 16, 40), RegionLabel::kOutside);
  EXPECT_EQ(At(labels, 2, 2), RegionLabel::kOutside);
  const cv::Mat evaluated = EvaluatedRegionMask(labels);
  // The square grown by the 3 px Euclidean band: 46x46 less, at each corner, the 5 of the 3x3
  // corner pixels farther than 3 px from the square.
  EXPECT_EQ(cv::countNonZero(evaluated), 46 * 46 - 4 * 5);
}

TEST(RegionLabels, EmptyAndFullMasksAndFeatures) {
  const cv::Mat none = LabelRegion(cv::Mat(10, 10, CV_8UC1, cv::Scalar(0)), 2.0);
  EXPECT_EQ(cv::countNonZero(none), 0);
  const cv::Mat all = LabelRegion(cv::Mat(10, 10, CV_8UC1, cv::Scalar(1)), 2.0);
  EXPECT_EQ(At(all, 0, 0), RegionLabel::kInterior);
  FeatureSet features(3);
  features[0].x = 4.6f, features[0].y = 5.2f;
  features[1].x = -3, features[1].y = 5;
  features[2].x = 9.4f, features[2].y = 9.4f;
  const auto labels = LabelFeatures(all, features);
  EXPECT_EQ(labels, (std::vector<RegionLabel>{RegionLabel::kInterior, RegionLabel::kOutside,
                                              RegionLabel::kInterior}));
  EXPECT_THROW(LabelRegion(cv::Mat(), 2.0), Error);
  EXPECT_THROW(LabelRegion(cv::Mat(10, 10, CV_8UC1), 0.0), Error);
  EXPECT_THROW(LabelRegion(cv::Mat(10, 10, CV_32F), 2.0), Error);
  EXPECT_STREQ(RegionLabelName(RegionLabel::kBoundary), "boundary");
}

}  // namespace
}  // namespace comic::frontend
