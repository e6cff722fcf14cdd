// Geometric verification of the matches of two frames without calibration: a fundamental matrix
// fitted by RANSAC (OpenCV's USAC: seven-point samples, MSAC scoring, local optimisation; single
// threaded and seeded, so deterministic), and the matches within a distance of their epipolar
// lines kept. A pair whose matches no epipolar geometry explains (too few inliers, or too small a
// fraction of them: random matches between unrelated views, repeated structure) loses all of
// them. The tracker applies it to frame pairs beyond the next frame (TrackerOptions::
// verify_min_gap), where a patch matcher across a wide viewpoint change accepts mostly chance
// matches that would otherwise link unrelated features into tracks.
//
//   MatchVerificationOptions options;                    // 2 px, >= 30 inliers, >= 25 %
//   std::vector<PatchMatch> kept = VerifyMatches(features1, features2, matches, options);
#pragma once

#include <cstdint>
#include <opencv2/core.hpp>
#include <vector>

#include "frontend/feature.h"
#include "frontend/matching/patch_matcher.h"

namespace comic::frontend {

struct MatchVerificationOptions {
  // RANSAC inlier threshold: distance of a match from its epipolar lines (Sampson), pixels.
  double max_error_px = 2.0;
  // A pair with fewer inliers than this, or a smaller inlier fraction, keeps no match.
  int min_num_inliers = 30;
  double min_inlier_ratio = 0.25;
  // RANSAC confidence (0..1) and iteration cap.
  double confidence = 0.999;
  int max_num_iterations = 2000;
  // Seed of the RANSAC random generator (< 2^31).
  uint32_t random_seed = 1;

  // Throws comic::Error(kInvalidArgument) naming the bad field.
  void Check() const;
};

// The matches (features1[index1], features2[index2]) consistent with the best fundamental matrix,
// order kept; empty when the pair fails (see above). Throws comic::Error(kInvalidArgument) for an
// index out of range or bad options.
// With `fundamental`, a kept pair also gives its fundamental matrix (x2ᵀ F x1 = 0, OpenCV pixel
// coordinates; untouched when the pair fails).
std::vector<PatchMatch> VerifyMatches(const FeatureSet& features1, const FeatureSet& features2,
                                      const std::vector<PatchMatch>& matches,
                                      const MatchVerificationOptions& options,
                                      cv::Matx33d* fundamental = nullptr);

}  // namespace comic::frontend
