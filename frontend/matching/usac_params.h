// The one set of OpenCV USAC settings every robust two-view fit of the project uses (fundamental
// matrix in frontend/matching/match_verification, essential matrix and homography in
// sfm/two_view_geometry): RANSAC with MSAC scoring and inner local optimisation, so a model and its
// inlier mask come from a least-squares fit to the inliers rather than from a noisy minimal sample;
// single-threaded and seeded, so the result is the same bit for bit on every run.
//
//   cv::UsacParams params = DeterministicUsacParams(2.0, 0.999, 2000, 1);
//   cv::Mat F = cv::findFundamentalMat(points1, points2, mask, params);
#pragma once

#include <cstdint>
#include <opencv2/calib3d.hpp>

namespace comic::frontend {

// threshold: inlier distance in the units of the points given to the fit; confidence in (0, 1);
// max_iterations > 0; random_seed < 2^31. Throws comic::Error(kInvalidArgument) otherwise.
cv::UsacParams DeterministicUsacParams(double threshold, double confidence, int max_iterations,
                                       uint32_t random_seed);

}  // namespace comic::frontend
