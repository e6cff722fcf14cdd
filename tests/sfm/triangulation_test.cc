// Triangulation: exact on noise-free views, robust to a wrong observation, and the angle,
// cheirality and depth checks.
#include "sfm/triangulation.h"

#include <gtest/gtest.h>

#include "io/core/error.h"
#include "sfm/reconstruction.h"
#include "sfm/synthetic_scene.h"

namespace comic::sfm {
namespace {

struct Views {
  Camera camera = Camera::FromImageSize(640, 480);
  std::vector<Rigid3d> poses;
};

// Cameras on a line along x (spacing in metres) looking at (0, 0, 10).
Views MakeViews(int n, double spacing) {
  Views views;
  for (int i = 0; i < n; ++i) {
    views.poses.push_back(LookAt(Eigen::Vector3d(spacing * i, 0, 0), Eigen::Vector3d(0, 0, 10)));
  }
  return views;
}

std::vector<TriangulationView> Observe(const Views& views, const Eigen::Vector3d& point) {
  std::vector<TriangulationView> observed;
  for (const Rigid3d& pose : views.poses) {
    observed.push_back({&views.camera, pose, *ProjectPoint(views.camera, pose, point)});
  }
  return observed;
}

TEST(Triangulation, DltIsExactWithoutNoise) {
  const Views views = MakeViews(3, 1.0);
  const Eigen::Vector3d point(0.4, -0.7, 9.0);
  std::vector<Eigen::Vector2d> normalized;
  for (const Rigid3d& pose : views.poses) {
    const Eigen::Vector3d p = pose * point;
    normalized.push_back(p.hnormalized());
  }
  const auto result = TriangulatePointDlt(views.poses, normalized);
  ASSERT_TRUE(result.has_value());
  EXPECT_LT((*result - point).norm(), 1e-9);
  EXPECT_FALSE(TriangulatePointDlt({views.poses[0]}, {normalized[0]}).has_value());
}

TEST(Triangulation, AngleBetweenRays) {
  EXPECT_NEAR(TriangulationAngleDeg({0, 0, 0}, {2, 0, 0}, {1, 0, 1}), 90.0, 1e-9);
  EXPECT_NEAR(TriangulationAngleDeg({0, 0, 0}, {0, 0, 0}, {1, 0, 1}), 0.0, 1e-5);
}

TEST(Triangulation, MultiViewRejectsAWrongObservation) {
  const Views views = MakeViews(5, 0.5);
  const Eigen::Vector3d point(0.3, 0.2, 10.0);
  std::vector<TriangulationView> observed = Observe(views, point);
  observed[2].point2D += Eigen::Vector2d(40, -25);  // a wrong match in the middle of the track
  const auto result = TriangulateMultiView(observed, TriangulationOptions());
  ASSERT_TRUE(result.has_value());
  EXPECT_LT((result->xyz - point).norm(), 1e-6);
  EXPECT_EQ(result->inlier_views, (std::vector<int>{0, 1, 3, 4}));
  EXPECT_GT(result->max_angle_deg, 5.0);
}

TEST(Triangulation, ChecksAngleDepthAndViewCount) {
  const Eigen::Vector3d point(0.3, 0.2, 10.0);
  // 2 cm baseline at 10 m: 0.1 degrees, below the 1.5 degree minimum.
  EXPECT_FALSE(TriangulateMultiView(Observe(MakeViews(2, 0.02), point), TriangulationOptions()));
  TriangulationOptions lenient;
  lenient.min_angle_deg = 0.05;
  EXPECT_TRUE(TriangulateMultiView(Observe(MakeViews(2, 0.02), point), lenient));
  // ... but it is 500 baselines away: rejected by a depth limit of 100 baselines.
  lenient.max_depth_to_baseline = 100;
  EXPECT_FALSE(TriangulateMultiView(Observe(MakeViews(2, 0.02), point), lenient));
  // One view is not enough; three agreeing views are required when asked.
  const Views views = MakeViews(3, 1.0);
  std::vector<TriangulationView> observed = Observe(views, point);
  EXPECT_FALSE(TriangulateMultiView({observed[0]}, TriangulationOptions()));
  TriangulationOptions three;
  three.min_num_views = 3;
  observed[1].point2D.x() += 30;
  EXPECT_FALSE(TriangulateMultiView(observed, three));
  EXPECT_TRUE(TriangulateMultiView(observed, TriangulationOptions()));
}

TEST(Triangulation, RejectsInvalidOptions) {
  TriangulationOptions options;
  options.min_num_views = 1;
  EXPECT_THROW(options.Check(), Error);
  options = TriangulationOptions();
  options.max_reprojection_error_px = 0;
  EXPECT_THROW(options.Check(), Error);
}

}  // namespace
}  // namespace comic::sfm
