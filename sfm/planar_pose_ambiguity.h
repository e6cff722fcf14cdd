// A near-planar pair's second relative pose. Two views of a plane determine the relative pose only
// up to a two-fold ambiguity: the homography between them decomposes into two physically valid
// (rotation, translation, plane normal) triples, and both explain every point on the plane. The
// essential matrix of a scene that is nearly flat inherits the ambiguity: the five-point solver
// and RANSAC pick one of the two by the few points off the plane, and a model grown from the
// wrong one stays consistent (every later frame registers, every pair fits) while its cameras are
// turned degrees away from the truth. The other solution is returned here so that the mapper can
// grow a model from each and keep the one that explains more of the tracks
// (IncrementalPipelineOptions::grow_planar_alternative, off by default).
//
//   if (const auto other = OtherPlanarPose(camera, camera, points1, points2, geometry, options))
//     ... grow from *other as well ...
#pragma once

#include <Eigen/Core>
#include <optional>
#include <vector>

#include "sfm/camera.h"
#include "sfm/two_view_geometry.h"

namespace comic::sfm {

struct PlanarAmbiguityOptions {
  // Only a pair whose homography explains at least this share of the essential matrix's inliers
  // is near-planar enough to be ambiguous (a general scene's homography fits a few points).
  double min_homography_share = 0.5;
  // The other decomposition counts only when its rotation differs at least this much (degrees)
  // from the pose the essential matrix gave: otherwise the two poses are one.
  double min_rotation_difference_deg = 1.0;
  // The other pose must keep at least this share of the essential pose's inliers (in front of
  // both cameras, reprojecting within the two-view threshold).
  double min_inlier_share = 0.5;

  // Throws comic::Error(kInvalidArgument) naming the bad field.
  void Check() const;
};

// The other physically valid pose of `geometry`'s homography decomposition, with its inliers
// among `points1`/`points2` (pixels; those `geometry` was estimated from) triangulated as
// EstimateCalibratedTwoViewGeometry does; nullopt when the pair is not near-planar, has no
// homography, or the other pose is the same as or worse supported than `geometry`'s.
// `max_error_px` is the two-view inlier threshold. Deterministic.
std::optional<TwoViewGeometry> OtherPlanarPose(const Camera& camera1, const Camera& camera2,
                                               const std::vector<Eigen::Vector2d>& points1,
                                               const std::vector<Eigen::Vector2d>& points2,
                                               const TwoViewGeometry& geometry, double max_error_px,
                                               const PlanarAmbiguityOptions& options);

}  // namespace comic::sfm
