#include "sfm/camera.h"

#include <gtest/gtest.h>

#include "io/core/error.h"

namespace comic::sfm {
namespace {

TEST(Camera, DefaultFromImageSize) {
  const Camera camera = Camera::FromImageSize(1226, 370);
  EXPECT_DOUBLE_EQ(camera.fx, 1.2 * 1226);
  EXPECT_DOUBLE_EQ(camera.fy, 1.2 * 1226);
  EXPECT_DOUBLE_EQ(camera.cx, 612.5);
  EXPECT_DOUBLE_EQ(camera.cy, 184.5);
  EXPECT_DOUBLE_EQ(camera.K()(0, 2), 612.5);
  EXPECT_DOUBLE_EQ(camera.K()(2, 2), 1.0);
}

TEST(Camera, ScalingMapsPixelAreas) {
  Camera camera = Camera::FromImageSize(100, 50);
  const Camera doubled = camera.Scaled(2.0);
  EXPECT_EQ(doubled.width, 200);
  EXPECT_EQ(doubled.height, 100);
  EXPECT_DOUBLE_EQ(doubled.fx, 2 * camera.fx);
  // The image centre stays the image centre.
  EXPECT_DOUBLE_EQ(doubled.cx, 99.5);
  EXPECT_DOUBLE_EQ(doubled.cy, 49.5);
}

TEST(Camera, CheckRejectsNonsense) {
  Camera camera;
  EXPECT_THROW(camera.Check(), Error);
  camera = Camera::FromImageSize(10, 10);
  camera.fx = -1;
  EXPECT_THROW(camera.Check(), Error);
  EXPECT_THROW(Camera::FromImageSize(0, 10), Error);
  EXPECT_THROW(Camera::FromImageSize(10, 10).Scaled(0.0), Error);
}

}  // namespace
}  // namespace comic::sfm
