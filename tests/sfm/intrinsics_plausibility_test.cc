// The plausible range of a self-calibrated camera: focal lengths within a factor of the prior,
// radial distortion that moves the image corner by a bounded fraction without folding it over.
#include "sfm/intrinsics_plausibility.h"

#include <gtest/gtest.h>

#include "io/core/error.h"

namespace comic::sfm {
namespace {

Camera Prior() { return Camera::FromImageSize(640, 480, CameraModelId::kSimpleRadial); }

TEST(IntrinsicsPlausibility, AcceptsCamerasNearThePrior) {
  Camera refined = Prior();
  refined.fx = refined.fy = 0.48 * Prior().fx;  // KITTI's focal against its prior
  refined.k1 = -0.15;
  const IntrinsicsPlausibility check =
      CheckIntrinsicsPlausibility(Prior(), refined, IntrinsicsPlausibilityOptions());
  EXPECT_TRUE(check.plausible) << check.reason;
  EXPECT_NEAR(check.focal_ratio, 0.48, 1e-12);
  EXPECT_TRUE(check.reason.empty());
}

TEST(IntrinsicsPlausibility, RejectsAFocalFarFromThePrior) {
  // VOT car1's first 150 frames: f 768 -> 2880 px.
  Camera refined = Prior();
  refined.fx = refined.fy = 2880.0;
  refined.k1 = -1.38;
  const IntrinsicsPlausibility check =
      CheckIntrinsicsPlausibility(Prior(), refined, IntrinsicsPlausibilityOptions());
  EXPECT_FALSE(check.plausible);
  EXPECT_NEAR(check.focal_ratio, 3.75, 1e-12);
  EXPECT_NE(check.reason.find("3.75x the prior 768.0 px"), std::string::npos) << check.reason;
  // A focal three times shorter than the prior is as implausible.
  refined.fx = refined.fy = 768.0 / 3.5;
  refined.k1 = 0.0;
  EXPECT_FALSE(
      CheckIntrinsicsPlausibility(Prior(), refined, IntrinsicsPlausibilityOptions()).plausible);
}

TEST(IntrinsicsPlausibility, RejectsDistortionThatMovesOrFoldsTheCorner) {
  Camera refined = Prior();
  // The corner's normalised radius is 400 / 768 = 0.52, r^2 = 0.27: k1 = -1.38 moves it by 37 %.
  refined.k1 = -1.38;
  IntrinsicsPlausibility check =
      CheckIntrinsicsPlausibility(Prior(), refined, IntrinsicsPlausibilityOptions());
  EXPECT_FALSE(check.plausible);
  EXPECT_NEAR(check.corner_distortion, -1.38 * (320.0 * 320.0 + 240.0 * 240.0) / (768.0 * 768.0),
              1e-9);
  EXPECT_NE(check.reason.find("radial distortion"), std::string::npos) << check.reason;
  // Within the bound the radius can still stop growing: k1 r^2 < -1/3 folds the image over.
  IntrinsicsPlausibilityOptions loose;
  loose.max_corner_distortion = 0.9;
  refined.k1 = -1.5;
  check = CheckIntrinsicsPlausibility(Prior(), refined, loose);
  EXPECT_FALSE(check.plausible);
  EXPECT_NE(check.reason.find("folds"), std::string::npos) << check.reason;
}

TEST(IntrinsicsPlausibility, RejectsBadOptions) {
  IntrinsicsPlausibilityOptions options;
  options.max_focal_ratio = 1.0;
  EXPECT_THROW(CheckIntrinsicsPlausibility(Prior(), Prior(), options), Error);
  options = IntrinsicsPlausibilityOptions();
  options.max_corner_distortion = 0.0;
  EXPECT_THROW(options.Check(), Error);
}

}  // namespace
}  // namespace comic::sfm
