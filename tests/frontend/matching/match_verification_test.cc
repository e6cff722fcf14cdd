#include "frontend/matching/match_verification.h"

#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/core.hpp>

#include "frontend/evaluation/epipolar_check.h"
#include "io/core/error.h"

namespace comic::frontend {
namespace {

// Two views of random points in front of both cameras: feature k of view 1 and feature k of
// view 2 are the projections of point k (with 0.3 px noise).
struct TwoViews {
  cv::Matx33d K{600, 0, 320, 0, 600, 240, 0, 0, 1};
  cv::Matx34d world_from_a{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0};
  cv::Matx34d world_from_b;
  FeatureSet a, b;
};

TwoViews MakeTwoViews(int num_points) {
  TwoViews views;
  const double angle = 10.0 * M_PI / 180.0;  // b: turned by 10 degrees about y, 0.5 m aside
  views.world_from_b = cv::Matx34d(std::cos(angle), 0, std::sin(angle), 0.5, 0, 1, 0, 0.05,
                                   -std::sin(angle), 0, std::cos(angle), 0.1);
  cv::RNG rng(3);
  auto project = [&](const cv::Matx34d& world_from_camera, const cv::Vec3d& x) {
    const cv::Matx33d r = world_from_camera.get_minor<3, 3>(0, 0);
    const cv::Vec3d t(world_from_camera(0, 3), world_from_camera(1, 3), world_from_camera(2, 3));
    const cv::Vec3d p = views.K * (r.t() * (x - t));
    Feature f;
    f.x = static_cast<float>(p[0] / p[2] + rng.gaussian(0.3));
    f.y = static_cast<float>(p[1] / p[2] + rng.gaussian(0.3));
    return f;
  };
  while (static_cast<int>(views.a.size()) < num_points) {
    const cv::Vec3d x(rng.uniform(-2.0, 2.0), rng.uniform(-1.5, 1.5), rng.uniform(4.0, 10.0));
    const Feature fa = project(views.world_from_a, x), fb = project(views.world_from_b, x);
    if (fa.x < 0 || fa.x > 640 || fa.y < 0 || fa.y > 480 || fb.x < 0 || fb.x > 640 || fb.y < 0 ||
        fb.y > 480) {
      continue;
    }
    views.a.push_back(fa);
    views.b.push_back(fb);
  }
  return views;
}

TEST(MatchVerification, KeepsTheMatchesOfTheEpipolarGeometryAndDropsTheRest) {
  const TwoViews views = MakeTwoViews(200);
  // 150 right matches, 50 wrong ones (feature k of view 1 with feature k + 1 of view 2).
  std::vector<PatchMatch> matches;
  for (int k = 0; k < 200; ++k) matches.push_back({k, k < 150 ? k : (k + 1) % 200, 1.f});
  const MatchVerificationOptions options;
  const std::vector<PatchMatch> kept = VerifyMatches(views.a, views.b, matches, options);
  const cv::Matx33d F = FundamentalFromPoses(views.K, views.world_from_a, views.world_from_b);
  int right = 0;
  for (const PatchMatch& m : kept) {
    right += m.index1 == m.index2 ? 1 : 0;
    // Whatever is kept lies on its true epipolar line (a wrong match may by chance).
    EXPECT_LT(EpipolarDistance(F, views.a[m.index1].Position(), views.b[m.index2].Position()), 3.0);
  }
  EXPECT_GE(right, 145);
  EXPECT_LE(static_cast<int>(kept.size()) - right, 3);
  EXPECT_TRUE(std::is_sorted(kept.begin(), kept.end(),
                             [](const auto& x, const auto& y) { return x.index1 < y.index1; }));
  // Seeded: the same result again.
  const std::vector<PatchMatch> again = VerifyMatches(views.a, views.b, matches, options);
  ASSERT_EQ(again.size(), kept.size());
  for (size_t i = 0; i < kept.size(); ++i) EXPECT_EQ(again[i].index1, kept[i].index1);
}

TEST(MatchVerification, APairOfChanceMatchesLosesThemAll) {
  const TwoViews views = MakeTwoViews(200);
  // Every match wrong: a shuffled pairing has no epipolar geometry.
  std::vector<PatchMatch> matches;
  for (int k = 0; k < 200; ++k) matches.push_back({k, (k * 37 + 11) % 200, 1.f});
  EXPECT_TRUE(VerifyMatches(views.a, views.b, matches, {}).empty());
  // Too few matches to verify at all, even right ones.
  std::vector<PatchMatch> few;
  for (int k = 0; k < 20; ++k) few.push_back({k, k, 1.f});
  EXPECT_TRUE(VerifyMatches(views.a, views.b, few, {}).empty());
  MatchVerificationOptions lenient;
  lenient.min_num_inliers = 10;
  EXPECT_GE(VerifyMatches(views.a, views.b, few, lenient).size(), 18u);
}

TEST(MatchVerification, RejectsBadInput) {
  const TwoViews views = MakeTwoViews(40);
  EXPECT_THROW(VerifyMatches(views.a, views.b, {{0, 40, 1.f}}, {}), Error);
  MatchVerificationOptions options;
  options.max_error_px = 0;
  EXPECT_THROW(options.Check(), Error);
  options = {};
  options.min_inlier_ratio = 1.5;
  EXPECT_THROW(options.Check(), Error);
  options = {};
  options.min_num_inliers = 7;
  EXPECT_THROW(options.Check(), Error);
}

}  // namespace
}  // namespace comic::frontend
