// Poses for frames a model could not register: the rotation about a posed neighbour's centre
// when the camera only turned (checked against the true rotations of a panning camera), and
// interpolation between posed frames, flagged, where the camera moved.
#include "sfm/pose_gap_filling.h"

#include <gtest/gtest.h>

#include "io/core/error.h"
#include "sfm/synthetic_scene.h"
#include "sfm/trajectory_evaluation.h"

namespace comic::sfm {
namespace {

// A model of the scene's frames, those in `registered` at their true poses, without points.
Reconstruction ModelOf(const SyntheticScene& scene, const std::vector<int>& registered) {
  Reconstruction model;
  const camera_t camera_id = model.AddCamera(scene.camera);
  for (size_t frame = 0; frame < scene.tracks.NumFrames(); ++frame) {
    Image image;
    image.image_id = static_cast<image_t>(frame + 1);
    image.camera_id = camera_id;
    image.name = scene.tracks.frame_names[frame];
    for (const frontend::Feature& feature : scene.tracks.features[frame]) {
      image.points2D.push_back({Eigen::Vector2d(feature.x, feature.y)});
    }
    image.cam_from_world = scene.cams_from_world[frame];
    model.AddImage(std::move(image));
  }
  for (int frame : registered) model.RegisterImage(static_cast<image_t>(frame + 1));
  return model;
}

double RotationErrorDeg(const Rigid3d& a, const Rigid3d& b) {
  return a.rotation.angularDistance(b.rotation) * 180.0 / M_PI;
}

TEST(PoseGapFilling, APanningCameraGetsItsRotationsAboutTheCentre) {
  SyntheticSceneOptions options;
  options.motion = SyntheticMotion::kPureRotation;
  options.num_frames = 12;
  const SyntheticScene scene = MakeSyntheticScene(options);
  Reconstruction model = ModelOf(scene, {0, 1});
  const std::vector<char> fillable(12, 1);
  const PoseGapFilling filled = FillPoseGaps(scene.tracks, fillable, {}, &model);
  std::vector<int> expected;
  for (int frame = 2; frame < 12; ++frame) expected.push_back(frame);
  EXPECT_EQ(filled.rotation_only_frames, expected);
  EXPECT_TRUE(filled.interpolated_frames.empty());
  for (int frame : expected) {
    const Image& image = model.image(static_cast<image_t>(frame + 1));
    ASSERT_TRUE(image.registered);
    EXPECT_LT(RotationErrorDeg(image.cam_from_world, scene.cams_from_world[frame]), 0.1) << frame;
    EXPECT_LT(ProjectionCenter(image.cam_from_world).norm(), 1e-9);  // the centre it turns on
  }
  // Frames that are not fillable keep their state.
  Reconstruction other = ModelOf(scene, {0, 1});
  std::vector<char> only_the_next(12, 0);
  only_the_next[2] = 1;
  EXPECT_EQ(FillPoseGaps(scene.tracks, only_the_next, {}, &other).rotation_only_frames,
            std::vector<int>{2});
  EXPECT_FALSE(other.image(4).registered);
}

TEST(PoseGapFilling, AMovingCameraIsInterpolatedBetweenCloseFramesOnly) {
  SyntheticSceneOptions options;
  options.motion = SyntheticMotion::kHandHeld;
  options.num_frames = 20;
  const SyntheticScene scene = MakeSyntheticScene(options);
  // Frames 5-7 missing between posed 4 and 8; 11-18 missing between 10 and 19 (too far apart).
  std::vector<int> registered = {0, 1, 2, 3, 4, 8, 9, 10, 19};
  Reconstruction model = ModelOf(scene, registered);
  PoseGapFillingOptions gap_options;
  gap_options.max_interpolated_gap = 5;
  const PoseGapFilling filled =
      FillPoseGaps(scene.tracks, std::vector<char>(20, 1), gap_options, &model);
  // The camera walks 0.3 m per frame 10 m from the points: no rotation explains the parallax.
  EXPECT_TRUE(filled.rotation_only_frames.empty());
  EXPECT_EQ(filled.interpolated_frames, (std::vector<int>{5, 6, 7}));
  EXPECT_FALSE(model.image(12).registered);
  // A guess is returned, never registered in the model (issue 47).
  EXPECT_FALSE(model.image(7).registered);
  EXPECT_EQ(model.NumRegisteredImages(), registered.size());
  ASSERT_EQ(filled.interpolated_poses.size(), 3u);
  // Frame 6, halfway between frames 4 and 8: the mean of their centres.
  const Eigen::Vector3d middle = 0.5 * (ProjectionCenter(scene.cams_from_world[4]) +
                                        ProjectionCenter(scene.cams_from_world[8]));
  EXPECT_LT((ProjectionCenter(filled.interpolated_poses[1]) - middle).norm(), 1e-9);
  EXPECT_THROW(FillPoseGaps(scene.tracks, std::vector<char>(3, 1), {}, &model), Error);
}

}  // namespace
}  // namespace comic::sfm
