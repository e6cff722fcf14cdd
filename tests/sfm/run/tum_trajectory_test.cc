// trajectory_tum.txt (sfm/run/tum_trajectory.h): known poses give known lines.
#include "sfm/run/tum_trajectory.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <sstream>
#include <vector>

#include "io/core/error.h"

namespace comic::sfm {
namespace {

// Frames a.png, b.png, c.png; b is not registered. a: identity pose. c: turned 90° about the
// world's z axis (cam_from_world), centre at (1, 2, 3).
Reconstruction ThreeFrames() {
  Reconstruction reconstruction;
  const camera_t camera = reconstruction.AddCamera(Camera::FromImageSize(640, 480));
  for (const char* name : {"a.png", "b.png", "c.png"}) {
    Image image;
    image.camera_id = camera;
    image.name = name;
    if (image.name == "c.png") {
      const Eigen::Quaterniond rotation(Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()));
      image.cam_from_world = Rigid3d(rotation, -(rotation * Eigen::Vector3d(1, 2, 3)));
    }
    const image_t id = reconstruction.AddImage(image);
    if (image.name != "b.png") reconstruction.RegisterImage(id);
  }
  return reconstruction;
}

TEST(TumTrajectory, RegisteredFramesOnlyWithCentreAndCameraToWorldRotation) {
  const std::string text =
      TumTrajectoryText(ThreeFrames(), {"a.png", "b.png", "c.png"}, {10, 11, 12}, 5.0);
  // c: world_from_cam turns −90° about z: q = (0, 0, −sin 45°, cos 45°).
  std::istringstream lines(text);
  std::string first, second, extra;
  std::getline(lines, first);
  std::getline(lines, second);
  EXPECT_FALSE(std::getline(lines, extra));
  std::istringstream identity(first);
  std::vector<double> values(8);
  for (double& value : values) identity >> value;
  EXPECT_EQ(values, std::vector<double>({2, 0, 0, 0, 0, 0, 0, 1}));
  std::istringstream fields(second);
  double t, x, y, z, qx, qy, qz, qw;
  fields >> t >> x >> y >> z >> qx >> qy >> qz >> qw;
  EXPECT_EQ(t, 12 / 5.0);
  EXPECT_NEAR(x, 1.0, 1e-12);
  EXPECT_NEAR(y, 2.0, 1e-12);
  EXPECT_NEAR(z, 3.0, 1e-12);
  EXPECT_NEAR(qx, 0.0, 1e-12);
  EXPECT_NEAR(qy, 0.0, 1e-12);
  EXPECT_NEAR(std::abs(qz), std::sqrt(0.5), 1e-12);
  EXPECT_NEAR(qw * qz, -0.5, 1e-12);  // the sign of the pair is free, their product is not
}

TEST(TumTrajectory, WithoutAFrameRateTheTimestampIsTheSourceIndex) {
  const std::string text =
      TumTrajectoryText(ThreeFrames(), {"a.png", "b.png", "c.png"}, {0, 3, 6}, 0.0);
  EXPECT_EQ(text.substr(0, 2), "0 ");
  EXPECT_NE(text.find("\n6 "), std::string::npos) << text;
}

TEST(TumTrajectory, NamesAndIndicesMustPair) {
  EXPECT_THROW(TumTrajectoryText(ThreeFrames(), {"a.png"}, {0, 1}, 0.0), Error);
}

}  // namespace
}  // namespace comic::sfm
