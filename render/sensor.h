// What a camera adds to the light that reaches it: exposure that drifts over the sequence (a
// smooth random gain), sensor noise (read noise plus shot noise whose variance grows with the
// signal), and 8-bit quantisation. Motion blur (the shutter open while the camera moves) is
// rendered by averaging sub-frames (sequence_renderer.h); its options live here with the rest.
// Everything is seeded by (seed, frame), so the same frame always gets the same noise.
#pragma once

#include <cstdint>
#include <opencv2/core.hpp>
#include <vector>

namespace comic::render {

struct SensorOptions {
  // Read noise, standard deviation in grey levels (0..255).
  double read_noise = 0.0;
  // Shot noise: variance added per grey level of signal (variance = read² + shot·I).
  double shot_noise = 0.0;
  // Exposure drift: the gain is exp(drift · n(t)) with n a smooth random function in [-1, 1]
  // whose knots are `exposure_period` frames apart (0.2: the gain wanders within ×0.82..×1.22).
  double exposure_drift = 0.0;
  double exposure_period = 60.0;
  // Motion blur: the shutter is open for this fraction of the time between frames, centred on
  // the frame's time (0: no blur), sampled by `blur_samples` sub-frames.
  double shutter = 0.0;
  int blur_samples = 5;
  // Only every `blur_every`-th frame is blurred (frames whose index % blur_every is
  // blur_every - 1), the others are sharp: what a camera does whose exposure time jumps between
  // frames, and a sequence whose frames alternate sharp and smeared (2). 1: every frame.
  int blur_every = 1;

  void Check() const;
  // The shutter of frame `frame`: `shutter` on the frames blur_every picks, 0 on the others.
  double ShutterOf(int frame) const;
};

// The exposure gain at `time` (frames).
double ExposureGain(const SensorOptions& options, uint64_t seed, double time);

// The 8-bit frame (CV_8UC3) of a rendered colour image (CV_32FC3, 0..255): gain, noise,
// rounding and clipping.
cv::Mat ExposeFrame(const cv::Mat& color, const SensorOptions& options, uint64_t seed, int frame);

// The standard normal quantile function (Acklam's approximation, relative error < 1.2e-9).
double InverseNormal(double p);
// Its 4096 midpoint quantiles, Phi^-1((k + 1/2) / 4096): the sensor noise's values.
std::vector<float> NormalQuantiles();

}  // namespace comic::render
