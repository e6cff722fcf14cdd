// Relative pose of two calibrated views from point correspondences: essential matrix RANSAC
// (OpenCV's USAC with the five-point solver and local optimisation), cheirality, and a homography
// check that flags planar scenes and rotation-only motion, both of which make the essential
// matrix unreliable for initialisation. Stateless; the RANSAC generator is seeded from the
// options, so results are deterministic for the same input.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "sfm/camera.h"
#include "sfm/rigid3d.h"

namespace comic::sfm {

struct TwoViewGeometryOptions {
  // RANSAC inlier threshold for the essential matrix and the homography, pixels.
  double max_error_px = 2.0;
  // RANSAC confidence (0..1).
  double confidence = 0.999;
  // Maximum number of RANSAC iterations.
  int max_num_iterations = 1000;
  // Fewer essential-matrix inliers than this: kDegenerate.
  int min_num_inliers = 15;
  // Homography inliers / essential inliers above this: kPlanarOrPanoramic.
  double max_homography_inlier_ratio = 0.8;
  // Seed of the RANSAC random generator (< 2^31).
  uint32_t random_seed = 1;

  void Check() const;
};

enum class TwoViewConfiguration {
  kDegenerate,         // too few correspondences or inliers, or no valid decomposition
  kPlanarOrPanoramic,  // a homography explains the matches: planar scene or pure rotation
  kCalibrated,         // a general relative pose
};

const char* TwoViewConfigurationName(TwoViewConfiguration configuration);

struct TwoViewGeometry {
  TwoViewConfiguration configuration = TwoViewConfiguration::kDegenerate;
  // Relative pose; the translation has unit length (scale is unobservable from two views).
  Rigid3d cam2_from_cam1;
  // Per correspondence: an essential-matrix inlier whose triangulation lies in front of both
  // cameras.
  std::vector<char> inlier_mask;
  int num_inliers = 0;            // count of inlier_mask
  int num_essential_inliers = 0;  // before the cheirality check
  int num_homography_inliers = 0;
  // The homography fitted to the correspondences in undistorted normalised coordinates (zero when
  // none was found): a near-planar pair's second relative pose comes from its decomposition
  // (sfm/planar_pose_ambiguity.h).
  Eigen::Matrix3d homography = Eigen::Matrix3d::Zero();
  double median_triangulation_angle_deg = 0.0;  // over the inliers
  // The inliers triangulated in camera 1's frame (unit baseline), in the order of inlier_mask,
  // and their triangulation angles (degrees).
  std::vector<Eigen::Vector3d> points3D;
  std::vector<double> triangulation_angles_deg;
};

// Estimates the relative pose of camera 2 with respect to camera 1 from pixel correspondences
// (OpenCV convention). points1 and points2 must have the same size (comic::Error otherwise).
TwoViewGeometry EstimateCalibratedTwoViewGeometry(const Camera& camera1, const Camera& camera2,
                                                  const std::vector<Eigen::Vector2d>& points1,
                                                  const std::vector<Eigen::Vector2d>& points2,
                                                  const TwoViewGeometryOptions& options);

}  // namespace comic::sfm
