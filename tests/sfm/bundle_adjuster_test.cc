// Bundle adjustment on a perturbed synthetic scene: the cost falls to the noise level, the gauge
// stays where it was fixed, the focal length is recovered when refined, and the result is
// deterministic.
#include "sfm/bundle_adjuster.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <random>
#include <set>
#include <vector>

#include "io/core/error.h"
#include "sfm/synthetic_scene.h"

namespace comic::sfm {
namespace {

constexpr double kNoisePx = 0.5;

// The ground truth of a synthetic scene (observations with 0.5 px noise, no outliers) as a
// Reconstruction, then perturbed: poses by ~1 degree and ~5 cm, points by ~10 cm.
struct Scene {
  Reconstruction truth;
  Reconstruction perturbed;
};

Scene MakeScene(uint32_t seed) {
  SyntheticSceneOptions options;
  options.num_frames = 6;
  options.num_points = 150;
  options.noise_px = kNoisePx;
  options.outlier_ratio = 0.0;
  options.track_break_probability = 0.0;
  options.seed = seed;
  const SyntheticScene synthetic = MakeSyntheticScene(options);
  Scene scene;
  const camera_t camera_id = scene.truth.AddCamera(synthetic.camera);
  for (size_t frame = 0; frame < synthetic.tracks.NumFrames(); ++frame) {
    Image image;
    image.camera_id = camera_id;
    image.cam_from_world = synthetic.cams_from_world[frame];
    for (const frontend::Feature& feature : synthetic.tracks.features[frame]) {
      Point2D point2D;
      point2D.xy = Eigen::Vector2d(feature.x, feature.y);
      image.points2D.push_back(point2D);
    }
    scene.truth.RegisterImage(scene.truth.AddImage(image));
  }
  for (size_t t = 0; t < synthetic.tracks.tracks.size(); ++t) {
    std::vector<TrackElement> track;
    for (const frontend::TrackObservation& obs : synthetic.tracks.tracks[t].observations) {
      track.push_back({static_cast<image_t>(obs.frame + 1), static_cast<point2D_t>(obs.feature)});
    }
    if (track.size() >= 2) {
      scene.truth.AddPoint3D(synthetic.points3D[synthetic.track_point_index[t]], track);
    }
  }
  scene.perturbed = scene.truth;
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal(0, 1);
  for (image_t image_id : scene.perturbed.RegisteredImageIds()) {
    if (image_id == 1) continue;  // the gauge image stays
    Rigid3d& pose = scene.perturbed.image(image_id).cam_from_world;
    const Eigen::Vector3d axis(normal(rng), normal(rng), normal(rng));
    pose.rotation =
        (Eigen::Quaterniond(Eigen::AngleAxisd(0.017, axis.normalized())) * pose.rotation)
            .normalized();
    // Image 2's translation sets the scale (see FullConfig): it stays true so the adjusted poses
    // can be compared with the truth directly.
    const Eigen::Vector3d shift(normal(rng), normal(rng), normal(rng));
    if (image_id != 2) pose.translation += 0.05 * shift;
  }
  for (const auto& [id, point] : scene.truth.points3D()) {
    scene.perturbed.point3D(id).xyz += 0.1 * Eigen::Vector3d(normal(rng), normal(rng), normal(rng));
  }
  return scene;
}

BundleAdjustmentConfig FullConfig(const Reconstruction& reconstruction) {
  BundleAdjustmentConfig config;
  for (image_t id : reconstruction.RegisteredImageIds()) config.image_ids.insert(id);
  config.constant_pose_ids.insert(1);
  config.fixed_scale_image_ids.insert(2);
  return config;
}

// The analytic Jacobians of the fixed-intrinsics residual against central differences, at a
// quaternion that is not of unit length (Ceres evaluates the ambient 7-vector as stored).
TEST(BundleAdjuster, AnalyticReprojectionJacobianMatchesCentralDifferences) {
  const Eigen::Quaterniond rotation =
      Eigen::Quaterniond(Eigen::AngleAxisd(0.4, Eigen::Vector3d(1, -2, 0.5).normalized()));
  double pose[7] = {1.1 * rotation.x(),
                    1.1 * rotation.y(),
                    1.1 * rotation.z(),
                    1.1 * rotation.w(),
                    0.3,
                    -0.2,
                    1.5};
  double point[3] = {0.7, -0.4, 6.0};
  const double intrinsics[4] = {700.0, 710.0, 320.0, 240.0};
  const Eigen::Vector2d observed(330.0, 250.0);
  double residuals[2], jacobian_pose[14], jacobian_point[6];
  ASSERT_TRUE(EvaluateReprojection(pose, point, intrinsics, observed, residuals, jacobian_pose,
                                   jacobian_point));
  // The residual itself: Eigen's rotation formula, v + 2w (u × v) + 2 u × (u × v), is quadratic in
  // q, so with q = s q0 (s = 1.1) it gives v + s^2 (R0 v - v), projected.
  const Eigen::Vector3d v(point[0], point[1], point[2]);
  const Eigen::Vector3d cam = v + 1.21 * (rotation * v - v) + Eigen::Vector3d(0.3, -0.2, 1.5);
  EXPECT_NEAR(residuals[0], 700.0 * cam.x() / cam.z() + 320.0 - 330.0, 1e-9);
  EXPECT_NEAR(residuals[1], 710.0 * cam.y() / cam.z() + 240.0 - 250.0, 1e-9);
  const double step = 1e-6;
  const auto numeric = [&](double* parameter, int row) {
    const double saved = *parameter;
    double plus[2], minus[2];
    *parameter = saved + step;
    EvaluateReprojection(pose, point, intrinsics, observed, plus, nullptr, nullptr);
    *parameter = saved - step;
    EvaluateReprojection(pose, point, intrinsics, observed, minus, nullptr, nullptr);
    *parameter = saved;
    return (plus[row] - minus[row]) / (2 * step);
  };
  for (int row = 0; row < 2; ++row) {
    for (int c = 0; c < 7; ++c) {
      EXPECT_NEAR(jacobian_pose[7 * row + c], numeric(&pose[c], row), 1e-4)
          << "pose row " << row << " column " << c;
    }
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(jacobian_point[3 * row + c], numeric(&point[c], row), 1e-4)
          << "point row " << row << " column " << c;
    }
  }
}

TEST(BundleAdjuster, ReducesThePerturbedCostToTheNoiseLevel) {
  Scene scene = MakeScene(11);
  const BundleAdjustmentConfig config = FullConfig(scene.perturbed);
  const Rigid3d gauge_pose = scene.perturbed.image(1).cam_from_world;
  const Eigen::Vector3d scale_translation = scene.perturbed.image(2).cam_from_world.translation;
  const BundleAdjustmentSummary summary =
      BundleAdjuster(BundleAdjustmentOptions(), config).Solve(&scene.perturbed);
  ASSERT_TRUE(summary.usable) << summary.termination;
  EXPECT_EQ(summary.num_images, 6);
  EXPECT_EQ(summary.num_variable_images, 5);
  EXPECT_EQ(summary.num_points, static_cast<int>(scene.perturbed.NumPoints3D()));
  EXPECT_EQ(summary.num_residuals, static_cast<int>(scene.perturbed.NumObservations()));
  // The noise level: an observation's error is the length of a 2-D Gaussian with kNoisePx per
  // axis, whose RMS is kNoisePx·√2; a least-squares fit (3 parameters per point, 6 per pose, 2
  // residuals per observation) sits a little below it.
  const double noise_rmse = kNoisePx * std::sqrt(2.0);
  EXPECT_GT(summary.initial_rmse_px, 10 * noise_rmse);
  EXPECT_LT(summary.final_rmse_px, noise_rmse);
  EXPECT_GT(summary.final_rmse_px, 0.7 * noise_rmse);
  // Ceres' cost ½ Σ ρ(r²) at that level (the Huber loss is quadratic below 1 px).
  const double noise_cost = 0.5 * summary.num_residuals * noise_rmse * noise_rmse;
  EXPECT_LT(summary.final_cost, noise_cost);
  EXPECT_GT(summary.initial_cost, 20 * noise_cost);
  EXPECT_GT(summary.wall_time_s, 0.0);
  // The gauge: the first pose untouched, the second's largest translation coordinate untouched.
  EXPECT_EQ(scene.perturbed.image(1).cam_from_world.translation, gauge_pose.translation);
  EXPECT_EQ(scene.perturbed.image(1).cam_from_world.rotation.coeffs(),
            gauge_pose.rotation.coeffs());
  int largest = 0;
  scale_translation.cwiseAbs().maxCoeff(&largest);
  EXPECT_DOUBLE_EQ(scene.perturbed.image(2).cam_from_world.translation(largest),
                   scale_translation(largest));
  // And the poses are back near the truth.
  for (image_t id : scene.truth.RegisteredImageIds()) {
    EXPECT_LT((ProjectionCenter(scene.perturbed.image(id).cam_from_world) -
               ProjectionCenter(scene.truth.image(id).cam_from_world))
                  .norm(),
              0.05)
        << "image " << id;
  }
}

TEST(BundleAdjuster, RefinesTheFocalLengthWhenAsked) {
  Scene scene = MakeScene(12);
  const double true_focal = scene.perturbed.camera(1).fx;
  scene.perturbed.camera(1).fx *= 1.03;
  scene.perturbed.camera(1).fy *= 1.03;
  BundleAdjustmentOptions fixed;
  Reconstruction held = scene.perturbed;
  BundleAdjuster(fixed, FullConfig(held)).Solve(&held);
  EXPECT_DOUBLE_EQ(held.camera(1).fx, 1.03 * true_focal);  // held fixed by default
  BundleAdjustmentOptions refine;
  refine.refine_focal_length = true;
  const BundleAdjustmentSummary summary =
      BundleAdjuster(refine, FullConfig(scene.perturbed)).Solve(&scene.perturbed);
  ASSERT_TRUE(summary.usable);
  EXPECT_NEAR(scene.perturbed.camera(1).fx / true_focal, 1.0, 0.01);
  EXPECT_DOUBLE_EQ(scene.perturbed.camera(1).cx, scene.truth.camera(1).cx);
  EXPECT_LT(summary.final_rmse_px, kNoisePx * std::sqrt(2.0));
}

// Each loss brings the perturbed scene back to the noise level; with wrong observations among
// the right ones the robust losses (Huber, Soft-L1) keep the poses nearer the truth than plain
// least squares.
TEST(BundleAdjuster, EveryLossReachesTheNoiseLevelAndRobustOnesResistWrongObservations) {
  EXPECT_STREQ(BundleAdjustmentLossName(BundleAdjustmentLoss::kTrivial), "trivial");
  EXPECT_STREQ(BundleAdjustmentLossName(BundleAdjustmentLoss::kHuber), "huber");
  EXPECT_STREQ(BundleAdjustmentLossName(BundleAdjustmentLoss::kSoftL1), "soft_l1");
  const double noise_rmse = kNoisePx * std::sqrt(2.0);
  // Largest camera-centre error against the truth after adjusting `scene` with `loss`.
  const auto adjust = [](Scene scene, BundleAdjustmentLoss loss, BundleAdjustmentSummary* out) {
    BundleAdjustmentOptions options;
    options.loss = loss;
    *out = BundleAdjuster(options, FullConfig(scene.perturbed)).Solve(&scene.perturbed);
    double max_error = 0.0;
    for (image_t id : scene.truth.RegisteredImageIds()) {
      max_error = std::max(max_error, (ProjectionCenter(scene.perturbed.image(id).cam_from_world) -
                                       ProjectionCenter(scene.truth.image(id).cam_from_world))
                                          .norm());
    }
    return max_error;
  };
  const Scene clean = MakeScene(15);
  for (BundleAdjustmentLoss loss : {BundleAdjustmentLoss::kTrivial, BundleAdjustmentLoss::kHuber,
                                    BundleAdjustmentLoss::kSoftL1}) {
    BundleAdjustmentSummary summary;
    EXPECT_LT(adjust(clean, loss, &summary), 0.05) << BundleAdjustmentLossName(loss);
    ASSERT_TRUE(summary.usable) << summary.termination;
    EXPECT_LT(summary.final_rmse_px, noise_rmse) << BundleAdjustmentLossName(loss);
  }
  // Every 15th observation moved by 40 px (a wrong match the tracker kept).
  Scene wrong = MakeScene(15);
  size_t count = 0;
  for (image_t id : wrong.perturbed.RegisteredImageIds()) {
    for (Point2D& point2D : wrong.perturbed.image(id).points2D) {
      if (point2D.HasPoint3D() && ++count % 15 == 0) point2D.xy += Eigen::Vector2d(40.0, -25.0);
    }
  }
  BundleAdjustmentSummary summary;
  const double trivial_error = adjust(wrong, BundleAdjustmentLoss::kTrivial, &summary);
  const double huber_error = adjust(wrong, BundleAdjustmentLoss::kHuber, &summary);
  const double soft_l1_error = adjust(wrong, BundleAdjustmentLoss::kSoftL1, &summary);
  EXPECT_LT(huber_error, 0.5 * trivial_error);
  EXPECT_LT(soft_l1_error, 0.5 * trivial_error);

  BundleAdjustmentOptions bad;
  bad.loss = static_cast<BundleAdjustmentLoss>(7);
  EXPECT_THROW(bad.Check(), Error);
}

TEST(BundleAdjuster, IsDeterministic) {
  Scene a = MakeScene(13);
  Scene b = MakeScene(13);
  BundleAdjuster(BundleAdjustmentOptions(), FullConfig(a.perturbed)).Solve(&a.perturbed);
  BundleAdjuster(BundleAdjustmentOptions(), FullConfig(b.perturbed)).Solve(&b.perturbed);
  for (image_t id : a.perturbed.RegisteredImageIds()) {
    EXPECT_EQ(a.perturbed.image(id).cam_from_world.translation,
              b.perturbed.image(id).cam_from_world.translation);
  }
  for (const auto& [id, point] : a.perturbed.points3D()) {
    EXPECT_EQ(point.xyz, b.perturbed.point3D(id).xyz);
  }
}

// Issue 19: with Ceres' threads the last bits changed between runs. The same problem at 1 and 2
// threads, and twice at 2, must give the same poses and points bit for bit.
TEST(BundleAdjuster, IsIdenticalBitForBitAtOneAndTwoThreads) {
  Scene one = MakeScene(15);
  Scene two = MakeScene(15);
  Scene again = MakeScene(15);
  BundleAdjustmentOptions single;
  single.num_threads = 1;
  BundleAdjustmentOptions threaded;
  threaded.num_threads = 2;
  BundleAdjuster(single, FullConfig(one.perturbed)).Solve(&one.perturbed);
  BundleAdjuster(threaded, FullConfig(two.perturbed)).Solve(&two.perturbed);
  BundleAdjuster(threaded, FullConfig(again.perturbed)).Solve(&again.perturbed);
  ASSERT_FALSE(one.perturbed.points3D().empty());
  for (image_t id : one.perturbed.RegisteredImageIds()) {
    for (const Scene* other : {&two, &again}) {
      EXPECT_EQ(one.perturbed.image(id).cam_from_world.translation,
                other->perturbed.image(id).cam_from_world.translation);
      EXPECT_EQ(one.perturbed.image(id).cam_from_world.rotation.coeffs(),
                other->perturbed.image(id).cam_from_world.rotation.coeffs());
    }
  }
  for (const auto& [id, point] : one.perturbed.points3D()) {
    EXPECT_EQ(point.xyz, two.perturbed.point3D(id).xyz);
    EXPECT_EQ(point.xyz, again.perturbed.point3D(id).xyz);
  }
}

// Issue 26: long adjustments report each iteration once progress_after_s has passed; the report
// changes nothing in the solution.
TEST(BundleAdjuster, ReportsProgressWithoutChangingTheSolution) {
  Scene quiet = MakeScene(16);
  Scene reported = MakeScene(16);
  const BundleAdjustmentSummary expected =
      BundleAdjuster(BundleAdjustmentOptions(), FullConfig(quiet.perturbed))
          .Solve(&quiet.perturbed);
  std::vector<BundleAdjustmentProgress> lines;
  BundleAdjustmentOptions options;
  options.progress_after_s = 0;
  options.progress = [&](const BundleAdjustmentProgress& p) { lines.push_back(p); };
  const BundleAdjustmentSummary summary =
      BundleAdjuster(options, FullConfig(reported.perturbed)).Solve(&reported.perturbed);
  ASSERT_GT(expected.num_iterations, 1);
  EXPECT_EQ(summary.num_iterations, expected.num_iterations);
  EXPECT_EQ(summary.final_cost, expected.final_cost);
  // Ceres reports the state before the first step as iteration 0, then one per iteration.
  ASSERT_EQ(static_cast<int>(lines.size()), expected.num_iterations);
  for (size_t i = 0; i < lines.size(); ++i) {
    EXPECT_EQ(lines[i].iteration, static_cast<int>(i));
    EXPECT_EQ(lines[i].num_variable_images, summary.num_variable_images);
    EXPECT_EQ(lines[i].num_points, summary.num_points);
    EXPECT_EQ(lines[i].max_num_iterations, options.max_num_iterations);
    EXPECT_EQ(lines[i].first, i == 0);  // a new solve starts a new series of lines
    if (i > 0) {
      EXPECT_GE(lines[i].elapsed_s, lines[i - 1].elapsed_s);
    }
  }
  EXPECT_EQ(lines.front().cost, summary.initial_cost);
  for (const auto& [id, point] : quiet.perturbed.points3D()) {
    EXPECT_EQ(point.xyz, reported.perturbed.point3D(id).xyz);
  }
  // A solve shorter than progress_after_s says nothing.
  Scene fast = MakeScene(16);
  lines.clear();
  options.progress_after_s = 3600;
  BundleAdjuster(options, FullConfig(fast.perturbed)).Solve(&fast.perturbed);
  EXPECT_TRUE(lines.empty());
  options.progress_after_s = -1;
  EXPECT_THROW(options.Check(), Error);
}

TEST(BundleAdjuster, ConstantNeighboursAreTheRegisteredImagesSeeingTheWindowsPoints) {
  Reconstruction reconstruction = MakeScene(3).truth;
  const std::set<image_t> window = {3, 4};
  std::set<point3D_t> point_ids;
  for (image_t id : window) {
    for (const Point2D& point2D : reconstruction.image(id).points2D) {
      if (point2D.HasPoint3D()) point_ids.insert(point2D.point3D_id);
    }
  }
  // Found the other way round: images outside the window with an observation of those points.
  auto expected = [&] {
    std::set<image_t> images;
    for (image_t id : reconstruction.RegisteredImageIds()) {
      if (window.count(id)) continue;
      for (const Point2D& point2D : reconstruction.image(id).points2D) {
        if (point2D.HasPoint3D() && point_ids.count(point2D.point3D_id)) images.insert(id);
      }
    }
    return images;
  };
  const std::set<image_t> neighbours = ConstantNeighbourImages(reconstruction, window, point_ids);
  EXPECT_EQ(neighbours, expected());
  EXPECT_EQ(neighbours.size(), 4u);  // every other frame of the six sees some of those points
  // An image not registered (its observations still in the tracks) is no neighbour, and no point
  // means no neighbour.
  reconstruction.image(6).registered = false;
  const std::set<image_t> registered = ConstantNeighbourImages(reconstruction, window, point_ids);
  EXPECT_EQ(registered.count(6), 0u);
  EXPECT_EQ(registered.size(), 3u);
  EXPECT_TRUE(ConstantNeighbourImages(reconstruction, window, {}).empty());
}

TEST(BundleAdjuster, EmptyProblemsAndBadInput) {
  Scene scene = MakeScene(14);
  BundleAdjustmentConfig nothing;
  const BundleAdjustmentSummary summary =
      BundleAdjuster(BundleAdjustmentOptions(), nothing).Solve(&scene.perturbed);
  EXPECT_FALSE(summary.usable);
  EXPECT_EQ(summary.num_residuals, 0);
  BundleAdjustmentConfig unknown;
  unknown.image_ids.insert(99);
  EXPECT_THROW(BundleAdjuster(BundleAdjustmentOptions(), unknown).Solve(&scene.perturbed), Error);
  BundleAdjustmentOptions bad;
  bad.loss_scale_px = 0;
  EXPECT_THROW(BundleAdjuster(bad, nothing), Error);
}

}  // namespace
}  // namespace comic::sfm
