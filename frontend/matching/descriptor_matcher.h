// Matching of two frames' descriptors (frontend/description/sift_descriptor.h) as COLMAP 3.8's
// exhaustive matcher does (SiftMatchingOptions): for every descriptor its nearest neighbour by
// angle, kept when the angle is at most max_distance and below max_ratio times the second
// nearest's (Lowe's ratio test), and with cross_check only when it is also the other way round.
// The angle between two descriptors is acos(dot / 512²) (descriptors have length ≈ 512).
//
//   std::vector<PatchMatch> matches = MatchDescriptors(descriptors1, descriptors2, {});
//   // matches[k].index1 / index2: rows of descriptors1 / descriptors2; cost: the angle (rad)
//
// Brute force, exact: the dot products of the uint8 descriptors are sums of integers below 2^24,
// which single-precision matrix products hold exactly in any summation order, so the result does
// not depend on the CPU's vector width or the thread count.
#pragma once

#include <opencv2/core.hpp>
#include <vector>

#include "frontend/matching/patch_matcher.h"

namespace comic::frontend {

struct DescriptorMatchOptions {
  // Largest angle between matched descriptors (radians; COLMAP: 0.7).
  double max_distance = 0.7;
  // Lowe's ratio: the nearest's angle must be below max_ratio × the second nearest's (0.8).
  double max_ratio = 0.8;
  // Keep a match only if each descriptor is the other's accepted nearest neighbour (COLMAP: on).
  bool cross_check = true;

  // Throws comic::Error(kInvalidArgument) naming the bad field.
  void Check() const;
};

// The matches between the rows of `descriptors1` and `descriptors2` (both CV_8UC1, 128 columns;
// either may have no rows), ordered by index1, cost = angle in radians. Throws
// comic::Error(kInvalidArgument) for other types or widths.
std::vector<PatchMatch> MatchDescriptors(const cv::Mat& descriptors1, const cv::Mat& descriptors2,
                                         const DescriptorMatchOptions& options = {});

// Guided matching (COLMAP's SiftMatchingOptions::guided_matching): as MatchDescriptors, but a
// descriptor's candidates are only the features of the other frame within `max_error_px` of its
// epipolar line (both ways; x2ᵀ F x1 = 0, OpenCV pixel coordinates), so the ratio test compares
// the nearest with the second nearest *along the line*: a match that a look-alike elsewhere in
// the image made ambiguous is kept. For a pair whose geometry is known (verified).
// `features1`/`features2` give the positions of the rows of `descriptors1`/`descriptors2`.
// Throws comic::Error(kInvalidArgument) for sizes that differ or bad options.
std::vector<PatchMatch> MatchDescriptorsAlongEpipolarLines(
    const cv::Mat& descriptors1, const cv::Mat& descriptors2, const FeatureSet& features1,
    const FeatureSet& features2, const cv::Matx33d& fundamental, double max_error_px,
    const DescriptorMatchOptions& options = {});

// The dot products of every row of `descriptors1` with every row of `descriptors2`: a
// rows1 × rows2 CV_32F matrix of exact integers. Exposed for tests and for callers that match one
// frame against several.
cv::Mat DescriptorDotProducts(const cv::Mat& descriptors1, const cv::Mat& descriptors2);

}  // namespace comic::frontend
