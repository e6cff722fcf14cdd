// Matching ground-truth cameras to the frames of a run: by image name or by frame index, with
// intrinsics scaled to resized frames.
#include "sfm/evaluation/ground_truth.h"

#include <gtest/gtest.h>

#include <cmath>

#include "io/core/error.h"

namespace comic::sfm {
namespace {

io::GroundTruthCameras MakeTruth(bool named) {
  io::GroundTruthCameras truth;
  for (int i = 0; i < 4; ++i) {
    io::GroundTruthCamera camera;
    camera.index = i;
    if (named) camera.image_name = "view" + std::to_string(i) + ".png";
    camera.cam_from_world_translation = Eigen::Vector3d(i, 0, 0);
    camera.has_intrinsics = true;
    camera.K << 800, 0, 319.5, 0, 810, 239.5, 0, 0, 1;
    truth.cameras.push_back(camera);
  }
  return truth;
}

TEST(GroundTruth, MatchesByNameAndScalesIntrinsics) {
  // Frames view3, view1 and an unknown one, resized from 640x480 to 320x240.
  const FrameGroundTruth matched =
      MatchGroundTruthToFrames(MakeTruth(true), {"view3.png", "view1.png", "other.png"}, {3, 1, 7},
                               cv::Size(640, 480), cv::Size(320, 240));
  EXPECT_EQ(matched.num_matched, 2);
  ASSERT_TRUE(matched.cams_from_world[0].has_value());
  EXPECT_DOUBLE_EQ(matched.cams_from_world[0]->translation.x(), 3.0);
  EXPECT_DOUBLE_EQ(matched.cams_from_world[1]->translation.x(), 1.0);
  EXPECT_FALSE(matched.cams_from_world[2].has_value());
  ASSERT_TRUE(matched.camera.has_value());
  EXPECT_EQ(matched.camera->width, 320);
  EXPECT_EQ(matched.camera->height, 240);
  EXPECT_DOUBLE_EQ(matched.camera->fx, 400);
  EXPECT_DOUBLE_EQ(matched.camera->fy, 405);
  // The image centre stays the image centre: (319.5 + 0.5) / 2 - 0.5.
  EXPECT_DOUBLE_EQ(matched.camera->cx, 159.5);
  EXPECT_DOUBLE_EQ(matched.camera->cy, 119.5);
}

TEST(GroundTruth, MatchesByIndexWithoutNames) {
  // Frames 2 and 3 of the source (e.g. --first 2).
  const FrameGroundTruth matched = MatchGroundTruthToFrames(
      MakeTruth(false), {"a.png", "b.png"}, {2, 3}, cv::Size(640, 480), cv::Size(640, 480));
  EXPECT_EQ(matched.num_matched, 2);
  EXPECT_DOUBLE_EQ(matched.cams_from_world[0]->translation.x(), 2.0);
  EXPECT_DOUBLE_EQ(matched.camera->fx, 800);
}

// TUM-style: poses at 1305031102.10, .11, .12, .13 s; frames named by their time stamps match
// the nearest pose within 20 ms, frames named otherwise line i to frame i.
io::GroundTruthCameras MakeTimestampedTruth() {
  io::GroundTruthCameras truth = MakeTruth(false);
  truth.timestamp_tolerance = 0.02;
  for (io::GroundTruthCamera& camera : truth.cameras) {
    camera.has_intrinsics = false;
    camera.timestamp = 1305031102.10 + 0.01 * camera.index;
  }
  return truth;
}

TEST(GroundTruth, MatchesByTimestampWhenTheFramesAreNamedByTheirs) {
  const FrameGroundTruth matched = MatchGroundTruthToFrames(
      MakeTimestampedTruth(), {"rgb/1305031102.131.png", "1305031102.104.png", "1305031102.2.png"},
      {0, 1, 2}, cv::Size(640, 480), cv::Size(640, 480));
  EXPECT_EQ(matched.num_matched, 2);
  EXPECT_DOUBLE_EQ(matched.cams_from_world[0]->translation.x(), 3.0);
  EXPECT_DOUBLE_EQ(matched.cams_from_world[1]->translation.x(), 0.0);
  EXPECT_FALSE(matched.cams_from_world[2].has_value());  // 70 ms from the last pose
  EXPECT_FALSE(matched.camera.has_value());
}

TEST(GroundTruth, TimestampedTruthFallsBackToTheIndex) {
  const FrameGroundTruth matched =
      MatchGroundTruthToFrames(MakeTimestampedTruth(), {"frame_000001.png", "frame_x.png"}, {1, 2},
                               cv::Size(640, 480), cv::Size(640, 480));
  EXPECT_EQ(matched.num_matched, 2);
  EXPECT_DOUBLE_EQ(matched.cams_from_world[0]->translation.x(), 1.0);
  EXPECT_DOUBLE_EQ(matched.cams_from_world[1]->translation.x(), 2.0);
}

TEST(GroundTruth, RejectsMismatches) {
  EXPECT_THROW(MatchGroundTruthToFrames(MakeTruth(true), {"nothing.png"}, {0}, cv::Size(640, 480),
                                        cv::Size(640, 480)),
               Error);
  io::GroundTruthCameras sized = MakeTruth(true);
  sized.cameras[0].width = 3072;
  sized.cameras[0].height = 2048;
  EXPECT_THROW(
      MatchGroundTruthToFrames(sized, {"view0.png"}, {0}, cv::Size(640, 480), cv::Size(640, 480)),
      Error);
  Eigen::Matrix3d skewed;
  skewed << 800, 5, 320, 0, 800, 240, 0, 0, 1;
  EXPECT_THROW(CameraFromK(skewed, 640, 480), Error);
}

TEST(GroundTruth, MatchesByPathComponentThenStem) {
  // A COLMAP model names "images/view1.png", a NeRF file "view2" (no extension); "view3.png"
  // matches exactly. Two cameras whose names share a stem match neither by stem.
  io::GroundTruthCameras truth = MakeTruth(true);
  truth.cameras[1].image_name = "images/view1.png";
  truth.cameras[2].image_name = "view2";
  truth.cameras[0].image_name = "a/dup";
  truth.cameras.push_back(truth.cameras[0]);
  truth.cameras.back().image_name = "b/dup";
  const FrameGroundTruth matched =
      MatchGroundTruthToFrames(truth, {"view1.png", "view2.png", "view3.png", "dup.png"},
                               {0, 1, 2, 3}, cv::Size(640, 480), cv::Size(640, 480));
  EXPECT_EQ(matched.num_matched, 3);
  EXPECT_DOUBLE_EQ(matched.cams_from_world[0]->translation.x(), 1.0);
  EXPECT_DOUBLE_EQ(matched.cams_from_world[1]->translation.x(), 2.0);
  EXPECT_DOUBLE_EQ(matched.cams_from_world[2]->translation.x(), 3.0);
  EXPECT_FALSE(matched.cams_from_world[3].has_value());
}

TEST(GroundTruth, FieldOfViewGivesTheIntrinsicsOfTheFrames) {
  // NeRF's camera_angle_x without an image size: f = w / 2 / tan(fov / 2) at the frames' size.
  io::GroundTruthCameras truth = MakeTruth(true);
  for (io::GroundTruthCamera& camera : truth.cameras) {
    camera.has_intrinsics = false;
    camera.horizontal_fov_rad = 2.0 * std::atan(0.5);  // f = w
  }
  const FrameGroundTruth matched =
      MatchGroundTruthToFrames(truth, {"view0.png"}, {0}, cv::Size(800, 800), cv::Size(400, 400));
  ASSERT_TRUE(matched.camera.has_value());
  EXPECT_NEAR(matched.camera->fx, 400.0, 1e-9);
  EXPECT_NEAR(matched.camera->fy, 400.0, 1e-9);
  EXPECT_DOUBLE_EQ(matched.camera->cx, 199.5);
  EXPECT_EQ(matched.camera->width, 400);
}

TEST(GroundTruth, RegisteredPosesByName) {
  Reconstruction reconstruction;
  reconstruction.AddCamera(Camera::FromImageSize(64, 48));
  for (const char* name : {"b.png", "a.png"}) {
    Image image;
    image.camera_id = 1;
    image.name = name;
    image.cam_from_world.translation = Eigen::Vector3d(name[0] == 'a' ? 1 : 2, 0, 0);
    reconstruction.AddImage(image);
  }
  reconstruction.RegisterImage(2);  // only a.png
  const auto poses = RegisteredPosesByName(reconstruction, {"a.png", "b.png", "c.png"});
  ASSERT_EQ(poses.size(), 3u);
  ASSERT_TRUE(poses[0].has_value());
  EXPECT_DOUBLE_EQ(poses[0]->translation.x(), 1.0);
  EXPECT_FALSE(poses[1].has_value());
  EXPECT_FALSE(poses[2].has_value());
}

}  // namespace
}  // namespace comic::sfm
