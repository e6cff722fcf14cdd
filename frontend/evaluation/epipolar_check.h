// Ground truth for frame-to-frame matches of a calibrated, posed sequence (KITTI): a match is
// consistent when the second point lies within a tolerance of the epipolar line of the first.
// Forward motion caveat: all epipolar lines pass through the epipole (near the image centre for a
// car driving straight), so a wrong match displaced along the line — e.g. radially, near the
// epipole — still passes. Epipolar precision is therefore an upper bound on the true precision.
//
//   cv::Matx33d K = ScaleIntrinsics(kitti_K, {1226, 370}, frame_size);   // frames resized
//   cv::Matx33d F = FundamentalFromPoses(K, world_from_camera[i], world_from_camera[i + 1]);
//   bool ok = EpipolarDistance(F, x_i, x_i1) <= 1.0;
#pragma once

#include <opencv2/core.hpp>
#include <vector>

#include "frontend/matching/patch_matcher.h"

namespace comic::frontend {

// Intrinsics of images resized from `from` to `to` (per-axis factors, as cv::resize maps them:
// pixel areas scale, so c' = (c + 0.5)·s − 0.5 and f' = f·s). Throws comic::Error
// (kInvalidArgument) for non-positive sizes.
cv::Matx33d ScaleIntrinsics(const cv::Matx33d& K, const cv::Size& from, const cv::Size& to);

// The fundamental matrix F with x_bᵀ F x_a = 0 for the images of one camera K at two poses given
// camera-to-world ([R | t]: X_world = R X_cam + t, KITTI's poses.txt convention).
cv::Matx33d FundamentalFromPoses(const cv::Matx33d& K, const cv::Matx34d& world_from_camera_a,
                                 const cv::Matx34d& world_from_camera_b);

// Distance in pixels of `b` from the epipolar line F·a in image b.
double EpipolarDistance(const cv::Matx33d& F, const cv::Point2f& a, const cv::Point2f& b);

// For each match, whether features_b[index2] lies within `tolerance` pixels of the epipolar line
// of features_a[index1].
std::vector<bool> EpipolarConsistency(const cv::Matx33d& F, const FeatureSet& features_a,
                                      const FeatureSet& features_b,
                                      const std::vector<PatchMatch>& matches, double tolerance);

}  // namespace comic::frontend
