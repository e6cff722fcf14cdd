// --undistort's workspace (sfm/run/undistorted_output.h): PINHOLE cameras whose projections are
// the undistorted observations, the images remapped, and COLMAP's stereo configuration files.
#include "sfm/run/undistorted_output.h"

#include <gtest/gtest.h>

#include "io/colmap/colmap_binary_model.h"
#include "io/core/error.h"
#include "io/core/file_utils.h"
#include "io/image/image_io.h"
#include "tests/test_support.h"

namespace comic::sfm {
namespace {

// One SIMPLE_RADIAL camera (k = 0.2: pincushion), two registered views of three points and an
// unregistered one; the observations are the distorted projections.
Reconstruction DistortedModel() {
  Reconstruction reconstruction;
  const camera_t camera_id = reconstruction.AddCamera(
      Camera::FromParams(CameraModelId::kSimpleRadial, 320, 240, {300.0, 159.5, 119.5, 0.2}));
  const std::vector<Eigen::Vector3d> points = {
      {-1.0, -0.8, 4.0}, {0.9, 0.7, 5.0}, {1.5, -1.0, 5.0}};
  std::vector<image_t> ids;
  for (int i = 0; i < 3; ++i) {
    Image image;
    image.camera_id = camera_id;
    image.name = "view" + std::to_string(i) + ".png";
    image.cam_from_world.translation = Eigen::Vector3d(-0.3 * i, 0.0, 0.0);
    for (const Eigen::Vector3d& point : points) {
      Point2D observation;
      observation.xy = *ProjectPoint(reconstruction.camera(camera_id), image.cam_from_world, point);
      image.points2D.push_back(observation);
    }
    ids.push_back(reconstruction.AddImage(image));
    if (i < 2) reconstruction.RegisterImage(ids.back());
  }
  for (point2D_t k = 0; k < points.size(); ++k) {
    reconstruction.AddPoint3D(points[k], {{ids[0], k}, {ids[1], k}});
  }
  return reconstruction;
}

TEST(UndistortedOutput, PinholeCamerasProjectToTheUndistortedObservations) {
  const Reconstruction distorted = DistortedModel();
  const Reconstruction undistorted = UndistortedReconstruction(distorted);
  const Camera& pinhole = undistorted.cameras().begin()->second;
  EXPECT_EQ(pinhole.model, CameraModelId::kPinhole);
  EXPECT_FALSE(pinhole.HasDistortion());
  EXPECT_DOUBLE_EQ(pinhole.fx, 300.0);
  EXPECT_DOUBLE_EQ(pinhole.cx, 159.5);
  for (const auto& [id, point] : undistorted.points3D()) {
    for (const TrackElement& element : point.track) {
      const Image& image = undistorted.image(element.image_id);
      const Eigen::Vector2d projected = *ProjectPoint(pinhole, image.cam_from_world, point.xyz);
      EXPECT_LT((projected - image.points2D[element.point2D_idx].xy).norm(), 1e-6);
      // The distortion did move it.
      EXPECT_GT(
          (projected - distorted.image(element.image_id).points2D[element.point2D_idx].xy).norm(),
          0.1);
    }
  }
  EXPECT_LT(undistorted.ComputeMeanReprojectionError(), 1e-6);
}

TEST(UndistortedOutput, WritesImageUndistortersLayout) {
  test::ScopedTempDir dir;
  const Reconstruction distorted = DistortedModel();
  // A white image: after the remap the corners, which the pincushion frame did not see, are black.
  const auto read_image = [](const Image&) {
    return cv::Mat(240, 320, CV_8UC3, cv::Scalar::all(255));
  };
  WriteUndistortedWorkspace(distorted, read_image, dir.File("dense"));
  for (const std::string& file : UndistortedWorkspaceFiles(distorted)) {
    EXPECT_TRUE(io::IsRegularFile(dir.File("dense/" + file))) << file;
  }
  EXPECT_FALSE(io::PathExists(dir.File("dense/images/view2.png")));  // not registered
  EXPECT_TRUE(io::IsDirectory(dir.File("dense/stereo/depth_maps")));
  EXPECT_EQ(io::ReadFileToString(dir.File("dense/stereo/patch-match.cfg")),
            "view0.png\n__auto__, 20\nview1.png\n__auto__, 20\n");
  EXPECT_EQ(io::ReadFileToString(dir.File("dense/stereo/fusion.cfg")), "view0.png\nview1.png\n");
  const io::ColmapTextModel model = io::ReadColmapBinaryModel(dir.File("dense/sparse"));
  ASSERT_EQ(model.cameras.size(), 1u);
  EXPECT_EQ(model.cameras[0].model, "PINHOLE");
  EXPECT_EQ(model.images.size(), 2u);
  EXPECT_EQ(model.points3D.size(), 3u);
  const cv::Mat image = io::LoadImage(dir.File("dense/images/view0.png")).gray;
  EXPECT_EQ(image.at<uint8_t>(120, 160), 255);
  EXPECT_EQ(image.at<uint8_t>(0, 0), 0);
}

TEST(UndistortedOutput, AnImageOfAnotherSizeIsRefused) {
  test::ScopedTempDir dir;
  const auto read_image = [](const Image&) { return cv::Mat(10, 10, CV_8UC3); };
  EXPECT_THROW(WriteUndistortedWorkspace(DistortedModel(), read_image, dir.File("dense")), Error);
}

}  // namespace
}  // namespace comic::sfm
