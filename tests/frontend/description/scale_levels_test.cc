#include "frontend/description/scale_levels.h"

#include <gtest/gtest.h>

#include <cmath>

#include "io/core/error.h"

namespace comic::frontend {
namespace {

TEST(ScaleLevels, NearestLevelIsTheNearestInLogScale) {
  const auto expect_level = [](double sigma, int octave, int layer) {
    const ScaleLevel level = NearestScaleLevel(sigma);
    EXPECT_EQ(level.octave, octave) << sigma;
    EXPECT_EQ(level.layer, layer) << sigma;
  };
  expect_level(1.6, 0, 0);
  expect_level(0.5, 0, 0);  // below the base blur: the base level
  expect_level(2.0, 0, 1);  // 3 log2(2 / 1.6) = 0.97
  expect_level(2.5, 0, 2);  // 1.93
  expect_level(3.0, 1, 0);  // 2.72: rounds up to the next octave
  expect_level(3.2, 1, 0);  // one octave up
  expect_level(8.4, 2, 1);  // CoMIC's s: 3 log2(5.25) = 7.18 -> level 7
  EXPECT_NEAR((ScaleLevel{2, 1}.Sigma()), 1.6 * std::pow(2.0, 7.0 / 3.0), 1e-12);
  EXPECT_NEAR((ScaleLevel{2, 1}.OctaveSigma()), 1.6 * std::pow(2.0, 1.0 / 3.0), 1e-12);
  EXPECT_THROW(NearestScaleLevel(0.0), Error);
  EXPECT_THROW(NearestScaleLevel(std::nan("")), Error);
}

TEST(ScaleLevels, OctaveCoordinatesKeepPixelCentres) {
  // Octave 1 averages input pixels 0 and 1 into pixel 0: input 0.5 is octave 0.
  EXPECT_DOUBLE_EQ((ScaleLevel{1, 0}.ToOctave(0.5)), 0.0);
  EXPECT_DOUBLE_EQ((ScaleLevel{2, 0}.ToOctave(1.5)), 0.0);
  EXPECT_DOUBLE_EQ((ScaleLevel{0, 2}.ToOctave(7.25)), 7.25);
}

TEST(ScaleLevels, PacksTheLevelAsOpenCvUnpacksIt) {
  const int packed = PackOpenCvOctave({2, 1});
  EXPECT_EQ(packed & 255, 2);
  EXPECT_EQ((packed >> 8) & 255, 1);
  EXPECT_EQ(PackOpenCvOctave({0, 0}), 0);
}

TEST(ScaleLevels, ImagesAreHalvedPerOctaveAndBlurred) {
  cv::Mat gray(80, 100, CV_8UC1, cv::Scalar(0));
  gray(cv::Rect(50, 0, 50, 80)).setTo(200);  // a vertical step edge at x = 49.5
  ScaleLevelImages images(gray);
  const cv::Mat& base = images.Get({0, 0});
  const cv::Mat& octave1 = images.Get({1, 2});
  EXPECT_EQ(base.size(), cv::Size(100, 80));
  EXPECT_EQ(octave1.size(), cv::Size(50, 40));
  EXPECT_EQ(base.type(), CV_32F);
  // Blurred: the step is smooth, symmetric about the edge, and flat far from it.
  EXPECT_NEAR(base.at<float>(40, 10), 0.0f, 1e-3);
  EXPECT_NEAR(base.at<float>(40, 90), 200.0f, 1e-3);
  EXPECT_NEAR(base.at<float>(40, 49) + base.at<float>(40, 50), 200.0f, 1e-2);
  EXPECT_GT(base.at<float>(40, 49), 20.0f);
  // The same level asked again is the same image (made once).
  EXPECT_EQ(images.Get({0, 0}).data, base.data);
  EXPECT_THROW(ScaleLevelImages(cv::Mat(4, 4, CV_32F)), Error);
}

}  // namespace
}  // namespace comic::frontend
