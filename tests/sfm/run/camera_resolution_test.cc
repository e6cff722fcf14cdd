// The camera of a run: --intrinsics describes the frames as stored (resized frames scale it),
// else the ground truth's, else COLMAP's default camera, self-calibrated unless held fixed.
#include "sfm/run/camera_resolution.h"

#include <gtest/gtest.h>

#include <vector>

#include "io/core/error.h"
#include "io/core/file_utils.h"
#include "tests/test_support.h"

namespace {

using comic::sfm::CameraChoice;
using comic::sfm::LoadCameraCalibration;
using comic::sfm::ResolveCamera;
using comic::sfm::ResolvedCamera;

TEST(LoadCameraCalibration, KeepsTheFileAtTheStoredSize) {
  comic::test::ScopedTempDir dir;
  comic::io::WriteFileAtomically(dir.File("k.txt"), "700 710 600.5 180.25\n");
  const comic::sfm::Camera camera =
      LoadCameraCalibration(dir.File("k.txt"), {1226, 370}, {1226, 370});
  EXPECT_EQ(camera.width, 1226);
  EXPECT_EQ(camera.height, 370);
  EXPECT_EQ(camera.fx, 700.0);
  EXPECT_EQ(camera.fy, 710.0);
  EXPECT_EQ(camera.cx, 600.5);
  EXPECT_EQ(camera.cy, 180.25);
}

TEST(LoadCameraCalibration, ScalesToResizedFramesAboutPixelCentres) {
  comic::test::ScopedTempDir dir;
  comic::io::WriteFileAtomically(dir.File("k.txt"), "700 700 599.5 183.5\n");
  // Half size: focal lengths halve, a pixel centre c maps to (c + 0.5) / 2 - 0.5.
  const comic::sfm::Camera camera =
      LoadCameraCalibration(dir.File("k.txt"), {1226, 370}, {613, 185});
  EXPECT_EQ(camera.width, 613);
  EXPECT_EQ(camera.height, 185);
  EXPECT_DOUBLE_EQ(camera.fx, 350.0);
  EXPECT_DOUBLE_EQ(camera.fy, 350.0);
  EXPECT_DOUBLE_EQ(camera.cx, 299.5);
  EXPECT_DOUBLE_EQ(camera.cy, 91.5);
}

TEST(LoadCameraCalibration, ReadsTheBundledKittiCalibration) {
  const comic::sfm::Camera camera =
      LoadCameraCalibration(comic::test::ExampleDir() + "/calib.txt", {1226, 370}, {1226, 370});
  EXPECT_GT(camera.fx, 500.0);  // KITTI odometry sequence 06: fx = fy = 707.0912
  EXPECT_EQ(camera.fx, camera.fy);
}

TEST(LoadCameraCalibration, MissingOrMalformedFilesThrow) {
  comic::test::ScopedTempDir dir;
  EXPECT_THROW(LoadCameraCalibration(dir.File("missing.txt"), {10, 10}, {10, 10}), comic::Error);
  comic::io::WriteFileAtomically(dir.File("bad.txt"), "not numbers\n");
  EXPECT_THROW(LoadCameraCalibration(dir.File("bad.txt"), {10, 10}, {10, 10}), comic::Error);
}

// --camera-model converts a camera only where nothing is lost.
TEST(LoadCameraCalibration, CameraModelConvertsWithoutLoss) {
  comic::test::ScopedTempDir dir;
  comic::io::WriteFileAtomically(dir.File("equal.txt"), "700 700 612 184\n");
  comic::io::WriteFileAtomically(dir.File("two.txt"), "700 710 612 184 -0.1\n");
  const comic::sfm::Camera radial = LoadCameraCalibration(
      dir.File("equal.txt"), {1226, 370}, {1226, 370}, comic::sfm::CameraModelId::kSimpleRadial);
  EXPECT_EQ(radial.model, comic::sfm::CameraModelId::kSimpleRadial);
  EXPECT_EQ(radial.Params(), (std::vector<double>{700, 612, 184, 0}));
  const comic::sfm::Camera opencv =
      LoadCameraCalibration(dir.File("two.txt"), {1226, 370}, {1226, 370});
  EXPECT_EQ(opencv.model, comic::sfm::CameraModelId::kOpenCV);
  EXPECT_EQ(opencv.k1, -0.1);
  // fx != fy, and a k1 that PINHOLE cannot hold.
  EXPECT_THROW(LoadCameraCalibration(dir.File("two.txt"), {1226, 370}, {1226, 370},
                                     comic::sfm::CameraModelId::kRadial),
               comic::Error);
  EXPECT_THROW(LoadCameraCalibration(dir.File("two.txt"), {1226, 370}, {1226, 370},
                                     comic::sfm::CameraModelId::kPinhole),
               comic::Error);
  EXPECT_EQ(comic::sfm::ParseCameraModel("RADIAL"), comic::sfm::CameraModelId::kRadial);
  EXPECT_THROW(comic::sfm::ParseCameraModel("radial"), comic::Error);
}

// The rule: a file first, then the ground truth's camera, then the default, self-calibrated.
TEST(ResolveCamera, FileThenGroundTruthThenTheSelfCalibratedDefault) {
  comic::test::ScopedTempDir dir;
  comic::io::WriteFileAtomically(dir.File("k.txt"), "700 700 612 184\n");
  comic::sfm::FrameGroundTruth truth;
  truth.camera = comic::sfm::Camera::FromParams(comic::sfm::CameraModelId::kPinhole, 1226, 370,
                                                {710, 710, 600, 180});
  CameraChoice choice;
  choice.intrinsics = dir.File("k.txt");
  ResolvedCamera file = ResolveCamera(choice, {1226, 370}, {1226, 370}, truth, "poses.txt");
  EXPECT_EQ(file.camera.fx, 700.0);
  EXPECT_EQ(file.source, "file " + dir.File("k.txt"));
  EXPECT_FALSE(file.self_calibrating);
  EXPECT_FALSE(file.refine_intrinsics);

  choice.intrinsics.clear();
  const ResolvedCamera gt = ResolveCamera(choice, {1226, 370}, {1226, 370}, truth, "poses.txt");
  EXPECT_EQ(gt.camera.fx, 710.0);
  EXPECT_EQ(gt.source, "ground truth poses.txt");
  EXPECT_FALSE(gt.self_calibrating);

  choice.ignore_gt_intrinsics = true;
  const ResolvedCamera guess = ResolveCamera(choice, {1226, 370}, {1226, 370}, truth, "poses.txt");
  // COLMAP's guess: SIMPLE_RADIAL, f = 1.2 max(w, h), principal point at the centre, k = 0.
  EXPECT_EQ(guess.camera.model, comic::sfm::CameraModelId::kSimpleRadial);
  EXPECT_DOUBLE_EQ(guess.camera.fx, 1.2 * 1226);
  EXPECT_TRUE(guess.self_calibrating);
  EXPECT_TRUE(guess.refine_intrinsics);
  EXPECT_NE(guess.source.find("refined once the model constrains it"), std::string::npos);

  choice.fixed_intrinsics = true;
  choice.camera_model = "PINHOLE";
  const ResolvedCamera fixed = ResolveCamera(choice, {1226, 370}, {613, 185}, std::nullopt);
  EXPECT_EQ(fixed.camera.model, comic::sfm::CameraModelId::kPinhole);
  EXPECT_EQ(fixed.camera.width, 613);
  EXPECT_TRUE(fixed.self_calibrating);
  EXPECT_FALSE(fixed.refine_intrinsics);
  EXPECT_NE(fixed.source.find("held fixed"), std::string::npos);
}

// The photos' EXIF focal: the prior of the self-calibrated camera, scaled to resized frames;
// a file or the ground truth still come first, and without an agreed EXIF focal the guess stays.
TEST(ResolveCamera, ExifFocalIsThePriorAfterFileAndGroundTruth) {
  comic::sfm::ExifFocalPrior exif;
  exif.focal_px = 700.0;
  exif.description = "EXIF FocalLengthIn35mmFilm 20 mm in a.jpg, 8 of 8 frames read agree";
  CameraChoice choice;
  const ResolvedCamera camera =
      ResolveCamera(choice, {1226, 370}, {1226, 370}, std::nullopt, "", exif);
  EXPECT_EQ(camera.camera.model, comic::sfm::CameraModelId::kSimpleRadial);
  EXPECT_EQ(camera.camera.fx, 700.0);
  EXPECT_EQ(camera.camera.fy, 700.0);
  EXPECT_DOUBLE_EQ(camera.camera.cx, 612.5);
  EXPECT_EQ(camera.origin, "exif");
  EXPECT_EQ(camera.source.rfind(exif.description, 0), 0u) << camera.source;
  EXPECT_TRUE(camera.self_calibrating);
  EXPECT_TRUE(camera.refine_intrinsics);
  const ResolvedCamera half =
      ResolveCamera(choice, {1226, 370}, {613, 185}, std::nullopt, "", exif);
  EXPECT_DOUBLE_EQ(half.camera.fx, 700.0 * 185 / 370);

  comic::sfm::FrameGroundTruth truth;
  truth.camera = comic::sfm::Camera::FromParams(comic::sfm::CameraModelId::kPinhole, 1226, 370,
                                                {710, 710, 600, 180});
  EXPECT_EQ(ResolveCamera(choice, {1226, 370}, {1226, 370}, truth, "gt", exif).origin,
            "ground_truth");
  comic::test::ScopedTempDir dir;
  comic::io::WriteFileAtomically(dir.File("k.txt"), "690 690 612 184\n");
  choice.intrinsics = dir.File("k.txt");
  EXPECT_EQ(ResolveCamera(choice, {1226, 370}, {1226, 370}, truth, "gt", exif).camera.fx, 690.0);

  choice.intrinsics.clear();
  comic::sfm::ExifFocalPrior disagree;
  disagree.description = "EXIF focal lengths disagree: 700.0 px (a.jpg) and 900.0 px (b.jpg)";
  const ResolvedCamera guess =
      ResolveCamera(choice, {1226, 370}, {1226, 370}, std::nullopt, "", disagree);
  EXPECT_EQ(guess.origin, "default");
  EXPECT_DOUBLE_EQ(guess.camera.fx, 1.2 * 1226);
  EXPECT_NE(guess.source.find(disagree.description), std::string::npos) << guess.source;
}

TEST(ResolveCamera, BadModelNamesTheFlag) {
  CameraChoice choice;
  choice.camera_model = "FISHEYE";
  try {
    choice.Check();
    ADD_FAILURE() << "FISHEYE accepted";
  } catch (const comic::Error& e) {
    EXPECT_EQ(e.kind(), comic::ErrorKind::kInvalidArgument);
    EXPECT_NE(std::string(e.what()).find("--camera-model"), std::string::npos) << e.what();
  }
}

}  // namespace
