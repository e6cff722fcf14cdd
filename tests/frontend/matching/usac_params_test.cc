#include "frontend/matching/usac_params.h"

#include <gtest/gtest.h>

#include <opencv2/calib3d.hpp>
#include <random>
#include <vector>

#include "io/core/error.h"

namespace comic::frontend {
namespace {

// Two views of random 3-D points (a translating, slightly rotating camera) plus 30 % outliers.
void MakeCorrespondences(std::vector<cv::Point2f>* points1, std::vector<cv::Point2f>* points2) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> xy(-2.0, 2.0), depth(4.0, 10.0), pixel(0.0, 640.0);
  const double f = 500.0, cx = 320.0, cy = 240.0;
  const cv::Matx33d rotation = [] {
    cv::Matx33d r;
    cv::Rodrigues(cv::Vec3d(0.0, 0.05, 0.01), r);
    return r;
  }();
  const cv::Vec3d translation(0.5, 0.05, 0.1);
  for (int i = 0; i < 200; ++i) {
    const cv::Vec3d X(xy(rng), xy(rng), depth(rng));
    const cv::Vec3d Y = rotation * X + translation;
    points1->emplace_back(f * X[0] / X[2] + cx, f * X[1] / X[2] + cy);
    if (i % 10 < 3) {
      points2->emplace_back(pixel(rng), pixel(rng) * 0.75);  // outlier
    } else {
      points2->emplace_back(f * Y[0] / Y[2] + cx, f * Y[1] / Y[2] + cy);
    }
  }
}

TEST(UsacParams, FitsAreSeededAndRepeatBitForBit) {
  std::vector<cv::Point2f> points1, points2;
  MakeCorrespondences(&points1, &points2);
  const cv::UsacParams params = DeterministicUsacParams(1.0, 0.999, 2000, 3);
  EXPECT_FALSE(params.isParallel);
  EXPECT_EQ(params.randomGeneratorState, 3);
  EXPECT_EQ(params.maxIterations, 2000);
  EXPECT_EQ(params.score, cv::SCORE_METHOD_MSAC);

  cv::Mat mask1, mask2;
  const cv::Mat f1 = cv::findFundamentalMat(points1, points2, mask1, params);
  const cv::Mat f2 = cv::findFundamentalMat(points1, points2, mask2, params);
  ASSERT_FALSE(f1.empty());
  EXPECT_EQ(cv::norm(f1, f2, cv::NORM_INF), 0.0);
  EXPECT_EQ(cv::countNonZero(mask1 != mask2), 0);
  // Every outlier rejected, (almost) every inlier kept.
  int inliers_kept = 0, outliers_kept = 0;
  for (int i = 0; i < static_cast<int>(points1.size()); ++i) {
    const bool kept = mask1.at<uchar>(i) != 0;
    if (i % 10 < 3) {
      outliers_kept += kept;
    } else {
      inliers_kept += kept;
    }
  }
  EXPECT_EQ(outliers_kept, 0);
  EXPECT_GE(inliers_kept, 135);  // of 140
}

TEST(UsacParams, RejectsBadSettings) {
  EXPECT_THROW(DeterministicUsacParams(0.0, 0.999, 100, 1), comic::Error);
  EXPECT_THROW(DeterministicUsacParams(1.0, 1.0, 100, 1), comic::Error);
  EXPECT_THROW(DeterministicUsacParams(1.0, 0.999, 0, 1), comic::Error);
  EXPECT_THROW(DeterministicUsacParams(1.0, 0.999, 100, 0x80000000u), comic::Error);
}

}  // namespace
}  // namespace comic::frontend
