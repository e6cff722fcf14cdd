#include "frontend/baselines/hessian_detector.h"

#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/imgproc.hpp>

#include "io/core/error.h"

namespace comic::frontend {
namespace {

TEST(HessianDetector, FindsBlobCentresWithSubPixelAccuracy) {
  // A dark and a bright Gaussian blob (σ = 2.5 px) at non-integer centres.
  cv::Mat image(100, 140, CV_32F, cv::Scalar(128));
  const cv::Point2f dark(40.3f, 50.6f), bright(100.7f, 45.2f);
  for (int y = 0; y < image.rows; ++y) {
    for (int x = 0; x < image.cols; ++x) {
      const auto blob = [&](cv::Point2f c) {
        return std::exp(-((x - c.x) * (x - c.x) + (y - c.y) * (y - c.y)) / (2 * 2.5 * 2.5));
      };
      image.at<float>(y, x) += static_cast<float>(-90 * blob(dark) + 90 * blob(bright));
    }
  }
  cv::Mat gray;
  image.convertTo(gray, CV_8U);
  const FeatureSet features = HessianDetector().Detect(gray);
  ASSERT_GE(features.size(), 2u);
  for (const cv::Point2f& centre : {dark, bright}) {
    bool found = false;
    for (size_t i = 0; i < 2; ++i) {
      found |= std::hypot(features[i].x - centre.x, features[i].y - centre.y) < 0.5;
    }
    EXPECT_TRUE(found) << centre << " strongest: " << features[0].Position() << " "
                       << features[1].Position();
  }
  EXPECT_GT(features[0].response, 0.0f);
  EXPECT_FLOAT_EQ(features[0].scale, 2.0f);
}

TEST(HessianDetector, StraightEdgeIsNotABlob) {
  cv::Mat edge(60, 60, CV_8UC1, cv::Scalar(30));
  edge(cv::Rect(30, 0, 30, 60)).setTo(220);
  // The determinant vanishes along a straight edge: no feature near x = 29.5 away from the ends.
  for (const Feature& f : HessianDetector().Detect(edge)) {
    EXPECT_FALSE(std::abs(f.x - 29.5f) < 4 && f.y > 10 && f.y < 50) << f.Position();
  }
  EXPECT_THROW(HessianDetector().Detect(cv::Mat(10, 10, CV_16UC1)), Error);
  HessianDetectorOptions bad;
  bad.sigma = 0;
  EXPECT_THROW(HessianDetector{bad}, Error);
}

}  // namespace
}  // namespace comic::frontend
