// Synthetic scenes with known cameras for tests and benchmarks (as COLMAP's scene/synthetic.h):
// random 3-D points, a camera path like a video, and the feature tracks a tracker would produce
// from them, with pixel noise, wrong observations and tracks that break. Seeded and
// deterministic.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <utility>
#include <vector>

#include "frontend/matching/track.h"
#include "sfm/camera.h"
#include "sfm/rigid3d.h"

namespace comic::sfm {

enum class SyntheticMotion {
  kHandHeld,      // sideways walk around an object with bobbing and a wandering gaze
  kForward,       // driving straight ahead down a street (~1.2 m per frame, like KITTI)
  kPureRotation,  // panning on the spot: no parallax at all
};

struct SyntheticSceneOptions {
  SyntheticMotion motion = SyntheticMotion::kHandHeld;
  int num_frames = 30;
  int num_points = 1500;
  int width = 640;       // pixels
  int height = 480;      // pixels
  double focal = 600.0;  // pixels (fx = fy), principal point at the image centre
  // The camera model the frames are rendered through (sfm/camera_model.h) and its distortion
  // (coefficients the model lacks must stay 0); focal_y != 0 sets fy apart from fx (two-focal
  // models only).
  CameraModelId model = CameraModelId::kPinhole;
  double focal_y = 0.0;
  double k1 = 0.0, k2 = 0.0, p1 = 0.0, p2 = 0.0;
  // Gaussian pixel noise on every observation, standard deviation in pixels.
  double noise_px = 0.5;
  // Fraction of observations replaced by a uniformly random pixel (wrong matches in a track).
  double outlier_ratio = 0.1;
  // Per frame, the chance that the tracker loses a feature and starts a new track for it.
  double track_break_probability = 0.03;
  uint32_t seed = 1;

  void Check() const;
};

struct SyntheticScene {
  Camera camera;
  std::vector<Rigid3d> cams_from_world;   // ground truth, one per frame
  std::vector<Eigen::Vector3d> points3D;  // ground truth, world coordinates
  frontend::FeatureTracks tracks;
  std::vector<int> track_point_index;  // per track: its point in points3D
  // Per frame, per feature: true if the observation was replaced by an outlier.
  std::vector<std::vector<bool>> is_outlier;

  // Sum of distances between consecutive camera centres.
  double PathLength() const;
};

// Throws comic::Error(kInvalidArgument) for invalid options.
SyntheticScene MakeSyntheticScene(const SyntheticSceneOptions& options);

// A scene along a given camera path among given points (a pan, a stretch that sees no texture, a
// return to an earlier view): the tracks as MakeSyntheticScene makes them, with the options'
// camera, noise, outliers, track breaks and seed (motion, num_frames and num_points are not
// used). A frame that sees no point has no features.
SyntheticScene MakeSyntheticSceneFromPath(const SyntheticSceneOptions& options,
                                          std::vector<Rigid3d> cams_from_world,
                                          std::vector<Eigen::Vector3d> points3D);

// What a feature matcher would find between two frames of `scene` that the tracks do not link:
// pairs (feature in frame1, feature in frame2) observing the same point (wrong observations
// included, as a matcher's mistakes), for points whose viewing directions from the two cameras
// differ by at most max_view_angle_deg (a matcher's invariance).
std::vector<std::pair<int, int>> MatchSyntheticFrames(const SyntheticScene& scene, int frame1,
                                                      int frame2, double max_view_angle_deg = 30.0);

// The pose of a camera at `center` looking at `target`, image y axis as close to world +y as
// possible (y down, as in KITTI and OpenCV).
Rigid3d LookAt(const Eigen::Vector3d& center, const Eigen::Vector3d& target);

}  // namespace comic::sfm
