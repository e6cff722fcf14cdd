#include "frontend/evaluation/threshold_equalisation.h"

#include <algorithm>
#include <cmath>
#include <functional>

#include "io/core/error.h"

namespace comic::frontend {
namespace {

void CheckRegion(const cv::Size& image_size, const cv::Mat& region) {
  COMIC_CHECK(image_size.width > 0 && image_size.height > 0, kInvalidArgument,
              "threshold equalisation: image size must be positive");
  COMIC_CHECK(region.empty() || (region.type() == CV_8UC1 && region.size() == image_size),
              kInvalidArgument,
              "threshold equalisation: the region mask must be CV_8UC1 of the image's size ("
                  << image_size.width << "x" << image_size.height << "), got " << region.cols << "x"
                  << region.rows);
}

bool Counted(const Feature& f, const cv::Size& image_size, const cv::Mat& region) {
  if (!PatchFits(f, image_size)) return false;
  if (region.empty()) return true;
  return region.at<uint8_t>(static_cast<int>(std::lround(f.y)),
                            static_cast<int>(std::lround(f.x))) != 0;
}

}  // namespace

ThresholdCut EqualiseThreshold(const FeatureSet& features, int target, const cv::Size& image_size,
                               const cv::Mat& region) {
  COMIC_CHECK(target >= 1, kInvalidArgument,
              "threshold equalisation: target count must be >= 1, got " << target);
  CheckRegion(image_size, region);
  std::vector<float> responses;
  for (const Feature& f : features) {
    if (Counted(f, image_size, region)) responses.push_back(f.response);
  }
  std::sort(responses.begin(), responses.end(), std::greater<float>());
  ThresholdCut cut;
  cut.target = target;
  cut.available = static_cast<int>(responses.size());
  if (cut.available <= target) {
    // Too few: the detector uses everything it returns (paper §5.1).
    cut.reached = cut.available == target;
    cut.count = cut.available;
    return cut;
  }
  cut.reached = true;
  const float r = responses[target - 1];
  // c_hi: features >= r; c_lo: features > r (responses sorted descending).
  const int c_hi = static_cast<int>(
      std::upper_bound(responses.begin(), responses.end(), r, std::greater<float>()) -
      responses.begin());
  const int c_lo = static_cast<int>(
      std::lower_bound(responses.begin(), responses.end(), r, std::greater<float>()) -
      responses.begin());
  if (c_lo == 0 || c_hi - target <= target - c_lo) {
    cut.min_response = r;
    cut.count = c_hi;
  } else {
    cut.min_response = responses[c_lo - 1];  // the smallest response above r
    cut.count = c_lo;
  }
  return cut;
}

FeatureSet ApplyThreshold(const FeatureSet& features, float min_response) {
  FeatureSet kept;
  for (const Feature& f : features) {
    if (f.response >= min_response) kept.push_back(f);
  }
  return kept;
}

int CountCountedFeatures(const FeatureSet& features, const cv::Size& image_size,
                         const cv::Mat& region) {
  CheckRegion(image_size, region);
  int count = 0;
  for (const Feature& f : features) count += Counted(f, image_size, region) ? 1 : 0;
  return count;
}

}  // namespace comic::frontend
