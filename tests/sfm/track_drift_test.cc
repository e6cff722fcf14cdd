#include "sfm/track_drift.h"

#include <gtest/gtest.h>

#include "sfm/synthetic_scene.h"

namespace comic::sfm {
namespace {

SyntheticScene ExactScene() {
  SyntheticSceneOptions options;
  options.num_frames = 8;
  options.num_points = 200;
  options.noise_px = 0.0;
  options.outlier_ratio = 0.0;
  options.track_break_probability = 0.0;
  return MakeSyntheticScene(options);
}

// Every frame registered at its true pose (image k + 1 is frame k).
Reconstruction TrueModel(const SyntheticScene& scene) {
  Reconstruction model;
  const camera_t camera_id = model.AddCamera(scene.camera);
  for (size_t frame = 0; frame < scene.cams_from_world.size(); ++frame) {
    Image image;
    image.image_id = static_cast<image_t>(frame + 1);
    image.camera_id = camera_id;
    image.name = "frame" + std::to_string(frame);
    image.cam_from_world = scene.cams_from_world[frame];
    model.AddImage(image);
    model.RegisterImage(image.image_id);
  }
  return model;
}

TEST(TrackDrift, ATrackOfOnePointHasNoDriftAndASlidingOneHas) {
  SyntheticScene scene = ExactScene();
  ASSERT_GE(scene.tracks.tracks.size(), 2u);
  // Track 0 slides 1.5 px further down in each frame, as a T-junction moving along an upright
  // silhouette while the camera moves sideways.
  const frontend::Track& sliding = scene.tracks.tracks[0];
  ASSERT_GE(sliding.Length(), 4u);
  for (size_t o = 0; o < sliding.observations.size(); ++o) {
    const frontend::TrackObservation& obs = sliding.observations[o];
    scene.tracks.features[obs.frame][obs.feature].y += 1.5f * static_cast<float>(o);
  }
  const std::vector<std::optional<double>> drift =
      MeasureTrackDrift(scene.tracks, TrueModel(scene));
  ASSERT_EQ(drift.size(), scene.tracks.tracks.size());
  ASSERT_TRUE(drift[0].has_value());
  EXPECT_GT(*drift[0], 0.5);
  int measured = 0;
  for (size_t t = 1; t < drift.size(); ++t) {
    if (!drift[t]) continue;
    ++measured;
    EXPECT_LT(*drift[t], 1e-3) << "track " << t;
  }
  EXPECT_GT(measured, 100);
}

TEST(TrackDrift, OnlyRegisteredFramesCountAndTooFewViewsGiveNone) {
  const SyntheticScene scene = ExactScene();
  Reconstruction model = TrueModel(scene);
  for (image_t id = 3; id <= scene.cams_from_world.size(); ++id) model.DeRegisterImage(id);
  // Frames 0 and 1 are all that remain registered: two views, fewer than three.
  for (const std::optional<double>& d : MeasureTrackDrift(scene.tracks, model)) {
    EXPECT_FALSE(d.has_value());
  }
  const std::vector<std::optional<double>> two_views = MeasureTrackDrift(scene.tracks, model, 2);
  EXPECT_TRUE(std::any_of(two_views.begin(), two_views.end(),
                          [](const std::optional<double>& d) { return d.has_value(); }));
}

}  // namespace
}  // namespace comic::sfm
