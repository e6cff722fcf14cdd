#include "frontend/evaluation/threshold_equalisation.h"

#include <gtest/gtest.h>

#include "frontend/baselines/harris_detector.h"
#include "io/core/error.h"
#include "io/image/image_io.h"
#include "tests/test_support.h"

namespace comic::frontend {
namespace {

Feature At(float x, float y, float response) {
  Feature f;
  f.x = x;
  f.y = y;
  f.response = response;
  return f;
}

TEST(ThresholdEqualisation, YieldsTheRequestedCountOnTheFirstFrame) {
  // 100 features with distinct responses inside a 200x200 image.
  FeatureSet features;
  for (int i = 0; i < 100; ++i) features.push_back(At(20.0f + i, 100.0f, 0.5f * i));
  const ThresholdCut cut = EqualiseThreshold(features, 30, {200, 200});
  EXPECT_TRUE(cut.reached);
  EXPECT_EQ(cut.available, 100);
  EXPECT_EQ(cut.count, 30);
  EXPECT_EQ(ApplyThreshold(features, cut.min_response).size(), 30u);
  EXPECT_FLOAT_EQ(cut.min_response, 0.5f * 70);
}

TEST(ThresholdEqualisation, CountsOnlyFeaturesInsideTheRegionWhosePatchFits) {
  FeatureSet features;
  features.push_back(At(5, 100, 100));  // patch does not fit: dropped before counting
  for (int i = 0; i < 20; ++i) features.push_back(At(30.0f + i, 50, 50.0f + i));   // in region
  for (int i = 0; i < 20; ++i) features.push_back(At(30.0f + i, 150, 80.0f + i));  // outside
  cv::Mat region(200, 200, CV_8UC1, cv::Scalar(0));
  region(cv::Rect(0, 0, 200, 100)).setTo(255);
  EXPECT_EQ(CountCountedFeatures(features, {200, 200}, region), 20);
  const ThresholdCut cut = EqualiseThreshold(features, 5, {200, 200}, region);
  EXPECT_EQ(cut.count, 5);
  EXPECT_FLOAT_EQ(cut.min_response, 65.0f);  // 69, 68, 67, 66, 65
  // The cut applies to all features, inside the region or not.
  EXPECT_EQ(ApplyThreshold(features, cut.min_response).size(), 5u + 20u + 1u);
}

TEST(ThresholdEqualisation, TooFewFeaturesUseAllTheDetectorHas) {
  FeatureSet features = {At(50, 50, 3), At(60, 60, 1)};
  const ThresholdCut cut = EqualiseThreshold(features, 10, {200, 200});
  EXPECT_FALSE(cut.reached);
  EXPECT_EQ(cut.count, 2);
  EXPECT_EQ(ApplyThreshold(features, cut.min_response).size(), 2u);
  EXPECT_EQ(ApplyThreshold({At(1, 1, -1e30f)}, cut.min_response).size(), 1u);
}

TEST(ThresholdEqualisation, TiesAtTheCutOffGoToTheCloserCount) {
  // Integer scores like FAST's: 10, 9, 8, 8, 8, 8, 7.
  FeatureSet features;
  for (float r : {10.f, 9.f, 8.f, 8.f, 8.f, 8.f, 7.f}) features.push_back(At(50, 50, r));
  // N = 3: keeping the 8s gives 6 (3 away), dropping them gives 2 (1 away) -> 2.
  ThresholdCut cut = EqualiseThreshold(features, 3, {200, 200});
  EXPECT_EQ(cut.count, 2);
  EXPECT_FLOAT_EQ(cut.min_response, 9.0f);
  // N = 5: 6 (1 away) beats 2 (3 away).
  cut = EqualiseThreshold(features, 5, {200, 200});
  EXPECT_EQ(cut.count, 6);
  EXPECT_FLOAT_EQ(cut.min_response, 8.0f);
  // N = 4: 6 and 2 are both 2 away -> the tie is kept.
  EXPECT_EQ(EqualiseThreshold(features, 4, {200, 200}).count, 6);
  // All tied at the top: nothing can be dropped.
  EXPECT_EQ(EqualiseThreshold({At(50, 50, 1), At(60, 60, 1), At(70, 70, 1)}, 1, {200, 200}).count,
            3);
}

TEST(ThresholdEqualisation, RealDetectorOnTheBundledExample) {
  const cv::Mat gray = io::LoadImage(test::ExampleDir() + "/image_l/000000.png").gray;
  const FeatureSet features = HarrisDetector().Detect(gray);
  cv::Mat region(gray.size(), CV_8UC1, cv::Scalar(0));
  region(cv::Rect(300, 100, 400, 200)).setTo(255);
  const ThresholdCut cut = EqualiseThreshold(features, 150, gray.size(), region);
  EXPECT_TRUE(cut.reached);
  EXPECT_EQ(cut.count, 150);  // float responses: no ties
  EXPECT_EQ(CountCountedFeatures(ApplyThreshold(features, cut.min_response), gray.size(), region),
            150);
}

TEST(ThresholdEqualisation, BadArgumentsThrow) {
  EXPECT_THROW(EqualiseThreshold({}, 0, {10, 10}), Error);
  EXPECT_THROW(EqualiseThreshold({}, 5, {0, 10}), Error);
  EXPECT_THROW(EqualiseThreshold({}, 5, {10, 10}, cv::Mat(11, 10, CV_8UC1)), Error);
  EXPECT_THROW(EqualiseThreshold({}, 5, {10, 10}, cv::Mat(10, 10, CV_32F)), Error);
}

}  // namespace
}  // namespace comic::frontend
