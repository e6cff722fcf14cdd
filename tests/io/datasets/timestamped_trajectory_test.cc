// TUM and EuRoC ground truth (io/datasets/timestamped_trajectory.h), on files with known poses.
#include "io/datasets/timestamped_trajectory.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>

#include "io/core/error.h"
#include "io/core/file_utils.h"
#include "tests/test_support.h"

namespace comic::io {
namespace {

// Pose 1 of both files: the camera at (1, 2, 3) turned 90° about the world's z axis
// (camera-to-world), so cam_from_world = Rz(−90°) and t = −R C.
void ExpectSecondPose(const GroundTruthCamera& camera) {
  const Eigen::Matrix3d expected =
      Eigen::AngleAxisd(-M_PI / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  EXPECT_LT((camera.cam_from_world_rotation - expected).norm(), 1e-9);
  EXPECT_LT((camera.cam_from_world_translation + expected * Eigen::Vector3d(1, 2, 3)).norm(), 1e-9);
}

const double kHalf = std::sqrt(0.5);

TEST(TimestampedTrajectory, ReadsTum) {
  test::ScopedTempDir dir;
  char second[200];
  std::snprintf(second, sizeof(second), "1305031102.2 1 2 3 0 0 %.17g %.17g\n", kHalf, kHalf);
  WriteFileAtomically(dir.File("groundtruth.txt"),
                      std::string("# ground truth trajectory\n# timestamp tx ty tz qx qy qz qw\n"
                                  "1305031102.1 0 0 0 0 0 0 1\n") +
                          second);
  EXPECT_EQ(DetectGroundTruthFormat(dir.File("groundtruth.txt")), GroundTruthFormat::kTum);
  const GroundTruthCameras truth = ReadGroundTruthCameras(dir.File("groundtruth.txt"));
  EXPECT_EQ(truth.format, GroundTruthFormat::kTum);
  EXPECT_EQ(truth.timestamp_tolerance, kTumTimestampTolerance);
  ASSERT_EQ(truth.cameras.size(), 2u);
  EXPECT_EQ(truth.cameras[0].index, 0);
  EXPECT_EQ(truth.cameras[1].index, 1);
  EXPECT_DOUBLE_EQ(truth.cameras[1].timestamp, 1305031102.2);
  EXPECT_TRUE(truth.cameras[0].cam_from_world_rotation.isIdentity(1e-12));
  EXPECT_TRUE(truth.cameras[0].image_name.empty());
  ExpectSecondPose(truth.cameras[1]);
}

TEST(TimestampedTrajectory, ReadsEurocWithTheScalarFirst) {
  test::ScopedTempDir dir;
  char second[300];
  std::snprintf(second, sizeof(second),
                "1403636579768555520,1,2,3,%.17g,0,0,%.17g,0.1,0.2,0.3,0,0,0,0,0,0\n", kHalf,
                kHalf);
  WriteFileAtomically(
      dir.File("data.csv"),
      std::string("#timestamp, p_RS_R_x [m], p_RS_R_y [m], p_RS_R_z [m], q_RS_w [], q_RS_x [], "
                  "q_RS_y [], q_RS_z [], v_RS_R_x [m s^-1], v_RS_R_y [m s^-1], v_RS_R_z [m s^-1], "
                  "b_w_RS_S_x [rad s^-1], b_w_RS_S_y [rad s^-1], b_w_RS_S_z [rad s^-1], "
                  "b_a_RS_S_x [m s^-2], b_a_RS_S_y [m s^-2], b_a_RS_S_z [m s^-2]\n"
                  "1403636579763555584,0,0,0,1,0,0,0,0,0,0,0,0,0,0,0,0\n") +
          second);
  EXPECT_EQ(DetectGroundTruthFormat(dir.File("data.csv")), GroundTruthFormat::kEuroc);
  const GroundTruthCameras truth = ReadGroundTruthCameras(dir.File("data.csv"));
  EXPECT_EQ(truth.format, GroundTruthFormat::kEuroc);
  ASSERT_EQ(truth.cameras.size(), 2u);
  EXPECT_DOUBLE_EQ(truth.cameras[0].timestamp, 1403636579763555584.0);
  EXPECT_TRUE(truth.cameras[0].cam_from_world_rotation.isIdentity(1e-12));
  ExpectSecondPose(truth.cameras[1]);
  EXPECT_STREQ(GroundTruthLengthUnit(truth.format), "m");
}

TEST(TimestampedTrajectory, KittiAndMiddleburyAreNotTaken) {
  EXPECT_FALSE(LooksLikeTumTrajectory("1 0 0 0 0 1 0 0 0 0 1 0\n"));
  EXPECT_FALSE(LooksLikeEurocGroundTruth("1 0 0 0 0 1 0 0 0 0 1 0\n"));
  EXPECT_FALSE(LooksLikeTumTrajectory("3\nimg 1 2 3\n"));
  EXPECT_EQ(DetectGroundTruthFormat(test::ExampleDir() + "/poses.txt"), GroundTruthFormat::kKitti);
}

TEST(TimestampedTrajectory, MalformedLinesNameTheLine) {
  test::ScopedTempDir dir;
  WriteFileAtomically(dir.File("tum.txt"), "0 0 0 0 0 0 0 1\n1 0 0 0 0 0 1\n");
  try {
    ReadTumTrajectory(dir.File("tum.txt"));
    FAIL() << "a 7-field line was accepted";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("tum.txt:2"), std::string::npos) << error.what();
  }
  WriteFileAtomically(dir.File("norm.txt"), "0 0 0 0 0 0 0 2\n");
  EXPECT_THROW(ReadTumTrajectory(dir.File("norm.txt")), Error);
  EXPECT_THROW(ReadEurocGroundTruth(dir.File("missing.csv")), Error);
}

}  // namespace
}  // namespace comic::io
