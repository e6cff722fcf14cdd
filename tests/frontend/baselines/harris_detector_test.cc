#include "frontend/baselines/harris_detector.h"

#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/imgproc.hpp>

#include "io/core/error.h"

namespace comic::frontend {
namespace {

// A bright 40x40 square (pixels 40..79) on a dark background.
cv::Mat SquareImage() {
  cv::Mat image(120, 120, CV_8UC1, cv::Scalar(40));
  cv::rectangle(image, cv::Rect(40, 40, 40, 40), cv::Scalar(200), cv::FILLED);
  return image;
}

TEST(HarrisDetector, FindsTheFourCornersOfASquareFirst) {
  const FeatureSet features = HarrisDetector().Detect(SquareImage());
  ASSERT_GE(features.size(), 4u);
  // The corners lie between pixels 39/40 and 79/80.
  const std::vector<cv::Point2f> corners = {
      {39.5f, 39.5f}, {79.5f, 39.5f}, {39.5f, 79.5f}, {79.5f, 79.5f}};
  for (const cv::Point2f& corner : corners) {
    bool found = false;
    for (size_t i = 0; i < 4; ++i) {
      found |= std::hypot(features[i].x - corner.x, features[i].y - corner.y) < 2.0;
    }
    EXPECT_TRUE(found) << corner;
  }
  for (size_t i = 0; i + 1 < features.size(); ++i) {
    EXPECT_GE(features[i].response, features[i + 1].response);
  }
  EXPECT_FLOAT_EQ(features[0].scale, 2.0f);
  EXPECT_FALSE(features[0].HasSideMask());
}

TEST(HarrisDetector, EdgesAndFlatAreasGiveNoCorner) {
  cv::Mat edge(100, 100, CV_8UC1, cv::Scalar(40));
  edge(cv::Rect(50, 0, 50, 100)).setTo(200);
  const FeatureSet features = HarrisDetector().Detect(edge);
  for (const Feature& f : features) EXPECT_LT(std::abs(f.x - 49.5f), 40.0f);
  EXPECT_TRUE(HarrisDetector().Detect(cv::Mat(100, 100, CV_8UC1, cv::Scalar(7))).empty());
  EXPECT_TRUE(HarrisDetector().Detect(cv::Mat(4, 4, CV_8UC1, cv::Scalar(7))).empty());
}

TEST(HarrisDetector, IsDeterministicAndRejectsBadInput) {
  cv::Mat noise(80, 90, CV_8UC1);
  cv::RNG rng(7);
  rng.fill(noise, cv::RNG::UNIFORM, 0, 256);
  const FeatureSet a = HarrisDetector().Detect(noise);
  const FeatureSet b = HarrisDetector().Detect(noise);
  ASSERT_EQ(a.size(), b.size());
  ASSERT_FALSE(a.empty());
  for (size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].x, b[i].x);
    EXPECT_EQ(a[i].response, b[i].response);
  }
  EXPECT_THROW(HarrisDetector().Detect(cv::Mat(10, 10, CV_8UC3)), Error);
  EXPECT_THROW(HarrisDetector().Detect(cv::Mat()), Error);
  HarrisDetectorOptions bad;
  bad.k = 0.3;
  EXPECT_THROW(HarrisDetector{bad}, Error);
}

}  // namespace
}  // namespace comic::frontend
