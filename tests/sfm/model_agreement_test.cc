// Two models of the same frames compared by their rotations: the same cameras in another world
// (rotated, scaled, moved) agree exactly; cameras turned from a frame on are found; frames are
// paired by image id and only registered ones count.
#include "sfm/model_agreement.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <string>
#include <vector>

namespace comic::sfm {
namespace {

// `count` cameras along an arc (image i + 1 is frame i), world-to-camera.
std::vector<Rigid3d> ArcCameras(int count) {
  std::vector<Rigid3d> cameras;
  for (int i = 0; i < count; ++i) {
    const Eigen::Quaterniond rotation(Eigen::AngleAxisd(0.08 * i, Eigen::Vector3d::UnitY()) *
                                      Eigen::AngleAxisd(0.02 * i, Eigen::Vector3d::UnitX()));
    const Eigen::Vector3d center(std::sin(0.08 * i) * 5, 0.1 * i, -std::cos(0.08 * i) * 5);
    cameras.emplace_back(rotation, -(rotation * center));
  }
  return cameras;
}

Reconstruction ModelOf(const std::vector<Rigid3d>& cameras, const std::vector<bool>& registered) {
  Reconstruction model;
  const camera_t camera_id = model.AddCamera(Camera::FromImageSize(640, 480));
  for (size_t i = 0; i < cameras.size(); ++i) {
    Image image;
    image.image_id = static_cast<image_t>(i + 1);
    image.camera_id = camera_id;
    image.name = "frame" + std::to_string(i);
    image.cam_from_world = cameras[i];
    model.AddImage(image);
    if (registered[i]) model.RegisterImage(image.image_id);
  }
  return model;
}

// The same cameras in the world x' = s R x + t.
std::vector<Rigid3d> InAnotherWorld(const std::vector<Rigid3d>& cameras) {
  const Eigen::Quaterniond world_rotation(
      Eigen::AngleAxisd(1.1, Eigen::Vector3d(0.2, 1.0, -0.4).normalized()));
  const double scale = 3.5;
  const Eigen::Vector3d shift(4, -2, 7);
  std::vector<Rigid3d> moved;
  for (const Rigid3d& camera : cameras) {
    const Eigen::Vector3d center = scale * (world_rotation * camera.Inverse().translation) + shift;
    const Eigen::Quaterniond rotation = camera.rotation * world_rotation.inverse();
    moved.emplace_back(rotation, -(rotation * center));
  }
  return moved;
}

TEST(ModelAgreement, TheSameCamerasInAnotherWorldAgree) {
  const std::vector<Rigid3d> cameras = ArcCameras(12);
  const std::vector<bool> all(12, true);
  const ModelAgreement agreement =
      CompareModelRotations(ModelOf(cameras, all), ModelOf(InAnotherWorld(cameras), all));
  EXPECT_EQ(agreement.common_frames, 12);
  EXPECT_LT(agreement.median_rotation_difference_deg, 1e-6);
  EXPECT_LT(agreement.max_rotation_difference_deg, 1e-6);
}

TEST(ModelAgreement, CamerasTurnedFromAFrameOnDisagree) {
  const std::vector<Rigid3d> cameras = ArcCameras(12);
  std::vector<Rigid3d> turned = InAnotherWorld(cameras);
  const Eigen::Quaterniond turn(Eigen::AngleAxisd(6.0 * M_PI / 180, Eigen::Vector3d::UnitZ()));
  for (size_t i = 4; i < turned.size(); ++i) {
    const Eigen::Vector3d center = turned[i].Inverse().translation;
    turned[i].rotation = turn * turned[i].rotation;
    turned[i].translation = -(turned[i].rotation * center);
  }
  const std::vector<bool> all(12, true);
  const ModelAgreement agreement =
      CompareModelRotations(ModelOf(cameras, all), ModelOf(turned, all));
  EXPECT_EQ(agreement.common_frames, 12);
  // 8 of 12 frames turned by 6 deg: the best common rotation sits nearer them, so the median
  // difference is a few degrees and the largest under 6.
  EXPECT_GT(agreement.median_rotation_difference_deg, 1.5);
  EXPECT_LT(agreement.max_rotation_difference_deg, 6.0 + 1e-9);
  EXPECT_GT(agreement.max_rotation_difference_deg, 3.0);
}

TEST(ModelAgreement, OnlyFramesBothRegisterCount) {
  const std::vector<Rigid3d> cameras = ArcCameras(10);
  std::vector<bool> first(10, true), second(10, true);
  first[0] = first[1] = false;
  second[9] = false;
  std::vector<Rigid3d> other = cameras;
  // Frames the first model does not register may be anything in the second.
  other[0].rotation = Eigen::Quaterniond(Eigen::AngleAxisd(2.0, Eigen::Vector3d::UnitX()));
  const ModelAgreement agreement =
      CompareModelRotations(ModelOf(cameras, first), ModelOf(other, second));
  EXPECT_EQ(agreement.common_frames, 7);
  EXPECT_LT(agreement.max_rotation_difference_deg, 1e-6);
  EXPECT_EQ(CompareModelRotations(ModelOf(cameras, std::vector<bool>(10, false)),
                                  ModelOf(cameras, second))
                .common_frames,
            0);
}

// Each camera turned a little further than the last about the same axis, as one model's
// rotation drifts from another's along a long clip: `step_deg` more per frame.
std::vector<Rigid3d> Drifted(const std::vector<Rigid3d>& cameras, double step_deg) {
  std::vector<Rigid3d> drifted;
  for (size_t i = 0; i < cameras.size(); ++i) {
    const Eigen::Vector3d center = cameras[i].Inverse().translation;
    const Eigen::Quaterniond drift(
        Eigen::AngleAxisd(step_deg * M_PI / 180 * i, Eigen::Vector3d(0.3, 1.0, 0.1).normalized()));
    const Eigen::Quaterniond rotation = cameras[i].rotation * drift;
    drifted.emplace_back(rotation, -(rotation * center));
  }
  return drifted;
}

TEST(ModelAgreement, SlowDriftOverALongClipIsSmallBetweenNeighbours) {
  // 0.02 deg per frame over 200 frames: 4 deg from end to end.
  const std::vector<Rigid3d> cameras = ArcCameras(200);
  const std::vector<bool> all(200, true);
  const ModelAgreement agreement = CompareModelRotations(
      ModelOf(cameras, all), ModelOf(InAnotherWorld(Drifted(cameras, 0.02)), all), 10);
  EXPECT_EQ(agreement.common_frames, 200);
  EXPECT_GT(agreement.median_rotation_difference_deg, 0.5);
  EXPECT_GT(agreement.max_rotation_difference_deg, 1.5);
  // Pairs 1..10 frames apart differ by 0.02..0.2 deg; the median pair is under 0.15.
  EXPECT_LT(agreement.median_relative_rotation_difference_deg, 0.15);
  EXPECT_GT(agreement.median_relative_rotation_difference_deg, 0.05);
  // 200 frames, each paired with the (at most) 10 after it.
  EXPECT_EQ(agreement.neighbour_pairs, 190 * 10 + 45);
}

TEST(ModelAgreement, CamerasTurnedTooFarFromFrameToFrameDifferBetweenNeighbours) {
  // 1.5 deg more per frame over 25 frames.
  const std::vector<Rigid3d> cameras = ArcCameras(25);
  const std::vector<bool> all(25, true);
  const ModelAgreement agreement = CompareModelRotations(
      ModelOf(cameras, all), ModelOf(InAnotherWorld(Drifted(cameras, 1.5)), all), 10);
  // The median pair is several frames apart: several times 1.5 deg.
  EXPECT_GT(agreement.median_relative_rotation_difference_deg, 4.5);
  EXPECT_LT(agreement.median_relative_rotation_difference_deg, 15.0 + 1e-9);
}

TEST(ModelAgreement, NeighboursAreCountedByImageIdAcrossGaps) {
  const std::vector<Rigid3d> cameras = ArcCameras(30);
  std::vector<bool> registered(30, true);
  for (int i = 5; i < 20; ++i) registered[i] = false;  // ids 6..20 missing
  const ModelAgreement agreement =
      CompareModelRotations(ModelOf(cameras, registered), ModelOf(cameras, registered), 3);
  // Pairs at most 3 ids apart: ids 1..5 give 4 + 3 + 2 = 9, ids 21..30 give 9 + 8 + 7 = 24,
  // and none crosses the gap of 15 ids.
  EXPECT_EQ(agreement.common_frames, 15);
  EXPECT_EQ(agreement.neighbour_pairs, 9 + 24);
  EXPECT_LT(agreement.median_relative_rotation_difference_deg, 1e-6);
}

}  // namespace
}  // namespace comic::sfm
