// A similarity between two point sets with outliers: the map that takes points of one model onto
// the same physical points of another (two models of one mapper merged, chunks of a distributed
// run merged).
//
//   int agreeing = 0;
//   std::optional<Sim3d> sim = EstimateSim3dRansac(
//       src, dst, [&](const Sim3d& s, size_t i) { return (s * src[i] - dst[i]).norm() < 0.1; },
//       /*min_num_inliers=*/10, /*min_inlier_ratio=*/0.3, &agreeing);
#pragma once

#include <Eigen/Core>
#include <functional>
#include <optional>
#include <vector>

#include "sfm/rigid3d.h"

namespace comic::sfm {

// Whether pair i agrees with a candidate similarity (taking src[i] near dst[i]).
using SimilarityConsistency = std::function<bool(const Sim3d& sim, size_t pair)>;

// The similarity dst ≈ sim * src: RANSAC over triples (Umeyama on each, a fixed seed, so the
// result is repeatable), then Umeyama refitted on the pairs `consistent` accepts until that set
// stops growing (twice at most). std::nullopt unless at least min_num_inliers and
// min_inlier_ratio of the pairs agree. `num_inliers` (optional) gets the agreeing pairs' count.
// Throws comic::Error(kInvalidArgument) for src and dst of different sizes.
std::optional<Sim3d> EstimateSim3dRansac(const std::vector<Eigen::Vector3d>& src,
                                         const std::vector<Eigen::Vector3d>& dst,
                                         const SimilarityConsistency& consistent,
                                         int min_num_inliers, double min_inlier_ratio,
                                         int* num_inliers = nullptr);

}  // namespace comic::sfm
