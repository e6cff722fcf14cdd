// EstimateRotationOnlyPath on a synthetic panning camera with known rotations (pixel noise and
// wrong observations included), on a chain that breaks, and on a same-input rerun.
#include "sfm/rotation_only_path.h"

#include <gtest/gtest.h>

#include "io/core/error.h"
#include "sfm/synthetic_scene.h"

namespace comic::sfm {
namespace {

SyntheticScene Panning(int num_frames) {
  SyntheticSceneOptions options;
  options.motion = SyntheticMotion::kPureRotation;
  options.num_frames = num_frames;
  options.num_points = 500;
  return MakeSyntheticScene(options);
}

TEST(RotationOnlyPath, RecoversThePanningCamerasRotations) {
  const SyntheticScene scene = Panning(12);
  const RotationOnlyPath path = EstimateRotationOnlyPath(scene.tracks, scene.camera);
  ASSERT_EQ(path.num_registered, 12);
  EXPECT_EQ(path.num_inliers.size(), 11u);
  for (double rms : path.rms_error_px) EXPECT_LT(rms, 1.5);  // 0.5 px noise
  // Frame 0 is the identity: compare each frame's rotation relative to frame 0 with the truth.
  const Eigen::Quaterniond truth0 = scene.cams_from_world[0].rotation;
  for (int frame = 0; frame < 12; ++frame) {
    const Image& image = path.reconstruction.image(static_cast<image_t>(frame + 1));
    ASSERT_TRUE(image.registered) << frame;
    EXPECT_EQ(image.name, scene.tracks.frame_names[frame]);
    EXPECT_LT(image.cam_from_world.translation.norm(), 1e-12);
    const Eigen::Quaterniond truth = scene.cams_from_world[frame].rotation * truth0.inverse();
    const double error_deg =
        image.cam_from_world.rotation.angularDistance(truth) * 180.0 / 3.14159265358979;
    EXPECT_LT(error_deg, 0.1) << frame;
  }
  EXPECT_EQ(path.reconstruction.NumPoints3D(), 0u);
}

TEST(RotationOnlyPath, TheChainStopsWhereTooFewTracksLinkTheFrames) {
  SyntheticScene scene = Panning(8);
  // Cut every track between frames 4 and 5.
  std::vector<frontend::Track> cut;
  for (const frontend::Track& track : scene.tracks.tracks) {
    frontend::Track before, after;
    for (const frontend::TrackObservation& obs : track.observations) {
      (obs.frame <= 4 ? before : after).observations.push_back(obs);
    }
    for (frontend::Track* part : {&before, &after}) {
      if (!part->observations.empty()) cut.push_back(*part);
    }
  }
  scene.tracks.tracks = cut;
  const RotationOnlyPath path = EstimateRotationOnlyPath(scene.tracks, scene.camera);
  EXPECT_EQ(path.num_registered, 5);
  EXPECT_TRUE(path.reconstruction.image(5).registered);
  EXPECT_FALSE(path.reconstruction.image(6).registered);
  EXPECT_FALSE(path.reconstruction.image(8).registered);
}

TEST(RotationOnlyPath, SameTracksSamePathAndBadOptionsAreRefused) {
  const SyntheticScene scene = Panning(5);
  const RotationOnlyPath a = EstimateRotationOnlyPath(scene.tracks, scene.camera);
  const RotationOnlyPath b = EstimateRotationOnlyPath(scene.tracks, scene.camera);
  for (image_t id = 1; id <= 5; ++id) {
    EXPECT_TRUE(a.reconstruction.image(id).cam_from_world.rotation.coeffs() ==
                b.reconstruction.image(id).cam_from_world.rotation.coeffs());
  }
  RotationOnlyPathOptions options;
  options.max_error_px = 0.0;
  EXPECT_THROW(EstimateRotationOnlyPath(scene.tracks, scene.camera, options), Error);
}

}  // namespace
}  // namespace comic::sfm
