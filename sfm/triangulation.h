// Triangulation of 3-D points from calibrated views: linear (DLT) estimation, the geometric checks
// the mapper applies (triangulation angle, positive depth, reprojection error), and a robust
// multi-view variant that tolerates wrong observations in a track. Stateless functions.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <vector>

#include "sfm/camera.h"
#include "sfm/rigid3d.h"

namespace comic::sfm {

// Linear (DLT) triangulation from two or more views: `cams_from_world[i]` observes the point at
// normalised image coordinates `points_normalized[i]` (K⁻¹ applied). std::nullopt if fewer than
// two views or the solution is at infinity.
std::optional<Eigen::Vector3d> TriangulatePointDlt(
    const std::vector<Rigid3d>& cams_from_world,
    const std::vector<Eigen::Vector2d>& points_normalized);

// Angle in degrees between the rays from two camera centres to a point.
double TriangulationAngleDeg(const Eigen::Vector3d& center1, const Eigen::Vector3d& center2,
                             const Eigen::Vector3d& point3D);

struct TriangulationOptions {
  // A point is kept only if some pair of its views sees it under at least this angle (degrees).
  double min_angle_deg = 1.5;
  // Every kept observation must reproject within this distance (pixels).
  double max_reprojection_error_px = 4.0;
  // Points farther than this multiple of the largest baseline between the views are rejected
  // (they are at infinity for this baseline and only add noise).
  double max_depth_to_baseline = 1000.0;
  // Minimum number of views that must agree on the point.
  int min_num_views = 2;

  void Check() const;
};

// One view of a point to triangulate: the camera, its pose and the observed pixel.
struct TriangulationView {
  const Camera* camera = nullptr;
  Rigid3d cam_from_world;
  Eigen::Vector2d point2D = Eigen::Vector2d::Zero();  // pixels, OpenCV convention
};

struct TriangulatedPoint {
  Eigen::Vector3d xyz = Eigen::Vector3d::Zero();
  std::vector<int> inlier_views;  // indices into the views, ascending
  double max_angle_deg = 0.0;     // largest triangulation angle among the inlier views
};

// Triangulates a point seen in `views` that may contain wrong observations: candidate pairs of
// views (all pairs up to 12 views, else the pairs with the first or last view and those half the
// track apart) are triangulated, the hypothesis agreed on by the most views (reprojection and
// positive depth) wins, and it is re-estimated from its inliers. Returns std::nullopt if no
// hypothesis passes the options' angle, depth, reprojection and view-count checks.
// Deterministic.
std::optional<TriangulatedPoint> TriangulateMultiView(const std::vector<TriangulationView>& views,
                                                      const TriangulationOptions& options);

}  // namespace comic::sfm
