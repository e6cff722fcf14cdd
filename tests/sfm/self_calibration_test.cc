// Self-calibration end to end: synthetic scenes rendered through each camera model with known
// distortion are reconstructed from a wrong prior (focal 8 % off, no distortion), and the bundle
// adjustment's refinement (sfm/incremental_pipeline.h policy) must recover the true parameters;
// a forward-only drive must be reported focal-unobservable and keep its prior.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

#include "sfm/incremental_pipeline.h"
#include "sfm/synthetic_scene.h"

namespace comic::sfm {
namespace {

struct ModelCase {
  CameraModelId model;
  double focal_y;  // 0: fy = fx
  double k1, k2, p1, p2;
};

// Renders a hand-held scene through `model_case`, reconstructs it from a prior focal 8 % long
// with zero distortion, and returns the refined camera.
Camera SelfCalibrate(const ModelCase& model_case, IncrementalReconstruction* result) {
  SyntheticSceneOptions scene_options;
  scene_options.motion = SyntheticMotion::kHandHeld;
  scene_options.num_frames = 16;
  scene_options.num_points = 900;
  scene_options.noise_px = 0.3;
  scene_options.outlier_ratio = 0.05;
  scene_options.model = model_case.model;
  scene_options.focal_y = model_case.focal_y;
  scene_options.k1 = model_case.k1;
  scene_options.k2 = model_case.k2;
  scene_options.p1 = model_case.p1;
  scene_options.p2 = model_case.p2;
  const SyntheticScene scene = MakeSyntheticScene(scene_options);
  Camera prior = scene.camera;
  prior.fx *= 1.08;
  prior.fy *= 1.08;
  prior.k1 = prior.k2 = prior.p1 = prior.p2 = 0.0;
  IncrementalPipelineOptions options;
  options.global_ba.refine_focal_length = true;
  options.global_ba.refine_extra_params = true;
  *result = ReconstructIncrementally(scene.tracks, prior, options);
  EXPECT_EQ(result->status, ReconstructionStatus::kSuccess);
  EXPECT_EQ(result->reconstruction.NumRegisteredImages(), scene.cams_from_world.size());
  EXPECT_TRUE(result->intrinsics_refined);
  EXPECT_TRUE(result->focal_assessed);
  EXPECT_TRUE(result->focal_observability.observable)
      << result->focal_observability.max_viewing_angle_deg << " deg";
  return result->reconstruction.cameras().begin()->second;
}

// Tolerances: focal within 0.5 % (the prior is 8 % off), distortion within 10 % of the true
// coefficient plus 0.005 absolute (radial) or 5e-4 (tangential), on 0.3 px noise.
void ExpectRecovered(const ModelCase& model_case) {
  IncrementalReconstruction result;
  const Camera camera = SelfCalibrate(model_case, &result);
  SCOPED_TRACE(camera.Describe());
  std::cout << "recovered: " << camera.Describe() << std::endl;
  EXPECT_EQ(camera.model, model_case.model);
  const double true_fy = model_case.focal_y != 0 ? model_case.focal_y : 600.0;
  EXPECT_NEAR(camera.fx, 600.0, 0.005 * 600.0);
  EXPECT_NEAR(camera.fy, true_fy, 0.005 * true_fy);
  EXPECT_NEAR(camera.k1, model_case.k1, 0.1 * std::abs(model_case.k1) + 0.005);
  EXPECT_NEAR(camera.k2, model_case.k2, 0.1 * std::abs(model_case.k2) + 0.005);
  EXPECT_NEAR(camera.p1, model_case.p1, 5e-4);
  EXPECT_NEAR(camera.p2, model_case.p2, 5e-4);
  EXPECT_LT(result.reconstruction.ComputeMeanReprojectionError(), 1.0);
}

TEST(SelfCalibration, RecoversSimplePinholeFocal) {
  ExpectRecovered({CameraModelId::kSimplePinhole, 0, 0, 0, 0, 0});
}

TEST(SelfCalibration, RecoversPinholeFocals) {
  ExpectRecovered({CameraModelId::kPinhole, 620, 0, 0, 0, 0});
}

TEST(SelfCalibration, RecoversSimpleRadialDistortion) {
  ExpectRecovered({CameraModelId::kSimpleRadial, 0, -0.12, 0, 0, 0});
}

TEST(SelfCalibration, RecoversRadialDistortion) {
  ExpectRecovered({CameraModelId::kRadial, 0, -0.15, 0.05, 0, 0});
}

TEST(SelfCalibration, RecoversOpenCvDistortion) {
  ExpectRecovered({CameraModelId::kOpenCV, 610, -0.15, 0.05, 0.002, -0.001});
}

// Driving straight ahead (optical axes within ~1.4°): the focal length is unobservable, which is
// reported, and the prior is kept instead of drifting.
TEST(SelfCalibration, ForwardOnlyMotionIsReportedFocalUnobservable) {
  SyntheticSceneOptions scene_options;
  scene_options.motion = SyntheticMotion::kForward;
  scene_options.num_frames = 25;
  scene_options.num_points = 800;
  const SyntheticScene scene = MakeSyntheticScene(scene_options);
  Camera prior = Camera::FromImageSize(scene.camera.width, scene.camera.height,
                                       CameraModelId::kSimpleRadial);  // f 768 for a true 600
  IncrementalPipelineOptions options;
  options.global_ba.refine_focal_length = true;
  options.global_ba.refine_extra_params = true;
  const IncrementalReconstruction result = ReconstructIncrementally(scene.tracks, prior, options);
  ASSERT_EQ(result.status, ReconstructionStatus::kSuccess);
  EXPECT_EQ(result.reconstruction.NumRegisteredImages(), scene.cams_from_world.size());
  ASSERT_TRUE(result.focal_assessed);
  EXPECT_FALSE(result.focal_observability.observable);
  EXPECT_LT(result.focal_observability.max_viewing_angle_deg, 5.0);
  const Camera& camera = result.reconstruction.cameras().begin()->second;
  EXPECT_EQ(camera.fx, prior.fx);
  EXPECT_EQ(camera.k1, 0.0);
}

// Fewer registered images than refine_intrinsics_min_num_images: nothing is refined.
TEST(SelfCalibration, TooFewImagesKeepThePrior) {
  SyntheticSceneOptions scene_options;
  scene_options.num_frames = 4;
  scene_options.num_points = 600;
  const SyntheticScene scene = MakeSyntheticScene(scene_options);
  Camera prior = scene.camera;
  prior.fx = prior.fy = 640.0;
  IncrementalPipelineOptions options;
  options.global_ba.refine_focal_length = true;
  const IncrementalReconstruction result = ReconstructIncrementally(scene.tracks, prior, options);
  ASSERT_EQ(result.status, ReconstructionStatus::kSuccess);
  EXPECT_FALSE(result.intrinsics_refined);
  EXPECT_EQ(result.reconstruction.cameras().begin()->second.fx, 640.0);
}

}  // namespace
}  // namespace comic::sfm
