#include "io/datasets/kitti_odometry.h"

#include <gtest/gtest.h>

#include "io/core/error.h"
#include "io/core/file_utils.h"
#include "tests/test_support.h"

namespace comic::io {
namespace {

TEST(KittiOdometry, ReadsTheBundledExample) {
  const auto poses = ReadKittiPoses(test::ExampleDir() + "/poses.txt");
  ASSERT_EQ(poses.size(), 12u);
  EXPECT_NEAR(poses[0](0, 0), 1.0, 1e-9);
  EXPECT_NEAR(poses[0](2, 3), 0.0, 1e-9);
  // Driving forward: camera 11 is about 13 m ahead of camera 0 along +z.
  EXPECT_GT(poses[11](2, 3), 12.0);
  EXPECT_LT(poses[11](2, 3), 14.5);
  const cv::Matx33d k = ReadKittiIntrinsics(test::ExampleDir() + "/calib.txt", 0);
  EXPECT_NEAR(k(0, 0), 707.0912, 1e-9);
  EXPECT_NEAR(k(0, 2), 601.8873, 1e-9);
  EXPECT_NEAR(k(1, 2), 183.1104, 1e-9);
  const cv::Matx34d p1 = ReadKittiProjection(test::ExampleDir() + "/calib.txt", 1);
  EXPECT_NEAR(p1(0, 3), -379.8145, 1e-4);
}

TEST(KittiOdometry, AcceptsLabelledCalibLines) {
  test::ScopedTempDir dir;
  WriteFileAtomically(dir.File("calib.txt"), "P0: 700 0 600 0 0 700 180 0 0 0 1 0\n");
  EXPECT_NEAR(ReadKittiIntrinsics(dir.File("calib.txt"))(1, 2), 180.0, 1e-12);
}

TEST(KittiOdometry, BadFilesGiveClearErrors) {
  test::ScopedTempDir dir;
  EXPECT_THROW(ReadKittiPoses(dir.File("missing.txt")), Error);
  WriteFileAtomically(dir.File("short.txt"), "1 0 0 0 0 1 0 0 0 0 1\n");
  try {
    ReadKittiPoses(dir.File("short.txt"));
    ADD_FAILURE();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("short.txt:1: expected 12 numbers"), std::string::npos)
        << e.what();
  }
  WriteFileAtomically(dir.File("scaled.txt"), "2 0 0 0 0 1 0 0 0 0 1 0\n");
  EXPECT_THROW(ReadKittiPoses(dir.File("scaled.txt")), Error);
  WriteFileAtomically(dir.File("calib.txt"), "700 0 600 0 0 700 180 0 0 0 1 0\n");
  EXPECT_THROW(ReadKittiProjection(dir.File("calib.txt"), 1), Error);
  WriteFileAtomically(dir.File("skew.txt"), "700 0 600 0 5 700 180 0 0 0 1 0\n");
  EXPECT_THROW(ReadKittiIntrinsics(dir.File("skew.txt")), Error);
}

}  // namespace
}  // namespace comic::io
