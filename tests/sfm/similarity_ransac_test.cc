// EstimateSim3dRansac (sfm/similarity_ransac.h): a known similarity found through outliers.
#include "sfm/similarity_ransac.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include "io/core/error.h"

namespace comic::sfm {
namespace {

struct PointSets {
  std::vector<Eigen::Vector3d> src, dst;
};

// 40 points on a grid mapped by `sim`; the last `num_outliers` destinations moved, each
// differently (no two outliers agree on one similarity).
PointSets MappedPoints(const Sim3d& sim, int num_outliers) {
  PointSets sets;
  for (int i = 0; i < 40; ++i) {
    const Eigen::Vector3d point(i % 5, (i / 5) % 4, 1.0 + 0.3 * (i % 7));
    sets.src.push_back(point);
    sets.dst.push_back(sim * point);
    if (i >= 40 - num_outliers)
      sets.dst.back() += Eigen::Vector3d(5.0 + i, -5.0 - 0.5 * i, 5.0 * (i % 3));
  }
  return sets;
}

SimilarityConsistency WithinOf(const PointSets& sets, double distance) {
  return [&sets, distance](const Sim3d& sim, size_t i) {
    return (sim * sets.src[i] - sets.dst[i]).norm() < distance;
  };
}

Sim3d KnownSimilarity() {
  Sim3d sim;
  sim.scale = 2.5;
  sim.rotation = Eigen::Quaterniond(Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()));
  sim.translation = Eigen::Vector3d(1.0, -4.0, 0.5);
  return sim;
}

TEST(SimilarityRansac, FindsTheSimilarityThroughAQuarterOfOutliers) {
  const Sim3d truth = KnownSimilarity();
  const PointSets sets = MappedPoints(truth, 10);
  int agreeing = -1;
  const std::optional<Sim3d> sim =
      EstimateSim3dRansac(sets.src, sets.dst, WithinOf(sets, 1e-6), 20, 0.5, &agreeing);
  ASSERT_TRUE(sim.has_value());
  EXPECT_EQ(agreeing, 30);
  EXPECT_NEAR(sim->scale, truth.scale, 1e-9);
  EXPECT_LT((sim->translation - truth.translation).norm(), 1e-9);
  EXPECT_LT(sim->rotation.angularDistance(truth.rotation), 1e-9);
}

TEST(SimilarityRansac, TooFewAgreeingPairsGiveNone) {
  const PointSets sets = MappedPoints(KnownSimilarity(), 25);
  int agreeing = -1;
  EXPECT_FALSE(EstimateSim3dRansac(sets.src, sets.dst, WithinOf(sets, 1e-6), 20, 0.0, &agreeing));
  EXPECT_EQ(agreeing, 15);
  EXPECT_FALSE(EstimateSim3dRansac(sets.src, sets.dst, WithinOf(sets, 1e-6), 3, 0.5));
  EXPECT_TRUE(EstimateSim3dRansac(sets.src, sets.dst, WithinOf(sets, 1e-6), 3, 0.3));
}

TEST(SimilarityRansac, FewerThanThreePairsOrUnequalSetsGiveNoneOrAnError) {
  const PointSets sets = MappedPoints(KnownSimilarity(), 0);
  const std::vector<Eigen::Vector3d> two(sets.src.begin(), sets.src.begin() + 2);
  int agreeing = -1;
  EXPECT_FALSE(EstimateSim3dRansac(two, two, WithinOf(sets, 1.0), 0, 0.0, &agreeing));
  EXPECT_EQ(agreeing, 0);
  EXPECT_THROW(EstimateSim3dRansac(sets.src, two, WithinOf(sets, 1.0), 3, 0.0), comic::Error);
}

}  // namespace
}  // namespace comic::sfm
