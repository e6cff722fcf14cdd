#include "frontend/evaluation/region_labels.h"

#include <cmath>
#include <opencv2/imgproc.hpp>

#include "io/core/error.h"

namespace comic::frontend {

const char* RegionLabelName(RegionLabel label) {
  switch (label) {
    case RegionLabel::kOutside:
      return "outside";
    case RegionLabel::kBoundary:
      return "boundary";
    case RegionLabel::kInterior:
      return "interior";
  }
  return "?";
}

cv::Mat LabelRegion(const cv::Mat& mask, double band) {
  COMIC_CHECK(!mask.empty() && mask.type() == CV_8UC1, kInvalidArgument,
              "region labels: the mask must be a non-empty CV_8UC1 image");
  COMIC_CHECK(band > 0, kInvalidArgument, "region labels: band must be > 0 px, got " << band);
  const cv::Mat inside = mask != 0;
  cv::Mat labels(mask.size(), CV_8UC1, cv::Scalar(static_cast<int>(RegionLabel::kOutside)));
  const int count = cv::countNonZero(inside);
  if (count == 0) return labels;
  if (count == static_cast<int>(mask.total())) {
    labels.setTo(static_cast<int>(RegionLabel::kInterior));
    return labels;
  }
  // Distance of every pixel to the nearest pixel of the other class (exact Euclidean).
  cv::Mat to_outside, to_inside;
  cv::distanceTransform(inside, to_outside, cv::DIST_L2, cv::DIST_MASK_PRECISE);
  const cv::Mat outside = inside == 0;
  cv::distanceTransform(outside, to_inside, cv::DIST_L2, cv::DIST_MASK_PRECISE);
  const float limit = static_cast<float>(band);
  for (int y = 0; y < mask.rows; ++y) {
    const uint8_t* in = inside.ptr<uint8_t>(y);
    const float* d_out = to_outside.ptr<float>(y);
    const float* d_in = to_inside.ptr<float>(y);
    uint8_t* label = labels.ptr<uint8_t>(y);
    for (int x = 0; x < mask.cols; ++x) {
      const float distance = in[x] ? d_out[x] : d_in[x];
      if (distance <= limit) {
        label[x] = static_cast<uint8_t>(RegionLabel::kBoundary);
      } else if (in[x]) {
        label[x] = static_cast<uint8_t>(RegionLabel::kInterior);
      }
    }
  }
  return labels;
}

std::vector<RegionLabel> LabelFeatures(const cv::Mat& labels, const FeatureSet& features) {
  COMIC_CHECK(!labels.empty() && labels.type() == CV_8UC1, kInvalidArgument,
              "region labels: label map must be a non-empty CV_8UC1 image");
  std::vector<RegionLabel> result;
  result.reserve(features.size());
  for (const Feature& f : features) {
    const int x = static_cast<int>(std::lround(f.x));
    const int y = static_cast<int>(std::lround(f.y));
    if (x < 0 || y < 0 || x >= labels.cols || y >= labels.rows) {
      result.push_back(RegionLabel::kOutside);
    } else {
      result.push_back(static_cast<RegionLabel>(labels.at<uint8_t>(y, x)));
    }
  }
  return result;
}

cv::Mat EvaluatedRegionMask(const cv::Mat& labels) {
  return labels != static_cast<int>(RegionLabel::kOutside);
}

}  // namespace comic::frontend
