// Camera models (sfm/camera_model.h, sfm/camera.h): COLMAP's names, ids and parameter order;
// projection through the distortion and iterative undistortion back.
#include "sfm/camera_model.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "io/core/error.h"
#include "sfm/camera.h"

namespace comic::sfm {
namespace {

TEST(CameraModel, NamesIdsAndParameterCountsAreColmaps) {
  const struct {
    CameraModelId id;
    int colmap_id;
    const char* name;
    int num_params;
    int num_focal;
  } kExpected[] = {{CameraModelId::kSimplePinhole, 0, "SIMPLE_PINHOLE", 3, 1},
                   {CameraModelId::kPinhole, 1, "PINHOLE", 4, 2},
                   {CameraModelId::kSimpleRadial, 2, "SIMPLE_RADIAL", 4, 1},
                   {CameraModelId::kRadial, 3, "RADIAL", 5, 1},
                   {CameraModelId::kOpenCV, 4, "OPENCV", 8, 2}};
  for (const auto& expected : kExpected) {
    EXPECT_EQ(static_cast<int>(expected.id), expected.colmap_id);
    EXPECT_EQ(CameraModelName(expected.id), expected.name);
    EXPECT_EQ(CameraModelFromName(expected.name), expected.id);
    EXPECT_EQ(CameraModelFromId(expected.colmap_id), expected.id);
    EXPECT_EQ(CameraModelNumParams(expected.id), expected.num_params);
    EXPECT_EQ(CameraModelNumFocalParams(expected.id), expected.num_focal);
  }
  EXPECT_FALSE(CameraModelFromName("OPENCV_FISHEYE").has_value());
  EXPECT_FALSE(CameraModelFromName("pinhole").has_value());
  EXPECT_FALSE(CameraModelFromId(5).has_value());
  EXPECT_FALSE(CameraModelFromId(-1).has_value());
}

TEST(CameraModel, ParamsRoundTripInColmapOrder) {
  const Camera opencv = Camera::FromParams(CameraModelId::kOpenCV, 640, 480,
                                           {500, 510, 320, 240, 0.1, -0.05, 0.001, -0.002});
  EXPECT_EQ(opencv.fx, 500);
  EXPECT_EQ(opencv.fy, 510);
  EXPECT_EQ(opencv.cx, 320);
  EXPECT_EQ(opencv.cy, 240);
  EXPECT_EQ(opencv.k1, 0.1);
  EXPECT_EQ(opencv.k2, -0.05);
  EXPECT_EQ(opencv.p1, 0.001);
  EXPECT_EQ(opencv.p2, -0.002);
  EXPECT_EQ(opencv.Params(), (std::vector<double>{500, 510, 320, 240, 0.1, -0.05, 0.001, -0.002}));
  const Camera radial =
      Camera::FromParams(CameraModelId::kRadial, 640, 480, {500, 320, 240, 0.1, 0.2});
  EXPECT_EQ(radial.fx, 500);
  EXPECT_EQ(radial.fy, 500);
  EXPECT_EQ(radial.k2, 0.2);
  EXPECT_EQ(radial.Params(), (std::vector<double>{500, 320, 240, 0.1, 0.2}));
  EXPECT_EQ(Camera::FromParams(CameraModelId::kSimpleRadial, 64, 48, {50, 32, 24, -0.3}).k1, -0.3);
  EXPECT_EQ(Camera::FromParams(CameraModelId::kSimplePinhole, 64, 48, {50, 32, 24}).Params(),
            (std::vector<double>{50, 32, 24}));
  // Wrong counts and invalid values are refused.
  EXPECT_THROW(Camera::FromParams(CameraModelId::kPinhole, 64, 48, {50, 32, 24}), Error);
  EXPECT_THROW(Camera::FromParams(CameraModelId::kSimplePinhole, 64, 48, {-50, 32, 24}), Error);
  EXPECT_THROW(Camera::FromParams(CameraModelId::kSimpleRadial, 64, 48, {50, 32, 24, NAN}), Error);
}

TEST(CameraModel, CheckRefusesWhatTheModelCannotHold) {
  Camera camera = Camera::FromImageSize(640, 480, CameraModelId::kSimplePinhole);
  camera.fy = camera.fx + 1;
  EXPECT_THROW(camera.Check(), Error);  // one focal length
  camera = Camera::FromImageSize(640, 480, CameraModelId::kSimpleRadial);
  camera.k2 = 0.01;
  EXPECT_THROW(camera.Check(), Error);  // SIMPLE_RADIAL has k only
  camera = Camera::FromImageSize(640, 480, CameraModelId::kPinhole);
  camera.k1 = 0.01;
  EXPECT_THROW(camera.Check(), Error);
  camera.model = CameraModelId::kOpenCV;
  EXPECT_NO_THROW(camera.Check());
}

// A known value: OPENCV's formula at one point, worked out by hand.
TEST(CameraModel, OpenCvDistortionMatchesTheFormula) {
  const Camera camera = Camera::FromParams(CameraModelId::kOpenCV, 640, 480,
                                           {500, 400, 320, 240, 0.1, 0.01, 0.002, 0.003});
  const double u = 0.2, v = -0.1, r2 = u * u + v * v;
  const double radial = 1 + 0.1 * r2 + 0.01 * r2 * r2;
  const double ud = u * radial + 2 * 0.002 * u * v + 0.003 * (r2 + 2 * u * u);
  const double vd = v * radial + 0.002 * (r2 + 2 * v * v) + 2 * 0.003 * u * v;
  const Eigen::Vector2d pixel = camera.ImageFromCam({u, v});
  EXPECT_NEAR(pixel.x(), 500 * ud + 320, 1e-12);
  EXPECT_NEAR(pixel.y(), 400 * vd + 240, 1e-12);
}

TEST(CameraModel, UndistortionInvertsProjectionForEveryModel) {
  const std::vector<Camera> cameras = {
      Camera::FromParams(CameraModelId::kSimplePinhole, 640, 480, {500, 319.5, 239.5}),
      Camera::FromParams(CameraModelId::kPinhole, 640, 480, {500, 520, 319.5, 239.5}),
      Camera::FromParams(CameraModelId::kSimpleRadial, 640, 480, {500, 319.5, 239.5, -0.2}),
      Camera::FromParams(CameraModelId::kRadial, 640, 480, {500, 319.5, 239.5, 0.15, -0.05}),
      Camera::FromParams(CameraModelId::kOpenCV, 640, 480,
                         {500, 520, 319.5, 239.5, -0.25, 0.08, 0.001, -0.0015})};
  for (const Camera& camera : cameras) {
    for (double x = 0; x <= 639; x += 71) {
      for (double y = 0; y <= 479; y += 53) {
        const Eigen::Vector2d normalized = camera.CamFromImage({x, y});
        const Eigen::Vector2d back = camera.ImageFromCam(normalized);
        EXPECT_NEAR(back.x(), x, 1e-8) << camera.Describe();
        EXPECT_NEAR(back.y(), y, 1e-8) << camera.Describe();
      }
    }
  }
  // Distortion moves the corner pixel: the undistorted pixel differs by the known amount.
  const Camera& barrel = cameras[2];
  const Eigen::Vector2d corner_normalized = barrel.CamFromImage({0, 0});
  const double r2 = corner_normalized.squaredNorm();
  EXPECT_NEAR(corner_normalized.x() * (1 - 0.2 * r2) * 500 + 319.5, 0.0, 1e-8);
  EXPECT_GT(barrel.UndistortPixel({0, 0}).norm(), 1.0);  // barrel: the corner moves outwards
}

TEST(CameraModel, ScalingKeepsDistortion) {
  const Camera camera =
      Camera::FromParams(CameraModelId::kRadial, 640, 480, {500, 319.5, 239.5, 0.15, -0.05});
  const Camera half = camera.Scaled(0.5);
  EXPECT_EQ(half.k1, 0.15);
  EXPECT_EQ(half.k2, -0.05);
  // The same ray lands on the same pixel area.
  const Eigen::Vector2d ray(0.3, -0.2);
  EXPECT_NEAR((half.ImageFromCam(ray).x() + 0.5) * 2, camera.ImageFromCam(ray).x() + 0.5, 1e-9);
}

}  // namespace
}  // namespace comic::sfm
