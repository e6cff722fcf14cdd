// Threshold equalisation (paper §5.1): "we vary the threshold of each detector to get the same
// number of points in the first frame of the sequence ... For this value of the threshold,
// features are detected on all other images in the sequence. In cases where the detector returns
// very few points in general, the threshold is fixed to yield the maximum number of points it can
// return." Every Detector returns all candidates with a response, so one generic function picks
// each detector's response cut-off.
//
//   FeatureSet first = detector->Detect(frame0);                 // every candidate
//   ThresholdCut cut = EqualiseThreshold(first, 300, frame0.size(), object_region0);
//   FeatureSet kept = ApplyThreshold(detector->Detect(frame_i), cut.min_response);  // any frame
//
// Which features count. A feature counts towards the target only if its 23x23 matching patch fits
// in the image (PatchFits: a feature that can never be matched is dropped before counting) and,
// when a region mask is given, if the mask is non-zero at its rounded position.
//
// Ties at the cut-off. Responses can tie (FAST scores are integers; MSER's 1/(1 + v) is 1 for
// every region that does not grow at all), so "the N strongest" may not be a response cut-off.
// With r the N-th largest counted response, keeping every feature ≥ r gives c_hi ≥ N features and
// keeping every feature > r gives c_lo < N. The cut-off is the one whose count is closer to N;
// on equal distance, or when c_lo = 0, c_hi wins (the tie is kept). So the count equals N exactly
// whenever no tie straddles the N-th response.
#pragma once

#include <limits>
#include <opencv2/core.hpp>

#include "frontend/feature.h"

namespace comic::frontend {

// A response cut-off and what it gives on the frame it was chosen on.
struct ThresholdCut {
  // Keep features with response >= min_response; the lowest float (-FLT_MAX) keeps everything.
  float min_response = -std::numeric_limits<float>::max();
  int target = 0;     // the requested count N
  int available = 0;  // counted features before the cut (patch fits, inside the region)
  int count = 0;      // counted features the cut keeps
  // False when fewer than N features were available: the detector then uses all it has.
  bool reached = false;
};

// Picks the cut-off giving `target` counted features of `features` (one frame's candidates of
// any detector, in any order), by the rules above. `region` is a CV_8UC1 mask of `image_size`,
// or empty for the whole image. Throws comic::Error(kInvalidArgument) for target < 1, a
// non-positive image size, or a region of the wrong size or type.
ThresholdCut EqualiseThreshold(const FeatureSet& features, int target, const cv::Size& image_size,
                               const cv::Mat& region = cv::Mat());

// The features with response >= min_response, order kept.
FeatureSet ApplyThreshold(const FeatureSet& features, float min_response);

// The number of features EqualiseThreshold counts (patch fits, inside `region` if given).
int CountCountedFeatures(const FeatureSet& features, const cv::Size& image_size,
                         const cv::Mat& region = cv::Mat());

}  // namespace comic::frontend
