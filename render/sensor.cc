#include "render/sensor.h"

#include <cmath>

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
}

double ExposureGain(const SensorOptions& options, uint64_t seed, double time) {
  if (options.exposure_drift == 0.0) return 1.0;
  return std::exp(options.exposure_drift *
                  SmoothNoise(seed, kExposure, time, options.exposure_period));
}

cv::Mat ExposeFrame(const cv::Mat& color, const SensorOptions& options, uint64_t seed, int frame) {
  const double gain = ExposureGain(options, seed, frame);
  cv::Mat out;
  if (options.read_noise == 0 && options.shot_noise == 0) {
    color.convertTo(out, CV_8U, gain);  // rounds to nearest, saturates
    return out;
  }
  Random random(seed, kNoise, static_cast<uint64_t>(frame));
  out.create(color.size(), CV_8UC3);
  const double read_variance = options.read_noise * options.read_noise;
  for (int y = 0; y < color.rows; ++y) {
    const float* in = color.ptr<float>(y);
    uint8_t* row = out.ptr<uint8_t>(y);
    for (int i = 0; i < color.cols * 3; ++i) {
      const double value = in[i] * gain;
      const double sigma = std::sqrt(read_variance + options.shot_noise * std::max(0.0, value));
      row[i] = cv::saturate_cast<uint8_t>(value + sigma * random.Normal());
    }
  }
  return out;
}

}  // namespace comic::render
