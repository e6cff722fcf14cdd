// Sensor effects (render/sensor.h): exposure drift within its bounds and smooth, noise of the
// asked strength, zero mean, seeded per frame; the normal quantiles the noise draws from.
#include "render/sensor.h"

#include <gtest/gtest.h>

#include <cmath>

#include "io/core/error.h"

namespace comic::render {
namespace {

TEST(Sensor, InverseNormalMatchesTheNormalDistribution) {
  for (double p : {1e-6, 0.001, 0.02, 0.1, 0.3, 0.5, 0.8, 0.975, 0.999999}) {
    const double x = InverseNormal(p);
    EXPECT_NEAR(0.5 * std::erfc(-x / std::sqrt(2.0)), p, 1e-9 * std::max(1.0, p / (1 - p))) << p;
  }
  const std::vector<float> table = NormalQuantiles();
  ASSERT_EQ(table.size(), 4096u);
  double mean = 0.0, variance = 0.0;
  for (float v : table) mean += v / 4096.0;
  for (float v : table) variance += (v - mean) * (v - mean) / 4096.0;
  EXPECT_NEAR(mean, 0.0, 1e-6);
  EXPECT_NEAR(variance, 1.0, 0.01);  // midpoint quantiles: the tails are cut at 3.6 sigma
}

TEST(Sensor, NoiseHasTheAskedStrengthAndIsSeededPerFrame) {
  const cv::Mat grey(200, 300, CV_32FC3, cv::Scalar(100, 100, 100));
  SensorOptions options;
  options.read_noise = 3.0;
  options.shot_noise = 0.16;  // at 100: variance 9 + 16 = 25
  const cv::Mat a = ExposeFrame(grey, options, 7, 0);
  cv::Scalar mean, stddev;
  cv::meanStdDev(a.reshape(1), mean, stddev);
  EXPECT_NEAR(mean[0], 100.0, 0.1);
  EXPECT_NEAR(stddev[0], 5.0, 0.1);
  EXPECT_EQ(cv::norm(a, ExposeFrame(grey, options, 7, 0), cv::NORM_INF), 0.0);
  EXPECT_GT(cv::norm(a, ExposeFrame(grey, options, 7, 1), cv::NORM_L1), 0.0);
  EXPECT_GT(cv::norm(a, ExposeFrame(grey, options, 8, 0), cv::NORM_L1), 0.0);
  // Without noise: rounding only.
  EXPECT_EQ(cv::norm(ExposeFrame(grey, SensorOptions(), 7, 0),
                     cv::Mat(200, 300, CV_8UC3, cv::Scalar::all(100)), cv::NORM_INF),
            0.0);
}

TEST(Sensor, ExposureDriftStaysWithinItsBoundsAndMovesSmoothly) {
  SensorOptions options;
  options.exposure_drift = 0.2;
  options.exposure_period = 30.0;
  double low = 10.0, high = 0.0;
  for (int t = 0; t < 600; ++t) {
    const double gain = ExposureGain(options, 5, t);
    low = std::min(low, gain);
    high = std::max(high, gain);
    EXPECT_LT(std::abs(std::log(ExposureGain(options, 5, t + 1)) - std::log(gain)),
              0.2 * M_PI / 30);
  }
  EXPECT_GE(low, std::exp(-0.2) - 1e-12);
  EXPECT_LE(high, std::exp(0.2) + 1e-12);
  EXPECT_LT(low, 0.9);  // it does drift
  EXPECT_GT(high, 1.1);
  options.shutter = 1.5;
  EXPECT_THROW(options.Check(), Error);
}

TEST(Sensor, BlurEveryNthFramePicksTheLastOfEachN) {
  SensorOptions options;
  options.shutter = 0.6;
  for (int frame = 0; frame < 5; ++frame) EXPECT_EQ(options.ShutterOf(frame), 0.6) << frame;
  options.blur_every = 2;
  EXPECT_EQ(options.ShutterOf(0), 0.0);
  EXPECT_EQ(options.ShutterOf(1), 0.6);
  EXPECT_EQ(options.ShutterOf(2), 0.0);
  EXPECT_EQ(options.ShutterOf(3), 0.6);
  options.blur_every = 3;
  EXPECT_EQ(options.ShutterOf(1), 0.0);
  EXPECT_EQ(options.ShutterOf(2), 0.6);
  EXPECT_EQ(options.ShutterOf(5), 0.6);
  options.Check();
  options.blur_every = 0;
  EXPECT_THROW(options.Check(), Error);
  options.blur_every = -2;
  EXPECT_THROW(options.Check(), Error);
}

}  // namespace
}  // namespace comic::render
