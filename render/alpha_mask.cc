#include "render/alpha_mask.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

namespace comic::render {

void AlphaMask::Finish() {
  constexpr int kBlock = 1 << kBlockShift;
  const int bw = (coverage.cols + kBlock - 1) / kBlock;
  const int bh = (coverage.rows + kBlock - 1) / kBlock;
  blocks.create(bh, bw, CV_8UC1);
  for (int by = 0; by < bh; ++by) {
    for (int bx = 0; bx < bw; ++bx) {
      // The block and the texels that interpolation reaches from it.
      const cv::Rect rect = cv::Rect(bx * kBlock - 1, by * kBlock - 1, kBlock + 2, kBlock + 2) &
                            cv::Rect(0, 0, coverage.cols, coverage.rows);
      double low = 0.0;
      double high = 0.0;
      cv::minMaxLoc(coverage(rect), &low, &high);
      blocks.at<uint8_t>(by, bx) = low == 255 ? 255 : (high == 0 ? 0 : kMixed);
    }
  }
}

bool AlphaMask::Interpolate(float x, float y, int x0, int y0) const {
  const int x1 = std::min(x0 + 1, coverage.cols - 1);
  const int y1 = std::min(y0 + 1, coverage.rows - 1);
  const float wx = x - x0;
  const float wy = y - y0;
  const uint8_t* row0 = coverage.ptr<uint8_t>(y0);
  const uint8_t* row1 = coverage.ptr<uint8_t>(y1);
  const float top = row0[x0] + wx * (row0[x1] - row0[x0]);
  const float bottom = row1[x0] + wx * (row1[x1] - row1[x0]);
  return top + wy * (bottom - top) >= 127.5f;
}

AlphaMask MakeTreeMask(Random& random, int size, double trunk_fraction) {
  AlphaMask mask;
  mask.coverage = cv::Mat::zeros(size, size, CV_8UC1);
  const double crown_bottom = size * (1.0 - trunk_fraction);
  // Trunk: from the ground up into the crown.
  const int trunk_half = std::max(1, size / 20);
  cv::rectangle(mask.coverage,
                cv::Point(size / 2 - trunk_half, static_cast<int>(crown_bottom * 0.7)),
                cv::Point(size / 2 + trunk_half, size - 1), cv::Scalar(255), cv::FILLED);
  // Crown: discs scattered in an ellipse over the trunk, each with a ragged rim (a polygon whose
  // radius wanders), so the silhouette has corners and concavities as foliage does.
  const double cx = size / 2.0;
  const double cy = crown_bottom / 2.0;
  const double rx = size * 0.42;
  const double ry = crown_bottom * 0.46;
  const int num_blobs = 9 + random.Index(6);
  for (int b = 0; b < num_blobs; ++b) {
    const double angle = random.Uniform(0.0, 2.0 * M_PI);
    const double reach = std::sqrt(random.Uniform()) * 0.6;
    const double bx = cx + reach * rx * std::cos(angle);
    const double by = cy + reach * ry * std::sin(angle);
    const double radius = size * random.Uniform(0.12, 0.22);
    std::vector<cv::Point> rim;
    const int num_points = 28;
    for (int k = 0; k < num_points; ++k) {
      const double a = 2.0 * M_PI * k / num_points;
      const double r = radius * random.Uniform(0.75, 1.05);
      rim.emplace_back(static_cast<int>(std::lround(bx + r * std::cos(a))),
                       static_cast<int>(std::lround(by + r * std::sin(a))));
    }
    cv::fillPoly(mask.coverage, std::vector<std::vector<cv::Point>>{rim}, cv::Scalar(255),
                 cv::LINE_AA);
  }
  mask.Finish();
  return mask;
}

AlphaMask MakeFenceMask(int slats, double fill, int texels_per_slat) {
  AlphaMask mask;
  const int width = std::max(1, slats) * texels_per_slat;
  const int height = 4 * texels_per_slat;
  mask.coverage = cv::Mat::zeros(height, width, CV_8UC1);
  const int slat_width = std::max(1, static_cast<int>(std::lround(fill * texels_per_slat)));
  for (int k = 0; k < slats; ++k) {
    const int x0 = k * texels_per_slat + (texels_per_slat - slat_width) / 2;
    mask.coverage.colRange(x0, x0 + slat_width).setTo(255);
  }
  const int rail = std::max(1, height / 16);
  for (double at : {0.2, 0.75}) {
    const int y0 = static_cast<int>(at * height);
    mask.coverage.rowRange(y0, std::min(height, y0 + rail)).setTo(255);
  }
  mask.Finish();
  return mask;
}

}  // namespace comic::render
