#include "frontend/baselines/response_peaks.h"

#include <algorithm>

#include "io/core/error.h"

namespace comic::frontend {

void ResponsePeakOptions::Check() const {
  COMIC_CHECK(nms_radius >= 1, kInvalidArgument, "nms_radius must be >= 1, got " << nms_radius);
  COMIC_CHECK(border >= 1, kInvalidArgument, "border must be >= 1, got " << border);
}

namespace {

// Offset in [-0.5, 0.5] of the vertex of the parabola through (-1, a), (0, b), (1, c).
float ParabolaVertex(float a, float b, float c) {
  const float curvature = a - 2.0f * b + c;
  if (curvature >= 0.0f) return 0.0f;  // not a maximum (flat or rising)
  return std::clamp(0.5f * (a - c) / curvature, -0.5f, 0.5f);
}

}  // namespace

FeatureSet FindResponsePeaks(const cv::Mat& response, const ResponsePeakOptions& options,
                             float feature_scale) {
  options.Check();
  COMIC_CHECK(response.type() == CV_32FC1, kInvalidArgument, "response map must be CV_32FC1");
  FeatureSet peaks;
  const int r = options.nms_radius;
  const int margin = std::max(options.border, r);
  for (int y = margin; y < response.rows - margin; ++y) {
    const float* row = response.ptr<float>(y);
    for (int x = margin; x < response.cols - margin; ++x) {
      const float value = row[x];
      if (!(value > options.min_value)) continue;
      bool is_peak = true;
      for (int dy = -r; dy <= r && is_peak; ++dy) {
        const float* other = response.ptr<float>(y + dy);
        for (int dx = -r; dx <= r; ++dx) {
          if (dx == 0 && dy == 0) continue;
          const float v = other[x + dx];
          // Ties go to the earlier pixel in raster order.
          const bool earlier = dy < 0 || (dy == 0 && dx < 0);
          if (v > value || (v == value && earlier)) {
            is_peak = false;
            break;
          }
        }
      }
      if (!is_peak) continue;
      Feature f;
      f.x = static_cast<float>(x);
      f.y = static_cast<float>(y);
      if (options.subpixel) {
        f.x += ParabolaVertex(row[x - 1], value, row[x + 1]);
        f.y += ParabolaVertex(response.at<float>(y - 1, x), value, response.at<float>(y + 1, x));
      }
      f.scale = feature_scale;
      f.response = value;
      peaks.push_back(std::move(f));
    }
  }
  SortByResponse(&peaks);
  return peaks;
}

}  // namespace comic::frontend
