// Camera pose from 2-D–3-D correspondences: PnP RANSAC (OpenCV's AP3P minimal solver inside its
// RANSAC, which seeds its generator with a fixed value) followed by Levenberg–Marquardt refinement
// on the inliers. Stateless.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <vector>

#include "sfm/camera.h"
#include "sfm/rigid3d.h"

namespace comic::sfm {

struct AbsolutePoseOptions {
  // RANSAC inlier threshold on the reprojection error, pixels.
  double max_error_px = 4.0;
  // RANSAC confidence (0..1).
  double confidence = 0.9999;
  // Maximum number of RANSAC iterations.
  int max_num_iterations = 1000;
  // Fewer inliers than this: no pose.
  int min_num_inliers = 15;
  // Inliers / correspondences below this: no pose (a pose fitting few of many points is a guess).
  double min_inlier_ratio = 0.25;

  void Check() const;
};

struct AbsolutePose {
  Rigid3d cam_from_world;
  std::vector<char> inlier_mask;  // per correspondence, after refinement
  int num_inliers = 0;
};

// Estimates cam_from_world from pixels (OpenCV convention) and world points of the same size
// (comic::Error otherwise). std::nullopt when too few correspondences or inliers; then
// `num_inliers_found` (if given) says how many inliers the best pose had (0 when RANSAC found
// none), so that a failure can be reported with its margin.
std::optional<AbsolutePose> EstimateAbsolutePose(const Camera& camera,
                                                 const std::vector<Eigen::Vector2d>& points2D,
                                                 const std::vector<Eigen::Vector3d>& points3D,
                                                 const AbsolutePoseOptions& options,
                                                 int* num_inliers_found = nullptr);

}  // namespace comic::sfm
