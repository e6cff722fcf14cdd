// Trajectory evaluation: Umeyama recovers a known similarity, a trajectory that differs from the
// truth only by a similarity scores zero, known errors come out as computed by hand, and a
// straight path (ill-posed Sim(3) rotation) still gets a meaningful rotation error.
#include "sfm/trajectory_evaluation.h"

#include <gtest/gtest.h>

#include <cmath>

#include "io/core/error.h"
#include "sfm/synthetic_scene.h"

namespace comic::sfm {
namespace {

Sim3d MakeSim3() {
  Sim3d sim3;
  sim3.scale = 0.37;
  sim3.rotation =
      Eigen::Quaterniond(Eigen::AngleAxisd(2.1, Eigen::Vector3d(1, -2, 0.5).normalized()));
  sim3.translation = Eigen::Vector3d(5, -1, 2);
  return sim3;
}

// A curved path of poses looking at a point.
std::vector<std::optional<Rigid3d>> MakeTruth(int n) {
  std::vector<std::optional<Rigid3d>> poses;
  for (int i = 0; i < n; ++i) {
    const double a = 0.15 * i;
    poses.push_back(LookAt(Eigen::Vector3d(4 * std::sin(a), 0.2 * i, 4 * std::cos(a)), {0, 0, 0}));
  }
  return poses;
}

TEST(TrajectoryEvaluation, UmeyamaRecoversASimilarity) {
  const Sim3d truth = MakeSim3();
  std::vector<Eigen::Vector3d> src = {{0, 0, 0}, {1, 0, 0}, {0, 2, 0}, {0, 0, 3}, {1, 1, 1}};
  std::vector<Eigen::Vector3d> dst;
  for (const Eigen::Vector3d& p : src) dst.push_back(truth * p);
  const auto estimate = EstimateSim3dUmeyama(src, dst);
  ASSERT_TRUE(estimate.has_value());
  EXPECT_NEAR(estimate->scale, truth.scale, 1e-12);
  EXPECT_LT(RotationAngleDeg(estimate->rotation, truth.rotation), 1e-6);
  EXPECT_TRUE(estimate->translation.isApprox(truth.translation, 1e-12));
  EXPECT_FALSE(EstimateSim3dUmeyama({src[0], src[1]}, {dst[0], dst[1]}).has_value());
  EXPECT_FALSE(EstimateSim3dUmeyama({src[0], src[0], src[0]}, {dst[0], dst[1], dst[2]}));
}

TEST(TrajectoryEvaluation, ASimilarityAwayFromTheTruthScoresZero) {
  const std::vector<std::optional<Rigid3d>> truth = MakeTruth(12);
  // The estimate lives in a world that the truth's world maps into by `estimated_from_true`.
  const Sim3d estimated_from_true = MakeSim3();
  std::vector<std::optional<Rigid3d>> estimated;
  for (const auto& pose : truth) estimated.push_back(estimated_from_true.TransformPose(*pose));
  estimated[4].reset();  // an unregistered frame
  const auto evaluation = EvaluateTrajectory(estimated, truth);
  ASSERT_TRUE(evaluation.has_value());
  EXPECT_EQ(evaluation->frames.size(), 11u);
  EXPECT_LT(evaluation->ate_rmse, 1e-9);
  EXPECT_LT(evaluation->mean_rotation_error_deg, 1e-6);
  EXPECT_LT(evaluation->mean_rotation_error_sim3_deg, 1e-6);
  EXPECT_NEAR(evaluation->gt_from_estimated.scale, 1.0 / estimated_from_true.scale, 1e-9);
  double path = 0;
  for (size_t k = 1; k < evaluation->frames.size(); ++k) {
    path += (ProjectionCenter(*truth[evaluation->frames[k]]) -
             ProjectionCenter(*truth[evaluation->frames[k - 1]]))
                .norm();
  }
  EXPECT_NEAR(evaluation->path_length, path, 1e-12);
}

TEST(TrajectoryEvaluation, KnownErrors) {
  // Truth: centres at x = 0..4 m on a line; estimate: the same but frame 2 moved 0.5 m sideways
  // and frame 3 rotated by 2 degrees. The alignment absorbs part of the shift, so compare with
  // the residuals of the fitted similarity rather than 0.5 itself.
  std::vector<std::optional<Rigid3d>> truth, estimated;
  for (int i = 0; i < 5; ++i) {
    Rigid3d pose;
    pose.translation = -Eigen::Vector3d(i, 0.1 * i * i, 0);  // a slightly curved path
    truth.push_back(pose);
    estimated.push_back(pose);
  }
  estimated[2]->translation.z() -= 0.5;
  estimated[3]->rotation =
      Eigen::Quaterniond(Eigen::AngleAxisd(2 * M_PI / 180, Eigen::Vector3d::UnitY()));
  const auto evaluation = EvaluateTrajectory(estimated, truth);
  ASSERT_TRUE(evaluation.has_value());
  double sum = 0;
  for (double e : evaluation->position_errors) sum += e * e;
  EXPECT_NEAR(evaluation->ate_rmse, std::sqrt(sum / 5), 1e-12);
  EXPECT_GT(evaluation->ate_rmse, 0.1);
  EXPECT_LT(evaluation->ate_rmse, 0.5);
  EXPECT_GT(evaluation->position_errors[2], evaluation->position_errors[0]);
  // One frame off by 2 degrees: the averaged alignment turns by about 2/5 degree, leaving
  // 0.4 degrees on four frames and 1.6 on the fifth: a mean of (4 x 0.4 + 1.6) / 5 = 0.64.
  EXPECT_NEAR(evaluation->mean_rotation_error_deg, 0.64, 1e-3);
  EXPECT_NEAR(evaluation->ate_fraction_of_path, evaluation->ate_rmse / evaluation->path_length,
              1e-15);
  // End to start: the aligned first and last centres against the true ones (frames 0 and 4 are
  // exact, so only the alignment moves them).
  const Sim3d& sim3 = evaluation->gt_from_estimated;
  const Eigen::Vector3d estimated_span =
      sim3 * ProjectionCenter(*estimated[4]) - sim3 * ProjectionCenter(*estimated[0]);
  const Eigen::Vector3d true_span = ProjectionCenter(*truth[4]) - ProjectionCenter(*truth[0]);
  EXPECT_NEAR(evaluation->end_to_start_error, (estimated_span - true_span).norm(), 1e-12);
}

TEST(TrajectoryEvaluation, EndToStartErrorIsTheDriftOfTheLastFrame) {
  // A square loop of 40 frames; the estimate's last 10 frames drift 1 m sideways (growing
  // linearly), as an open loop does. The error of the last position relative to the first is
  // about that 1 m (the alignment shares a little of it out), and 0 without the drift.
  std::vector<std::optional<Rigid3d>> truth, estimated;
  for (int i = 0; i < 40; ++i) {
    const double t = i / 10.0;
    Eigen::Vector3d center(std::min(t, 1.0) - std::max(0.0, std::min(t - 2, 1.0)), 0,
                           std::max(0.0, std::min(t - 1, 1.0)) - std::max(0.0, t - 3));
    Rigid3d pose;
    pose.translation = -center;
    truth.push_back(pose);
    if (i >= 30) center.x() += (i - 29) / 10.0;
    Rigid3d drifted;
    drifted.translation = -center;
    estimated.push_back(drifted);
  }
  const auto exact = EvaluateTrajectory(truth, truth);
  ASSERT_TRUE(exact.has_value());
  EXPECT_LT(exact->end_to_start_error, 1e-9);
  const auto evaluation = EvaluateTrajectory(estimated, truth);
  ASSERT_TRUE(evaluation.has_value());
  EXPECT_GT(evaluation->end_to_start_error, 0.7);
  EXPECT_LT(evaluation->end_to_start_error, 1.3);
}

TEST(TrajectoryEvaluation, StraightPathRotationErrorIsWellDefined) {
  // Cameras on a straight line: the centres leave the roll about the line to chance, so the
  // Sim(3) rotation can be off; the orientation-based alignment is not.
  std::vector<std::optional<Rigid3d>> truth, estimated;
  const Eigen::Quaterniond roll(Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ()));
  for (int i = 0; i < 10; ++i) {
    Rigid3d pose;
    pose.translation = Eigen::Vector3d(0, 0, -1.2 * i);
    truth.push_back(pose);
    // The estimate's world is rolled by 0.3 rad about the path: same centres, rotated cameras.
    estimated.push_back(Rigid3d(pose.rotation * roll.conjugate(), pose.translation));
  }
  const auto evaluation = EvaluateTrajectory(estimated, truth);
  ASSERT_TRUE(evaluation.has_value());
  EXPECT_LT(evaluation->ate_rmse, 1e-9);
  EXPECT_LT(evaluation->mean_rotation_error_deg, 1e-6);
}

TEST(TrajectoryEvaluation, TooFewFramesOrMismatchedSizes) {
  const std::vector<std::optional<Rigid3d>> truth = MakeTruth(4);
  std::vector<std::optional<Rigid3d>> estimated = truth;
  estimated[0].reset();
  estimated[1].reset();
  EXPECT_FALSE(EvaluateTrajectory(estimated, truth).has_value());
  EXPECT_THROW(EvaluateTrajectory({truth[0]}, truth), Error);
}

}  // namespace
}  // namespace comic::sfm
