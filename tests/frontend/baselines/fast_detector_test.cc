#include "frontend/baselines/fast_detector.h"

#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/imgproc.hpp>

#include "io/core/error.h"

namespace comic::frontend {
namespace {

TEST(FastDetector, FindsSquareCornersWithIntegerScores) {
  cv::Mat image(100, 100, CV_8UC1, cv::Scalar(50));
  cv::rectangle(image, cv::Rect(30, 30, 40, 40), cv::Scalar(200), cv::FILLED);
  // Slightly blurred, as a camera would see it: the score then peaks at one pixel per corner.
  cv::GaussianBlur(image, image, cv::Size(5, 5), 1.0);
  const FeatureSet features = FastDetector().Detect(image);
  ASSERT_GE(features.size(), 4u);
  const std::vector<cv::Point2f> corners = {{30, 30}, {69, 30}, {30, 69}, {69, 69}};
  for (const cv::Point2f& corner : corners) {
    bool found = false;
    for (size_t i = 0; i < 4; ++i) {
      found |= std::hypot(features[i].x - corner.x, features[i].y - corner.y) < 2.0;
    }
    EXPECT_TRUE(found) << corner;
  }
  for (const Feature& f : features) {
    EXPECT_EQ(f.response, std::round(f.response));  // OpenCV's FAST score is an integer
    EXPECT_GE(f.response, 5.0f);
  }
  for (size_t i = 0; i + 1 < features.size(); ++i) {
    EXPECT_GE(features[i].response, features[i + 1].response);
  }
}

TEST(FastDetector, AdjacentCornersOfEqualScoreKeepOne) {
  // A sharp synthetic square: each corner is a cluster of candidates with one score; OpenCV's
  // strict suppression would drop them all, ours keeps exactly one per corner.
  cv::Mat image(100, 100, CV_8UC1, cv::Scalar(50));
  cv::rectangle(image, cv::Rect(30, 30, 40, 40), cv::Scalar(200), cv::FILLED);
  const FeatureSet features = FastDetector().Detect(image);
  ASSERT_EQ(features.size(), 4u);
  for (const Feature& f : features) EXPECT_EQ(f.response, 149.0f);  // 200 - 50 - 1
}

TEST(FastDetector, ThresholdAndBadInput) {
  cv::Mat image(100, 100, CV_8UC1, cv::Scalar(100));
  cv::rectangle(image, cv::Rect(30, 30, 40, 40), cv::Scalar(110), cv::FILLED);
  FastDetectorOptions options;
  options.min_threshold = 20;  // the 10-level step is below it
  EXPECT_TRUE(FastDetector(options).Detect(image).empty());
  EXPECT_FALSE(FastDetector().Detect(image).empty());
  EXPECT_THROW(FastDetector().Detect(cv::Mat(10, 10, CV_32F)), Error);
  options.min_threshold = 0;
  EXPECT_THROW(FastDetector{options}, Error);
}

}  // namespace
}  // namespace comic::frontend
