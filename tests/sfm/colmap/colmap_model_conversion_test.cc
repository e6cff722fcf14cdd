// Reconstruction <-> COLMAP text model: the pixel-centre shift, and a written model read back
// identically.
#include "sfm/colmap/colmap_model_conversion.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "io/colmap/colmap_binary_model.h"
#include "io/colmap/colmap_text_model.h"
#include "io/core/error.h"
#include "sfm/synthetic_scene.h"
#include "tests/test_support.h"

namespace comic::sfm {
namespace {

// A noise-free reconstruction of a small synthetic scene: ground-truth poses and points, every
// track as observations, one unregistered image.
Reconstruction MakeReconstruction() {
  SyntheticSceneOptions options;
  options.num_frames = 5;
  options.num_points = 60;
  options.noise_px = 0.0;
  options.outlier_ratio = 0.0;
  options.track_break_probability = 0.0;
  const SyntheticScene scene = MakeSyntheticScene(options);
  Reconstruction reconstruction;
  const camera_t camera_id = reconstruction.AddCamera(scene.camera);
  for (size_t frame = 0; frame < scene.tracks.NumFrames(); ++frame) {
    Image image;
    image.camera_id = camera_id;
    image.name = scene.tracks.frame_names[frame];
    image.cam_from_world = scene.cams_from_world[frame];
    for (const frontend::Feature& feature : scene.tracks.features[frame]) {
      Point2D point2D;
      point2D.xy = Eigen::Vector2d(feature.x, feature.y);
      image.points2D.push_back(point2D);
    }
    const image_t image_id = reconstruction.AddImage(image);
    if (frame != 3) reconstruction.RegisterImage(image_id);
  }
  for (size_t t = 0; t < scene.tracks.tracks.size(); ++t) {
    std::vector<TrackElement> track;
    for (const frontend::TrackObservation& obs : scene.tracks.tracks[t].observations) {
      if (obs.frame == 3) continue;
      track.push_back({static_cast<image_t>(obs.frame + 1), static_cast<point2D_t>(obs.feature)});
    }
    if (track.size() < 2) continue;
    reconstruction.AddPoint3D(scene.points3D[scene.track_point_index[t]], track,
                              {static_cast<uint8_t>(t % 256), 7, 200});
  }
  return reconstruction;
}

TEST(ColmapModelConversion, ShiftsPixelsByHalfAndUsesPinhole) {
  const Reconstruction reconstruction = MakeReconstruction();
  const io::ColmapTextModel model = ToColmapTextModel(reconstruction);
  ASSERT_EQ(model.cameras.size(), 1u);
  const Camera& camera = reconstruction.camera(1);
  EXPECT_EQ(model.cameras[0].model, "PINHOLE");
  EXPECT_EQ(model.cameras[0].params,
            (std::vector<double>{camera.fx, camera.fy, camera.cx + 0.5, camera.cy + 0.5}));
  // Only registered images are written.
  EXPECT_EQ(model.images.size(), 4u);
  for (const io::ColmapImage& image : model.images) EXPECT_NE(image.image_id, 4u);
  // In COLMAP's convention (its params, its keypoints) a point projects onto its keypoint.
  const io::ColmapCamera& c = model.cameras[0];
  int checked = 0;
  for (const io::ColmapPoint3D& point : model.points3D) {
    for (const io::ColmapTrackElement& element : point.track) {
      const auto image = std::find_if(model.images.begin(), model.images.end(), [&](const auto& i) {
        return i.image_id == element.image_id;
      });
      ASSERT_NE(image, model.images.end());
      const Eigen::Vector3d p =
          image->cam_from_world_rotation * point.xyz + image->cam_from_world_translation;
      const io::ColmapPoint2D& keypoint = image->points2D[element.point2D_idx];
      EXPECT_NEAR(c.params[0] * p.x() / p.z() + c.params[2], keypoint.x, 1e-3);
      EXPECT_NEAR(c.params[1] * p.y() / p.z() + c.params[3], keypoint.y, 1e-3);
      EXPECT_EQ(keypoint.point3D_id, static_cast<int64_t>(point.point3D_id));
      ++checked;
    }
    EXPECT_LT(point.error, 1e-3);
  }
  EXPECT_GT(checked, 100);
}

TEST(ColmapModelConversion, WrittenModelReadsBackIdentically) {
  const Reconstruction original = MakeReconstruction();
  const io::ColmapTextModel written = ToColmapTextModel(original);
  test::ScopedTempDir dir;
  io::WriteColmapTextModel(written, dir.path());
  const Reconstruction read = FromColmapTextModel(io::ReadColmapTextModel(dir.path()));

  // The files written again from what was read are byte for byte the same.
  const io::ColmapTextModel rewritten = ToColmapTextModel(read);
  EXPECT_EQ(io::ColmapCamerasText(rewritten), io::ColmapCamerasText(written));
  EXPECT_EQ(io::ColmapImagesText(rewritten), io::ColmapImagesText(written));
  EXPECT_EQ(io::ColmapPoints3DText(rewritten), io::ColmapPoints3DText(written));

  // And the reconstruction itself: same ids, poses, points, tracks, colours; pixels shifted back.
  EXPECT_EQ(read.NumRegisteredImages(), original.NumRegisteredImages());
  EXPECT_EQ(read.NumPoints3D(), original.NumPoints3D());
  for (image_t image_id : original.RegisteredImageIds()) {
    const Image& a = original.image(image_id);
    const Image& b = read.image(image_id);
    EXPECT_EQ(a.name, b.name);
    EXPECT_EQ(a.cam_from_world.translation, b.cam_from_world.translation);
    EXPECT_LT(RotationAngleDeg(a.cam_from_world.rotation, b.cam_from_world.rotation), 1e-9);
    ASSERT_EQ(a.points2D.size(), b.points2D.size());
    for (size_t i = 0; i < a.points2D.size(); ++i) {
      EXPECT_NEAR(a.points2D[i].xy.x(), b.points2D[i].xy.x(), 1e-12);
      EXPECT_NEAR(a.points2D[i].xy.y(), b.points2D[i].xy.y(), 1e-12);
      EXPECT_EQ(a.points2D[i].point3D_id, b.points2D[i].point3D_id);
    }
  }
  for (const auto& [point3D_id, point] : original.points3D()) {
    const Point3D& other = read.point3D(point3D_id);
    EXPECT_EQ(point.xyz, other.xyz);
    EXPECT_EQ(point.color, other.color);
    EXPECT_EQ(point.track, other.track);
  }
  EXPECT_NEAR(read.camera(1).cx, original.camera(1).cx, 1e-12);
}

// Issue 17: distorted cameras are read with their distortion (they used to be refused unless
// ignore_distortion dropped it); ignore_distortion still keeps only the pinhole part, and models
// outside the five are refused.
TEST(ColmapModelConversion, DistortedCamerasKeepTheirDistortion) {
  io::ColmapTextModel model;
  model.cameras.push_back({1, "SIMPLE_RADIAL", 640, 480, {500.0, 320.5, 240.5, 0.01}});
  const Reconstruction distorted = FromColmapTextModel(model);
  EXPECT_EQ(distorted.camera(1).model, CameraModelId::kSimpleRadial);
  EXPECT_DOUBLE_EQ(distorted.camera(1).k1, 0.01);
  EXPECT_DOUBLE_EQ(distorted.camera(1).cx, 320.0);
  const Reconstruction reconstruction = FromColmapTextModel(model, /*ignore_distortion=*/true);
  EXPECT_DOUBLE_EQ(reconstruction.camera(1).fx, 500.0);
  EXPECT_DOUBLE_EQ(reconstruction.camera(1).cx, 320.0);
  EXPECT_DOUBLE_EQ(reconstruction.camera(1).k1, 0.0);
  model.cameras[0].model = "FISHEYE";
  EXPECT_THROW(FromColmapTextModel(model, true), Error);
  model.cameras[0].model = "RADIAL";  // 5 parameters, 4 given
  EXPECT_THROW(FromColmapTextModel(model), Error);
}

// Every model is written with its COLMAP name and parameters (principal point + 0.5) and read
// back identically.
TEST(ColmapModelConversion, WritesEachCameraModelWithItsParameters) {
  const std::vector<std::pair<CameraModelId, std::vector<double>>> kCameras = {
      {CameraModelId::kSimplePinhole, {500, 319.5, 239.5}},
      {CameraModelId::kPinhole, {500, 510, 319.5, 239.5}},
      {CameraModelId::kSimpleRadial, {500, 319.5, 239.5, -0.1}},
      {CameraModelId::kRadial, {500, 319.5, 239.5, -0.1, 0.02}},
      {CameraModelId::kOpenCV, {500, 510, 319.5, 239.5, -0.1, 0.02, 0.001, -0.002}}};
  for (const auto& [model_id, params] : kCameras) {
    Reconstruction reconstruction;
    reconstruction.AddCamera(Camera::FromParams(model_id, 640, 480, params));
    const io::ColmapTextModel model = ToColmapTextModel(reconstruction);
    ASSERT_EQ(model.cameras.size(), 1u);
    EXPECT_EQ(model.cameras[0].model, CameraModelName(model_id));
    std::vector<double> expected = params;
    const int pp = CameraModelPrincipalPointIndex(model_id);
    expected[pp] += 0.5;
    expected[pp + 1] += 0.5;
    EXPECT_EQ(model.cameras[0].params, expected);
    EXPECT_EQ(io::ColmapCameraModelId(model.cameras[0].model), static_cast<int>(model_id));
    const Reconstruction read = FromColmapTextModel(model);
    EXPECT_EQ(read.camera(1).Params(), params);
    EXPECT_EQ(read.camera(1).model, model_id);
  }
}

}  // namespace
}  // namespace comic::sfm
