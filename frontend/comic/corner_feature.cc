#include "frontend/comic/corner_feature.h"

#include <cmath>

#include "frontend/comic/side_mask.h"

namespace comic::frontend {

Feature MakeCornerFeature(const cv::Mat& gray, double scale, const CornerOnCurve& corner,
                          const std::vector<cv::Point2f>& segment) {
  Feature feature;
  feature.x = corner.position.x;
  feature.y = corner.position.y;
  feature.scale = static_cast<float>(scale);
  feature.response = static_cast<float>(corner.stability);
  feature.cornerness = static_cast<float>(corner.cornerness);
  feature.level = corner.level;
  feature.polarity = corner.polarity;
  feature.curve = segment;
  // The patch is centred on the rounded position of the feature as stored (float).
  const cv::Point centre(static_cast<int>(std::lround(feature.x)),
                         static_cast<int>(std::lround(feature.y)));
  feature.side_mask = ComputeSideMask(gray, corner.curve_threshold, corner.apex, centre);
  return feature;
}

}  // namespace comic::frontend
