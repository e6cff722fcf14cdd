// The camera path of a panning clip: when a homography explains every frame pair (the camera
// turns on the spot, no parallax, so no initial pair and no 3-D points), the rotations are still
// observable (Hartley & Zisserman §8.4.4: such views are related by H = K R K^-1). Each frame's
// rotation relative to the one before is fitted to the viewing rays of their shared tracks
// (Kabsch inside a two-ray RANSAC), and the rotations are chained from frame 0; every camera
// centre is the origin. Written by comic_sfm when the diagnosis says rotation only (issue 17),
// so that a failed run still shows what the frames allow.
//
//   const RotationOnlyPath path = EstimateRotationOnlyPath(tracks, camera);
//   if (path.num_registered > 1) WriteColmapTextModel(ToColmapTextModel(path.reconstruction), ...);
#pragma once

#include <Eigen/Core>
#include <optional>
#include <random>
#include <vector>

#include "frontend/matching/track.h"
#include "sfm/camera.h"
#include "sfm/reconstruction.h"

namespace comic::sfm {

struct RotationOnlyPathOptions {
  // A link between consecutive frames needs at least this many shared tracks consistent with one
  // rotation; the chain stops at the first frame without (later frames stay unregistered).
  int min_num_inliers = 30;
  // A ray pair is consistent when the rotated ray lands within this many pixels (at the focal
  // length) of the observed one.
  double max_error_px = 2.0;
  // RANSAC trials per link (fixed seed: the same tracks give the same path).
  int num_trials = 200;

  // Throws comic::Error(kInvalidArgument) naming the bad field.
  void Check() const;
};

struct RotationOnlyPath {
  // One camera; one image per frame named as the tracks name it (no 2-D points), registered
  // (cam_from_world a pure rotation) from frame 0 up to where the chain stops; no 3-D points.
  Reconstruction reconstruction;
  int num_registered = 0;
  // Per link i -> i + 1 that was made: inliers and their RMS error in pixels.
  std::vector<int> num_inliers;
  std::vector<double> rms_error_px;
};

// The rotation R with b_i ≈ R a_i for unit rays a_i, b_i: RANSAC over ray pairs drawn with
// `random`, then Kabsch refits on the inliers (rays within max_angle radians) twice.
struct RayRotation {
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  std::vector<int> inliers;
  double rms_angle = 0.0;  // of the inliers, radians
};
// std::nullopt with fewer than min_num_inliers inliers.
std::optional<RayRotation> EstimateRayRotation(const std::vector<Eigen::Vector3d>& a,
                                               const std::vector<Eigen::Vector3d>& b,
                                               double max_angle, int min_num_inliers,
                                               int num_trials, std::mt19937* random);

// Throws comic::Error(kInvalidArgument) for invalid tracks, camera or options.
RotationOnlyPath EstimateRotationOnlyPath(const frontend::FeatureTracks& tracks,
                                          const Camera& camera,
                                          const RotationOnlyPathOptions& options = {});

}  // namespace comic::sfm
