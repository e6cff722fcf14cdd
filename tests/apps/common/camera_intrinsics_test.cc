// LoadCameraIntrinsics: --intrinsics describes the frames as stored; resized frames scale it.
#include "apps/common/camera_intrinsics.h"

#include <gtest/gtest.h>

#include <vector>

#include "io/core/error.h"
#include "io/core/file_utils.h"
#include "tests/test_support.h"

namespace {

using comic::apps::LoadCameraIntrinsics;

TEST(LoadCameraIntrinsics, KeepsTheFileAtTheStoredSize) {
  comic::test::ScopedTempDir dir;
  comic::io::WriteFileAtomically(dir.File("k.txt"), "700 710 600.5 180.25\n");
  const comic::sfm::Camera camera =
      LoadCameraIntrinsics(dir.File("k.txt"), {1226, 370}, {1226, 370});
  EXPECT_EQ(camera.width, 1226);
  EXPECT_EQ(camera.height, 370);
  EXPECT_EQ(camera.fx, 700.0);
  EXPECT_EQ(camera.fy, 710.0);
  EXPECT_EQ(camera.cx, 600.5);
  EXPECT_EQ(camera.cy, 180.25);
}

TEST(LoadCameraIntrinsics, ScalesToResizedFramesAboutPixelCentres) {
  comic::test::ScopedTempDir dir;
  comic::io::WriteFileAtomically(dir.File("k.txt"), "700 700 599.5 183.5\n");
  // Half size: focal lengths halve, a pixel centre c maps to (c + 0.5) / 2 - 0.5.
  const comic::sfm::Camera camera =
      LoadCameraIntrinsics(dir.File("k.txt"), {1226, 370}, {613, 185});
  EXPECT_EQ(camera.width, 613);
  EXPECT_EQ(camera.height, 185);
  EXPECT_DOUBLE_EQ(camera.fx, 350.0);
  EXPECT_DOUBLE_EQ(camera.fy, 350.0);
  EXPECT_DOUBLE_EQ(camera.cx, 299.5);
  EXPECT_DOUBLE_EQ(camera.cy, 91.5);
}

TEST(LoadCameraIntrinsics, ReadsTheBundledKittiCalibration) {
  const comic::sfm::Camera camera =
      LoadCameraIntrinsics(comic::test::ExampleDir() + "/calib.txt", {1226, 370}, {1226, 370});
  EXPECT_GT(camera.fx, 500.0);  // KITTI odometry sequence 06: fx = fy = 707.0912
  EXPECT_EQ(camera.fx, camera.fy);
}

TEST(LoadCameraIntrinsics, MissingOrMalformedFilesThrow) {
  comic::test::ScopedTempDir dir;
  EXPECT_THROW(LoadCameraIntrinsics(dir.File("missing.txt"), {10, 10}, {10, 10}), comic::Error);
  comic::io::WriteFileAtomically(dir.File("bad.txt"), "not numbers\n");
  EXPECT_THROW(LoadCameraIntrinsics(dir.File("bad.txt"), {10, 10}, {10, 10}), comic::Error);
}

// --camera-model converts a camera only where nothing is lost.
TEST(LoadCameraIntrinsics, CameraModelConvertsWithoutLoss) {
  comic::test::ScopedTempDir dir;
  comic::io::WriteFileAtomically(dir.File("equal.txt"), "700 700 612 184\n");
  comic::io::WriteFileAtomically(dir.File("two.txt"), "700 710 612 184 -0.1\n");
  const comic::sfm::Camera radial = LoadCameraIntrinsics(
      dir.File("equal.txt"), {1226, 370}, {1226, 370}, comic::sfm::CameraModelId::kSimpleRadial);
  EXPECT_EQ(radial.model, comic::sfm::CameraModelId::kSimpleRadial);
  EXPECT_EQ(radial.Params(), (std::vector<double>{700, 612, 184, 0}));
  const comic::sfm::Camera opencv =
      LoadCameraIntrinsics(dir.File("two.txt"), {1226, 370}, {1226, 370});
  EXPECT_EQ(opencv.model, comic::sfm::CameraModelId::kOpenCV);
  EXPECT_EQ(opencv.k1, -0.1);
  // fx != fy, and a k1 that PINHOLE cannot hold.
  EXPECT_THROW(LoadCameraIntrinsics(dir.File("two.txt"), {1226, 370}, {1226, 370},
                                    comic::sfm::CameraModelId::kRadial),
               comic::Error);
  EXPECT_THROW(LoadCameraIntrinsics(dir.File("two.txt"), {1226, 370}, {1226, 370},
                                    comic::sfm::CameraModelId::kPinhole),
               comic::Error);
  EXPECT_EQ(comic::apps::ParseCameraModelFlag("RADIAL"), comic::sfm::CameraModelId::kRadial);
  EXPECT_THROW(comic::apps::ParseCameraModelFlag("radial"), comic::Error);
}

}  // namespace
