#include "frontend/description/feature_orientation.h"

#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/imgproc.hpp>

#include "io/core/error.h"

namespace comic::frontend {
namespace {

// Smooth random texture, the same for every call.
cv::Mat Texture(int width, int height) {
  cv::Mat noise(height, width, CV_32F);
  cv::RNG rng(5);
  rng.fill(noise, cv::RNG::UNIFORM, 0.0, 1.0);
  cv::GaussianBlur(noise, noise, cv::Size(), 3.0);
  cv::normalize(noise, noise, 0, 255, cv::NORM_MINMAX);
  cv::Mat gray;
  noise.convertTo(gray, CV_8U);
  return gray;
}

double AngleDifference(double a, double b) {
  const double d = std::fmod(std::abs(a - b), 360.0);
  return std::min(d, 360.0 - d);
}

TEST(FeatureOrientation, GradientOfAStepEdgePointsToTheBrightSide) {
  cv::Mat gray(60, 60, CV_8UC1, cv::Scalar(20));
  gray(cv::Rect(30, 0, 30, 60)).setTo(220);  // bright on the right
  OrientationOptions options;
  options.mode = OrientationMode::kGradient;
  ScaleLevelImages images(gray);
  EXPECT_LT(AngleDifference(DominantGradientOrientation(29.5, 30, 2.0, options, &images), 0.0),
            1.0);
  // Bright below: +90 degrees in image axes (y down).
  cv::Mat below(60, 60, CV_8UC1, cv::Scalar(20));
  below(cv::Rect(0, 30, 60, 30)).setTo(220);
  ScaleLevelImages below_images(below);
  EXPECT_LT(
      AngleDifference(DominantGradientOrientation(30, 29.5, 2.0, options, &below_images), 90.0),
      1.0);
  // No gradient at all: 0.
  ScaleLevelImages flat(cv::Mat(60, 60, CV_8UC1, cv::Scalar(90)));
  EXPECT_EQ(DominantGradientOrientation(30, 30, 2.0, options, &flat), 0.0f);
}

TEST(FeatureOrientation, TurnsWithTheImage) {
  const cv::Mat gray = Texture(120, 100);
  cv::Mat turned;
  cv::rotate(gray, turned, cv::ROTATE_90_CLOCKWISE);  // (x, y) -> (h - 1 - y, x)
  OrientationOptions options;
  options.mode = OrientationMode::kGradient;
  ScaleLevelImages images(gray), turned_images(turned);
  cv::RNG rng(9);
  for (int k = 0; k < 40; ++k) {
    const int x = rng.uniform(25, 95), y = rng.uniform(25, 75);
    for (double sigma : {2.0, 3.0}) {  // octave 0 and octave 1 (2^1 divides 120 and 100)
      const double angle = DominantGradientOrientation(x, y, sigma, options, &images);
      const double turned_angle =
          DominantGradientOrientation(gray.rows - 1 - y, x, sigma, options, &turned_images);
      // Clockwise on screen is +90 degrees in image axes.
      EXPECT_LT(AngleDifference(turned_angle, angle + 90.0), 0.5)
          << "at " << x << "," << y << " sigma " << sigma;
    }
  }
}

TEST(FeatureOrientation, IsoCurveBisectorPointsIntoTheCorner) {
  Feature corner;
  corner.x = 20;
  corner.y = 20;
  for (int k = -8; k <= 8; ++k) {  // an L: one arm along +x, the other along +y
    corner.curve.emplace_back(k < 0 ? 20.0f : 20.0f + k, k < 0 ? 20.0f - k : 20.0f);
  }
  EXPECT_NEAR(IsoCurveOrientation(corner, 4.0), 45.0, 1e-3);
  // A straight curve has no bisector.
  Feature straight;
  straight.x = 20;
  straight.y = 20;
  for (int k = -8; k <= 8; ++k) straight.curve.emplace_back(20.0f + k, 20.0f);
  EXPECT_LT(IsoCurveOrientation(straight, 4.0), 0.0f);
  // kIsoCurve uses the curve where there is one and the gradient elsewhere; kUpright gives 0.
  cv::Mat gray(60, 60, CV_8UC1, cv::Scalar(20));
  gray(cv::Rect(30, 0, 30, 60)).setTo(220);
  Feature edge;
  edge.x = 29.5;
  edge.y = 30;
  ScaleLevelImages images(gray);
  OrientationOptions options;  // kIsoCurve
  const std::vector<float> angles =
      ComputeOrientations({corner, edge, straight}, {4.0, 2.0, 2.0}, options, &images);
  EXPECT_NEAR(angles[0], 45.0, 1e-3);
  EXPECT_LT(AngleDifference(angles[1], 0.0), 1.0);
  options.mode = OrientationMode::kUpright;
  EXPECT_EQ(ComputeOrientations({corner, edge}, {4.0, 2.0}, options, &images),
            (std::vector<float>{0.0f, 0.0f}));
}

TEST(FeatureOrientation, NamesAndOptions) {
  for (OrientationMode mode :
       {OrientationMode::kGradient, OrientationMode::kUpright, OrientationMode::kIsoCurve}) {
    EXPECT_EQ(ParseOrientationMode(OrientationModeName(mode)), mode);
  }
  EXPECT_THROW(ParseOrientationMode("north"), Error);
  OrientationOptions options;
  options.num_bins = 2;
  EXPECT_THROW(options.Check(), Error);
  options = {};
  options.radius_factor = 0;
  EXPECT_THROW(options.Check(), Error);
  ScaleLevelImages images(cv::Mat(10, 10, CV_8UC1, cv::Scalar(0)));
  EXPECT_THROW(ComputeOrientations({Feature()}, {}, {}, &images), Error);
}

}  // namespace
}  // namespace comic::frontend
