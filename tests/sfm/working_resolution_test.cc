// The working resolution: the scale that caps an image's larger side, the resize height a
// sequence needs, and tracks and models scaled there and back in pixel areas (a pixel centre c
// maps to (c + 0.5) s - 0.5, as Camera::Scaled).
#include "sfm/working_resolution.h"

#include <gtest/gtest.h>

#include "io/core/error.h"
#include "sfm/synthetic_scene.h"

namespace comic::sfm {
namespace {

TEST(WorkingResolution, CapsTheLargerSide) {
  EXPECT_EQ(WorkingScale(640, 480, 1280), 1.0);
  EXPECT_EQ(WorkingScale(1226, 370, 1280), 1.0);  // KITTI stays as it is
  EXPECT_DOUBLE_EQ(WorkingScale(3072, 2048, 1280), 1280.0 / 3072.0);
  EXPECT_DOUBLE_EQ(WorkingScale(1080, 1920, 1280), 1280.0 / 1920.0);  // portrait
  EXPECT_EQ(WorkingScale(3072, 2048, 0), 1.0);                        // 0: any size
  EXPECT_EQ(WorkingResizeHeight(cv::Size(640, 480), 1280), 0);
  EXPECT_EQ(WorkingResizeHeight(cv::Size(3072, 2048), 1280), 853);  // Herz-Jesu: 1280 x 853
  EXPECT_EQ(WorkingResizeHeight(cv::Size(1920, 1080), 1280), 720);
}

TEST(WorkingResolution, TracksAndModelsGoThereAndBack) {
  SyntheticSceneOptions options;
  options.num_frames = 3;
  options.num_points = 50;
  const SyntheticScene scene = MakeSyntheticScene(options);
  const frontend::FeatureTracks half = ScaleTracks(scene.tracks, 0.5);
  EXPECT_EQ(half.image_size, cv::Size(320, 240));
  const frontend::Feature& original = scene.tracks.features[1][4];
  const frontend::Feature& scaled = half.features[1][4];
  EXPECT_FLOAT_EQ(scaled.x, (original.x + 0.5f) * 0.5f - 0.5f);
  EXPECT_FLOAT_EQ(scaled.y, (original.y + 0.5f) * 0.5f - 0.5f);
  EXPECT_EQ(half.tracks.size(), scene.tracks.tracks.size());

  Reconstruction model;
  const camera_t camera_id = model.AddCamera(scene.camera.Scaled(0.5));
  Image image;
  image.camera_id = camera_id;
  image.points2D.push_back({Eigen::Vector2d(scaled.x, scaled.y)});
  const image_t image_id = model.AddImage(image);
  ASSERT_TRUE(ResizedReconstruction(model, 640, 480).has_value());
  const Reconstruction back = *ResizedReconstruction(model, 640, 480);
  // Already that size, or no camera: nothing to copy.
  EXPECT_FALSE(ResizedReconstruction(back, 640, 480).has_value());
  EXPECT_FALSE(ResizedReconstruction(Reconstruction(), 640, 480).has_value());
  const Camera& camera = back.cameras().begin()->second;
  EXPECT_EQ(camera.width, 640);
  EXPECT_EQ(camera.height, 480);
  EXPECT_NEAR(camera.fx, scene.camera.fx, 1e-9);
  EXPECT_NEAR(camera.cx, scene.camera.cx, 1e-9);
  EXPECT_NEAR(back.image(image_id).points2D[0].xy.x(), original.x, 1e-4);
  EXPECT_NEAR(back.image(image_id).points2D[0].xy.y(), original.y, 1e-4);
  // The exact size, whatever the rounding of the scaled one.
  const Camera odd = ResizedCamera(Camera::FromImageSize(1281, 853), 3075, 2048);
  EXPECT_EQ(odd.width, 3075);
  EXPECT_EQ(odd.height, 2048);
  EXPECT_THROW(ScaleTracks(scene.tracks, 0.0), Error);
}

}  // namespace
}  // namespace comic::sfm
