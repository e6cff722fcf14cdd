// Non-maximum suppression on a dense detector response (Harris cornerness, determinant of the
// Hessian): the local maxima of the map become candidate features carrying the map's value as
// their response, so a detection threshold is a cut-off applied later (threshold equalisation).
#pragma once

#include <opencv2/core.hpp>

#include "frontend/feature.h"

namespace comic::frontend {

struct ResponsePeakOptions {
  // A peak is the maximum of the (2·nms_radius + 1)² window around it, in pixels (1 = 3x3).
  int nms_radius = 1;
  // Only values strictly above this are peaks (0 keeps every positive maximum).
  float min_value = 0.0f;
  // Pixels closer than this to the image border are never peaks (their filter support was cut
  // by the border), in pixels.
  int border = 3;
  // Refine each peak by a 1-D parabola through its neighbours along x and along y (offsets
  // clamped to ±0.5 px).
  bool subpixel = true;

  // Throws comic::Error(kInvalidArgument) naming the bad field.
  void Check() const;
};

// Peaks of a CV_32FC1 map, each with `response` = the map value and `scale` = `feature_scale`,
// sorted strongest first (SortByResponse). On a plateau of equal values only the first pixel in
// raster order is a peak, so the result is a deterministic function of the map.
FeatureSet FindResponsePeaks(const cv::Mat& response, const ResponsePeakOptions& options,
                             float feature_scale);

}  // namespace comic::frontend
