// A CoMIC corner as the Feature both searches output (ComicDetector, ComicDirectDetector): its
// position, the detection scale s, the stability ρ as response (Eq. 1), the cornerness κ (§2.2),
// the MSICS's level, polarity and segment, and the side mask of its patch (§4).
//
//   CornerOnCurve corner;
//   corner.position = vertex;  corner.apex = apex;  corner.curve_threshold = level + 0.5;  ...
//   Feature feature = MakeCornerFeature(gray, options.scale, corner, segment);
#pragma once

#include <opencv2/core.hpp>
#include <vector>

#include "frontend/feature.h"

namespace comic::frontend {

// What a search knows of one settled corner.
struct CornerOnCurve {
  cv::Point2f position;     // the feature position (the vertex), sub-pixel
  double stability = 0.0;   // ρ (1/px)
  double cornerness = 0.0;  // κ
  int level = 0;            // the MSICS's integer level I
  Polarity polarity = Polarity::kNone;
  // The side mask follows the level line of the image at curve_threshold (I + 0.5, or the refined
  // threshold of the convergence) that passes nearest to apex, the κ maximum on the curve.
  cv::Point2f apex;
  double curve_threshold = 0.5;
};

// The Feature of `corner` found at detection scale `scale` (px) in `gray` (CV_8UC1), with
// `segment` (the MSICS samples around the corner) as its curve and the side mask of the patch
// centred on the rounded position.
Feature MakeCornerFeature(const cv::Mat& gray, double scale, const CornerOnCurve& corner,
                          const std::vector<cv::Point2f>& segment);

}  // namespace comic::frontend
