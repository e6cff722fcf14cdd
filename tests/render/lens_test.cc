// render/lens.h against sfm/camera_model.h: the renderer keeps its own copy of the OPENCV
// distortion (render/ may not include sfm/), so the two are compared here point by point.
#include "render/lens.h"

#include <gtest/gtest.h>

#include <cmath>

#include "io/core/error.h"
#include "sfm/camera_model.h"

namespace comic::render {
namespace {

Lens DistortedLens() {
  Lens lens;
  lens.fx = 480.0;
  lens.fy = 470.0;
  lens.cx = 322.3;
  lens.cy = 236.8;
  lens.k1 = -0.12;
  lens.k2 = 0.03;
  lens.p1 = 0.001;
  lens.p2 = -0.0015;
  return lens;
}

TEST(Lens, DistortionMatchesSfmCameraModelEverywhereInTheImage) {
  const Lens lens = DistortedLens();
  const double params[8] = {lens.fx, lens.fy, lens.cx, lens.cy, lens.k1, lens.k2, lens.p1, lens.p2};
  for (double u = -0.75; u <= 0.75; u += 0.05) {
    for (double v = -0.55; v <= 0.55; v += 0.05) {
      const Eigen::Vector2d ours = lens.PixelFromNormalized({u, v});
      double x = 0.0;
      double y = 0.0;
      sfm::ImageFromNormalized(sfm::CameraModelId::kOpenCV, params, u, v, &x, &y);
      EXPECT_NEAR(ours.x(), x, 1e-9) << u << ", " << v;
      EXPECT_NEAR(ours.y(), y, 1e-9) << u << ", " << v;
      // And back: both inversions land on the same normalised point.
      const Eigen::Vector2d back = lens.NormalizedFromPixel(ours);
      const Eigen::Vector2d sfm_back =
          sfm::NormalizedFromImage(sfm::CameraModelId::kOpenCV, params, ours);
      EXPECT_NEAR(back.x(), u, 1e-10);
      EXPECT_NEAR(back.y(), v, 1e-10);
      EXPECT_NEAR(back.x(), sfm_back.x(), 1e-9);
      EXPECT_NEAR(back.y(), sfm_back.y(), 1e-9);
    }
  }
}

TEST(Lens, PinholeIsTheProjectionAndColmapParamsShiftThePrincipalPoint) {
  Lens lens;
  EXPECT_FALSE(lens.HasDistortion());
  const Eigen::Vector2d pixel = lens.PixelFromNormalized({0.1, -0.2});
  EXPECT_DOUBLE_EQ(pixel.x(), 500.0 * 0.1 + 319.5);
  EXPECT_DOUBLE_EQ(pixel.y(), 500.0 * -0.2 + 239.5);
  EXPECT_EQ(lens.ColmapModelName(), "PINHOLE");
  EXPECT_EQ(lens.ColmapParams(), (std::vector<double>{500.0, 500.0, 320.0, 240.0}));
  const Lens distorted = DistortedLens();
  EXPECT_EQ(distorted.ColmapModelName(), "OPENCV");
  EXPECT_EQ(distorted.ColmapParams().size(), 8u);
}

TEST(Lens, CheckRefusesBadValuesAndAFoldingDistortion) {
  Lens lens;
  EXPECT_NO_THROW(lens.Check());
  lens.fx = 0.0;
  EXPECT_THROW(lens.Check(), Error);
  lens = Lens();
  lens.width = 0;
  EXPECT_THROW(lens.Check(), Error);
  lens = Lens();
  lens.k1 = -1.5;  // r (1 - 1.5 r^2) turns back within the image's corners (r ~ 0.8)
  EXPECT_THROW(lens.Check(), Error);
  lens.k1 = -0.1;
  EXPECT_NO_THROW(lens.Check());
}

}  // namespace
}  // namespace comic::render
