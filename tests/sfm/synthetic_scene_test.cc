// Synthetic scenes: tracks a tracker could have produced, with the noise and outliers asked for.
#include "sfm/synthetic_scene.h"

#include <gtest/gtest.h>

#include "io/error.h"
#include "sfm/reconstruction.h"

namespace comic::sfm {
namespace {

TEST(SyntheticScene, TracksMatchTheirPointsUpToNoiseAndOutliers) {
  SyntheticSceneOptions options;
  options.num_frames = 10;
  options.num_points = 300;
  const SyntheticScene scene = MakeSyntheticScene(options);
  EXPECT_NO_THROW(scene.tracks.Check());
  ASSERT_EQ(scene.cams_from_world.size(), 10u);
  ASSERT_EQ(scene.track_point_index.size(), scene.tracks.tracks.size());
  size_t observations = 0, outliers = 0;
  double squared_error = 0;
  for (size_t t = 0; t < scene.tracks.tracks.size(); ++t) {
    for (const frontend::TrackObservation& obs : scene.tracks.tracks[t].observations) {
      const frontend::Feature& feature = scene.tracks.FeatureOf(obs);
      const auto projection = ProjectPoint(scene.camera, scene.cams_from_world[obs.frame],
                                           scene.points3D[scene.track_point_index[t]]);
      ASSERT_TRUE(projection.has_value());
      ++observations;
      if (scene.is_outlier[obs.frame][obs.feature]) {
        ++outliers;
      } else {
        squared_error += (*projection - Eigen::Vector2d(feature.x, feature.y)).squaredNorm();
      }
    }
  }
  const double outlier_ratio = static_cast<double>(outliers) / observations;
  EXPECT_NEAR(outlier_ratio, 0.1, 0.02);
  // Per-axis noise of 0.5 px: mean squared 2-D error 0.5.
  EXPECT_NEAR(squared_error / (observations - outliers), 0.5, 0.05);
  EXPECT_GT(scene.PathLength(), 5.0);
}

TEST(SyntheticScene, SeededAndValidated) {
  SyntheticSceneOptions options;
  options.num_frames = 5;
  options.num_points = 50;
  const SyntheticScene a = MakeSyntheticScene(options);
  const SyntheticScene b = MakeSyntheticScene(options);
  ASSERT_EQ(a.tracks.features.size(), b.tracks.features.size());
  EXPECT_EQ(a.tracks.features[3][7].x, b.tracks.features[3][7].x);
  options.seed = 2;
  const SyntheticScene c = MakeSyntheticScene(options);
  EXPECT_NE(a.points3D[0], c.points3D[0]);
  options.outlier_ratio = 1.0;
  EXPECT_THROW(MakeSyntheticScene(options), Error);
  // Forward motion goes 1.2 m per frame along +z.
  SyntheticSceneOptions forward;
  forward.motion = SyntheticMotion::kForward;
  forward.num_frames = 6;
  forward.num_points = 50;
  const SyntheticScene f = MakeSyntheticScene(forward);
  EXPECT_NEAR(ProjectionCenter(f.cams_from_world[5]).z(), 6.0, 1e-9);
}

}  // namespace
}  // namespace comic::sfm
