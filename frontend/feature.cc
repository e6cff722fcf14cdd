#include "frontend/feature.h"

#include <algorithm>
#include <cmath>

namespace comic::frontend {

void SortByResponse(FeatureSet* features) {
  std::stable_sort(features->begin(), features->end(), [](const Feature& a, const Feature& b) {
    if (a.response != b.response) return a.response > b.response;
    if (a.y != b.y) return a.y < b.y;
    return a.x < b.x;
  });
}

bool PatchFits(const Feature& feature, const cv::Size& size) {
  const int cx = static_cast<int>(std::lround(feature.x));
  const int cy = static_cast<int>(std::lround(feature.y));
  return cx - kPatchRadius >= 0 && cy - kPatchRadius >= 0 && cx + kPatchRadius < size.width &&
         cy + kPatchRadius < size.height;
}

}  // namespace comic::frontend
