#include "frontend/description/feature_orientation.h"

#include <algorithm>
#include <cmath>

#include "io/core/error.h"

namespace comic::frontend {
namespace {

constexpr double kTwoPi = 2.0 * M_PI;

float DegreesIn360(double radians) {
  double degrees = radians * 180.0 / M_PI;
  degrees = std::fmod(degrees, 360.0);
  if (degrees < 0) degrees += 360.0;
  if (degrees >= 360.0) degrees = 0.0;
  return static_cast<float>(degrees);
}

}  // namespace

const char* OrientationModeName(OrientationMode mode) {
  switch (mode) {
    case OrientationMode::kGradient:
      return "gradient";
    case OrientationMode::kUpright:
      return "upright";
    case OrientationMode::kIsoCurve:
      return "iso-curve";
  }
  return "unknown";
}

OrientationMode ParseOrientationMode(const std::string& name) {
  for (OrientationMode mode :
       {OrientationMode::kGradient, OrientationMode::kUpright, OrientationMode::kIsoCurve}) {
    if (name == OrientationModeName(mode)) return mode;
  }
  throw Error(ErrorKind::kInvalidArgument,
              "unknown orientation '" + name + "' (expected gradient, upright or iso-curve)");
}

void OrientationOptions::Check() const {
  COMIC_CHECK(num_bins >= 4 && num_bins <= 360, kInvalidArgument,
              "orientation: num_bins must be in [4, 360], got " << num_bins);
  COMIC_CHECK(weight_sigma_factor > 0 && weight_sigma_factor <= 10, kInvalidArgument,
              "orientation: weight_sigma_factor must be in (0, 10], got " << weight_sigma_factor);
  COMIC_CHECK(radius_factor > 0 && radius_factor <= 10, kInvalidArgument,
              "orientation: radius_factor must be in (0, 10], got " << radius_factor);
}

float DominantGradientOrientation(double x, double y, double sigma,
                                  const OrientationOptions& options, ScaleLevelImages* images) {
  const ScaleLevel level = NearestScaleLevel(sigma);
  const cv::Mat& image = images->Get(level);
  // The window in the octave's pixels: the level's σ there, not the asked σ, so that the window
  // holds the same structure whatever the octave.
  const double weight_sigma = options.weight_sigma_factor * level.OctaveSigma();
  const int radius = static_cast<int>(std::lround(options.radius_factor * weight_sigma));
  const int cx = static_cast<int>(std::lround(level.ToOctave(x)));
  const int cy = static_cast<int>(std::lround(level.ToOctave(y)));
  const double weight_scale = -1.0 / (2.0 * weight_sigma * weight_sigma);
  std::vector<double> histogram(options.num_bins, 0.0);
  for (int v = -radius; v <= radius; ++v) {
    const int py = cy + v;
    if (py <= 0 || py >= image.rows - 1) continue;
    const float* row = image.ptr<float>(py);
    const float* up = image.ptr<float>(py - 1);
    const float* down = image.ptr<float>(py + 1);
    for (int u = -radius; u <= radius; ++u) {
      const int px = cx + u;
      if (px <= 0 || px >= image.cols - 1) continue;
      const double dx = row[px + 1] - row[px - 1];
      const double dy = down[px] - up[px];  // y down: image axes
      const double magnitude = std::sqrt(dx * dx + dy * dy);
      if (magnitude == 0.0) continue;
      double angle = std::atan2(dy, dx);
      if (angle < 0) angle += kTwoPi;
      int bin = static_cast<int>(std::lround(angle / kTwoPi * options.num_bins));
      if (bin >= options.num_bins) bin -= options.num_bins;
      histogram[bin] += magnitude * std::exp((u * u + v * v) * weight_scale);
    }
  }
  // Smooth circularly with [1 4 6 4 1] / 16 (as OpenCV's SIFT) so that one noisy bin cannot win.
  const int n = options.num_bins;
  std::vector<double> smooth(n, 0.0);
  for (int i = 0; i < n; ++i) {
    const auto at = [&](int k) { return histogram[((i + k) % n + n) % n]; };
    smooth[i] = (at(-2) + at(2)) * (1.0 / 16) + (at(-1) + at(1)) * (4.0 / 16) + at(0) * (6.0 / 16);
  }
  // The highest bin, ties to the lowest index (deterministic).
  const int peak =
      static_cast<int>(std::max_element(smooth.begin(), smooth.end()) - smooth.begin());
  if (smooth[peak] <= 0.0) return 0.0f;
  const double left = smooth[(peak + n - 1) % n];
  const double right = smooth[(peak + 1) % n];
  const double curvature = left - 2.0 * smooth[peak] + right;
  const double offset = curvature < 0 ? 0.5 * (left - right) / curvature : 0.0;
  return DegreesIn360((peak + offset) * kTwoPi / n);
}

float IsoCurveOrientation(const Feature& feature, double sigma) {
  double sum_x = 0.0, sum_y = 0.0;
  int count = 0;
  const double max_distance = 2.0 * sigma;
  for (const cv::Point2f& point : feature.curve) {
    const double dx = point.x - feature.x;
    const double dy = point.y - feature.y;
    const double distance = std::sqrt(dx * dx + dy * dy);
    if (distance < 0.5 || distance > max_distance) continue;
    sum_x += dx / distance;
    sum_y += dy / distance;
    ++count;
  }
  // A straight curve (or none) gives a mean near zero: its direction would be noise.
  if (count == 0 || std::sqrt(sum_x * sum_x + sum_y * sum_y) < 0.05 * count) return -1.0f;
  return DegreesIn360(std::atan2(sum_y, sum_x));
}

std::vector<float> ComputeOrientations(const FeatureSet& features,
                                       const std::vector<double>& sigmas,
                                       const OrientationOptions& options,
                                       ScaleLevelImages* images) {
  options.Check();
  COMIC_CHECK(sigmas.size() == features.size(), kInvalidArgument,
              "orientation: " << sigmas.size() << " scales for " << features.size() << " features");
  COMIC_CHECK(images != nullptr, kInvalidArgument, "orientation: no images");
  std::vector<float> angles(features.size(), 0.0f);
  if (options.mode == OrientationMode::kUpright) return angles;
  for (size_t i = 0; i < features.size(); ++i) {
    const Feature& feature = features[i];
    if (options.mode == OrientationMode::kIsoCurve && !feature.curve.empty()) {
      const float angle = IsoCurveOrientation(feature, sigmas[i]);
      if (angle >= 0.0f) {
        angles[i] = angle;
        continue;
      }
    }
    angles[i] = DominantGradientOrientation(feature.x, feature.y, sigmas[i], options, images);
  }
  return angles;
}

}  // namespace comic::frontend
