#include "frontend/comic/segment_stability.h"

#include <algorithm>
#include <cmath>

#include "io/core/error.h"

namespace comic::frontend {

void SegmentStabilityOptions::Check() const {
  COMIC_CHECK(half_length >= 1, kInvalidArgument,
              "segment stability: half_length must be >= 1, got " << half_length);
  COMIC_CHECK(sigma > 0, kInvalidArgument, "segment stability: sigma must be > 0, got " << sigma);
  COMIC_CHECK(delta > 0, kInvalidArgument, "segment stability: delta must be > 0, got " << delta);
  COMIC_CHECK(normal_step >= 1, kInvalidArgument,
              "segment stability: normal_step must be >= 1, got " << normal_step);
  COMIC_CHECK(sample_step > 0 && max_distance >= sample_step, kInvalidArgument,
              "segment stability: need 0 < sample_step <= max_distance, got "
                  << sample_step << " and " << max_distance);
}

SegmentStabilityEvaluator::SegmentStabilityEvaluator(const SegmentStabilityOptions& options)
    : options_(options) {
  options_.Check();
  weights_.resize(options_.half_length + 1);
  for (int d = 0; d <= options_.half_length; ++d) {
    weights_[d] = std::exp(-d * d / (2.0 * options_.sigma * options_.sigma));
  }
  max_steps_ = static_cast<int>(std::floor(options_.max_distance / options_.sample_step + 1e-9));
}

namespace {

// Bilinear interpolation of an 8-bit image at (x, y) in [0, cols - 1) x [0, rows - 1),
// pixel-centre coordinates.
inline float BilinearInside(const cv::Mat& gray, float x, float y) {
  const int x0 = static_cast<int>(x);
  const int y0 = static_cast<int>(y);
  const float tx = x - x0;
  const float ty = y - y0;
  const uint8_t* r0 = gray.data + y0 * gray.step[0] + x0;
  const uint8_t* r1 = r0 + gray.step[0];
  const float top = r0[0] + tx * (r0[1] - r0[0]);
  const float bottom = r1[0] + tx * (r1[1] - r1[0]);
  return top + ty * (bottom - top);
}

// The same anywhere, border replicated.
inline float Bilinear(const cv::Mat& gray, float x, float y) {
  if (x >= 0.0f && y >= 0.0f && x < gray.cols - 1.0f && y < gray.rows - 1.0f) {
    return BilinearInside(gray, x, y);
  }
  x = std::clamp(x, 0.0f, gray.cols - 1.0f);
  y = std::clamp(y, 0.0f, gray.rows - 1.0f);
  const int x0 = std::min(static_cast<int>(x), std::max(0, gray.cols - 2));
  const int y0 = std::min(static_cast<int>(y), std::max(0, gray.rows - 2));
  const int x1 = std::min(x0 + 1, gray.cols - 1);
  const int y1 = std::min(y0 + 1, gray.rows - 1);
  const float tx = x - x0;
  const float ty = y - y0;
  const uint8_t* r0 = gray.ptr<uint8_t>(y0);
  const uint8_t* r1 = gray.ptr<uint8_t>(y1);
  const float top = r0[x0] + tx * (r0[x1] - r0[x0]);
  const float bottom = r1[x0] + tx * (r1[x1] - r1[x0]);
  return top + ty * (bottom - top);
}

}  // namespace

double SegmentStabilityEvaluator::Evaluate(const cv::Mat& gray,
                                           const std::vector<cv::Point2f>& segment, int centre,
                                           double threshold) const {
  const int n = static_cast<int>(segment.size());
  if (centre < 1 || centre > n - 2) return 0.0;
  const int step = options_.normal_step;
  const int before = std::min(centre, options_.half_length) / step;
  const int after = std::min(n - 1 - centre, options_.half_length) / step;
  const float up = static_cast<float>(threshold + options_.delta);
  const float down = static_cast<float>(threshold - options_.delta);
  const float ds = static_cast<float>(options_.sample_step);
  const double clip = max_steps_ * options_.sample_step;
  double length = 0.0;
  double band = 0.0;
  double weight_sum = 0.0;
  for (int r = -before; r <= after; ++r) {
    const int i = centre + r * step;
    // The strip's length along the curve: half of each chord to the neighbouring normals' points.
    double element = 0.0;
    if (r > -before) element += 0.5 * cv::norm(segment[i] - segment[i - step]);
    if (r < after) element += 0.5 * cv::norm(segment[i + step] - segment[i]);
    const double weight = weights_[std::abs(r * step)];
    weight_sum += weight;
    // Unit normal towards the bright side (the right of the direction of travel).
    const cv::Point2f tangent = segment[std::min(n - 1, i + 1)] - segment[std::max(0, i - 1)];
    const float norm = std::sqrt(tangent.x * tangent.x + tangent.y * tangent.y);
    if (!(norm > 0.0f) || element == 0.0) continue;
    const float nx = -tangent.y / norm, ny = tangent.x / norm;
    const float px = segment[i].x, py = segment[i].y;
    // Up: the first sample at or above T + δ on the bright side; Down: the first below T - δ on
    // the dark side; each interpolated linearly from the sample before (the curve's own point,
    // at T, starts both walks). A normal whose whole reach lies inside the image is sampled
    // without the border clamps (the same values).
    const float reach = max_steps_ * ds;
    const bool inside = std::min(px - reach * std::abs(nx), py - reach * std::abs(ny)) >= 0.0f &&
                        px + reach * std::abs(nx) < gray.cols - 1.0f &&
                        py + reach * std::abs(ny) < gray.rows - 1.0f;
    double width = 0.0;
    for (const int side : {1, -1}) {
      const float target = side > 0 ? up : down;
      float previous = static_cast<float>(threshold);
      double u = clip;
      for (int s = 1; s <= max_steps_; ++s) {
        const float offset = side * s * ds;
        const float x = px + offset * nx, y = py + offset * ny;
        const float value = inside ? BilinearInside(gray, x, y) : Bilinear(gray, x, y);
        if (side > 0 ? value >= target : value < target) {
          u = (s - 1 + (target - previous) / (value - previous)) * options_.sample_step;
          break;
        }
        previous = value;
      }
      width += u;
    }
    length += weight * element;
    band += weight * element * width;
  }
  band = std::max(band, 1e-6 * weight_sum);
  return length > 0.0 ? length / band : 0.0;
}

}  // namespace comic::frontend
