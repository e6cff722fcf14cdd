#include "render/sensor.h"

#include <cmath>
#include <vector>

#include "io/core/error.h"
#include "render/random.h"

namespace comic::render {
namespace {

enum SensorStream : uint64_t { kExposure = 201, kNoise = 202 };

}  // namespace

void SensorOptions::Check() const {
  COMIC_CHECK(read_noise >= 0 && shot_noise >= 0 && exposure_drift >= 0, kInvalidArgument,
              "noise and exposure drift must be >= 0");
  COMIC_CHECK(exposure_period > 0, kInvalidArgument,
              "exposure period must be > 0 frames, got " << exposure_period);
  COMIC_CHECK(shutter >= 0 && shutter <= 1, kInvalidArgument,
              "shutter must be in 0..1 (fraction of the frame interval), got " << shutter);
  COMIC_CHECK(blur_samples >= 2 && blur_samples <= 64, kInvalidArgument,
              "blur samples must be in 2..64, got " << blur_samples);
  COMIC_CHECK(blur_every >= 1 && blur_every <= 100000, kInvalidArgument,
              "blur every must be in 1..100000 frames, got " << blur_every);
}

double SensorOptions::ShutterOf(int frame) const {
  return frame % blur_every == blur_every - 1 ? shutter : 0.0;
}

double ExposureGain(const SensorOptions& options, uint64_t seed, double time) {
  if (options.exposure_drift == 0.0) return 1.0;
  return std::exp(options.exposure_drift *
                  SmoothNoise(seed, kExposure, time, options.exposure_period));
}

cv::Mat ExposeFrame(const cv::Mat& color, const SensorOptions& options, uint64_t seed, int frame) {
  const double gain = ExposureGain(options, seed, frame);
  cv::Mat out;
  color.convertTo(out, CV_8U, gain);  // rounds to nearest, saturates
  if (options.read_noise == 0 && options.shot_noise == 0) return out;
  // Noise on the exposed signal. The standard deviation per grey level, and standard normal
  // values from a table of 4096 quantiles indexed by 12 random bits (five draws per 64-bit
  // number): per pixel a table lookup instead of a logarithm, a root and a cosine.
  float sigma[256];
  for (int level = 0; level < 256; ++level) {
    sigma[level] = static_cast<float>(
        std::sqrt(options.read_noise * options.read_noise + options.shot_noise * level));
  }
  const std::vector<float> normal = NormalQuantiles();
  Random random(seed, kNoise, static_cast<uint64_t>(frame));
  uint64_t bits = 0;
  int left = 0;
  for (int y = 0; y < out.rows; ++y) {
    uint8_t* row = out.ptr<uint8_t>(y);
    const float* exact = color.ptr<float>(y);
    for (int i = 0; i < out.cols * 3; ++i) {
      if (left == 0) {
        bits = random.Next();
        left = 5;
      }
      const float n = normal[bits & 4095];
      bits >>= 12;
      --left;
      const float value = exact[i] * static_cast<float>(gain);
      row[i] = cv::saturate_cast<uint8_t>(value + sigma[row[i]] * n);
    }
  }
  return out;
}

double InverseNormal(double p) {
  // Acklam's rational approximation of the normal quantile function (relative error < 1.2e-9).
  static constexpr double a[6] = {-3.969683028665376e+01, 2.209460984245205e+02,
                                  -2.759285104469687e+02, 1.383577518672690e+02,
                                  -3.066479806614716e+01, 2.506628277459239e+00};
  static constexpr double b[5] = {-5.447609879822406e+01, 1.615858368580409e+02,
                                  -1.556989798598866e+02, 6.680131188771972e+01,
                                  -1.328068155288572e+01};
  static constexpr double c[6] = {-7.784894002430293e-03, -3.223964580411365e-01,
                                  -2.400758277161838e+00, -2.549732539343734e+00,
                                  4.374664141464968e+00,  2.938163982698783e+00};
  static constexpr double d[4] = {7.784695709041462e-03, 3.224671290700398e-01,
                                  2.445134137142996e+00, 3.754408661907416e+00};
  constexpr double kLow = 0.02425;
  const auto tail = [&](double q) {
    return (((((c[0] * q + c[1]) * q + c[2]) * q + c[3]) * q + c[4]) * q + c[5]) /
           ((((d[0] * q + d[1]) * q + d[2]) * q + d[3]) * q + 1.0);
  };
  if (p < kLow) return tail(std::sqrt(-2.0 * std::log(p)));
  if (p > 1.0 - kLow) return -tail(std::sqrt(-2.0 * std::log(1.0 - p)));
  const double q = p - 0.5;
  const double r = q * q;
  return (((((a[0] * r + a[1]) * r + a[2]) * r + a[3]) * r + a[4]) * r + a[5]) * q /
         (((((b[0] * r + b[1]) * r + b[2]) * r + b[3]) * r + b[4]) * r + 1.0);
}

std::vector<float> NormalQuantiles() {
  std::vector<float> table(4096);
  for (int k = 0; k < 4096; ++k) table[k] = static_cast<float>(InverseNormal((k + 0.5) / 4096.0));
  return table;
}

}  // namespace comic::render
