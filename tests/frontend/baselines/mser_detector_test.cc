#include "frontend/baselines/mser_detector.h"

#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/imgproc.hpp>

#include "io/core/error.h"

namespace comic::frontend {
namespace {

const Feature* Nearest(const FeatureSet& features, cv::Point2f p) {
  const Feature* best = nullptr;
  for (const Feature& f : features) {
    if (!best || std::hypot(f.x - p.x, f.y - p.y) < std::hypot(best->x - p.x, best->y - p.y)) {
      best = &f;
    }
  }
  return best;
}

TEST(MserDetector, OnePointPerStableRegionAtItsCentroid) {
  // A dark disk and a bright rectangle on a mid-grey background, slightly blurred.
  cv::Mat image(120, 160, CV_8UC1, cv::Scalar(128));
  cv::circle(image, {50, 60}, 15, cv::Scalar(30), cv::FILLED);
  cv::rectangle(image, cv::Rect(100, 40, 30, 20), cv::Scalar(230),
                cv::FILLED);  // centre 114.5, 49.5
  cv::GaussianBlur(image, image, cv::Size(5, 5), 1.0);
  const FeatureSet features = MserDetector().Detect(image);
  ASSERT_GE(features.size(), 2u);
  const Feature* disk = Nearest(features, {50, 60});
  const Feature* box = Nearest(features, {114.5f, 49.5f});
  ASSERT_NE(disk, nullptr);
  EXPECT_LT(std::hypot(disk->x - 50, disk->y - 60), 0.5);
  EXPECT_EQ(disk->polarity, Polarity::kDark);
  EXPECT_NEAR(disk->scale, 15.0, 1.5);
  EXPECT_LT(std::hypot(box->x - 114.5, box->y - 49.5), 0.5);
  EXPECT_EQ(box->polarity, Polarity::kBright);
  // Sharp-edged regions are very stable: response 1 / (1 + v) close to 1.
  EXPECT_GT(disk->response, 0.8f);
  EXPECT_LE(disk->response, 1.0f);
  // No two features closer than the merge radius.
  for (size_t i = 0; i < features.size(); ++i) {
    for (size_t j = i + 1; j < features.size(); ++j) {
      EXPECT_GE(std::hypot(features[i].x - features[j].x, features[i].y - features[j].y), 2.0);
    }
  }
}

TEST(MserDetector, AreaLimitsAndBadInput) {
  cv::Mat image(120, 160, CV_8UC1, cv::Scalar(128));
  cv::circle(image, {50, 60}, 3, cv::Scalar(30), cv::FILLED);  // area ≈ 29 < min_area 60
  for (const Feature& f : MserDetector().Detect(image)) {
    EXPECT_GT(std::hypot(f.x - 50, f.y - 60), 1.0) << "a region below min_area was returned";
  }
  EXPECT_TRUE(MserDetector().Detect(cv::Mat(50, 50, CV_8UC1, cv::Scalar(9))).empty());
  EXPECT_THROW(MserDetector().Detect(cv::Mat(10, 10, CV_8UC3)), Error);
  MserDetectorOptions bad;
  bad.max_area = 10;
  EXPECT_THROW(MserDetector{bad}, Error);
}

TEST(MserDetector, IsDeterministic) {
  cv::Mat noise(90, 110, CV_8UC1);
  cv::RNG rng(3);
  rng.fill(noise, cv::RNG::UNIFORM, 0, 256);
  cv::GaussianBlur(noise, noise, cv::Size(7, 7), 2.0);
  const FeatureSet a = MserDetector().Detect(noise);
  const FeatureSet b = MserDetector().Detect(noise);
  ASSERT_EQ(a.size(), b.size());
  ASSERT_FALSE(a.empty());
  for (size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].x, b[i].x);
    EXPECT_EQ(a[i].response, b[i].response);
  }
}

}  // namespace
}  // namespace comic::frontend
