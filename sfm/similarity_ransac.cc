#include "sfm/similarity_ransac.h"

#include <random>

#include "io/core/error.h"
#include "sfm/trajectory_evaluation.h"

namespace comic::sfm {

std::optional<Sim3d> EstimateSim3dRansac(const std::vector<Eigen::Vector3d>& src,
                                         const std::vector<Eigen::Vector3d>& dst,
                                         const SimilarityConsistency& consistent,
                                         int min_num_inliers, double min_inlier_ratio,
                                         int* num_inliers) {
  COMIC_CHECK(src.size() == dst.size(), kInvalidArgument,
              "similarity RANSAC: " << src.size() << " source points, " << dst.size()
                                    << " destination points");
  if (num_inliers != nullptr) *num_inliers = 0;
  if (src.size() < 3) return std::nullopt;
  const auto count_inliers = [&](const Sim3d& sim, std::vector<Eigen::Vector3d>* agreeing_src,
                                 std::vector<Eigen::Vector3d>* agreeing_dst) {
    agreeing_src->clear();
    agreeing_dst->clear();
    for (size_t i = 0; i < src.size(); ++i) {
      if (!consistent(sim, i)) continue;
      agreeing_src->push_back(src[i]);
      agreeing_dst->push_back(dst[i]);
    }
    return agreeing_src->size();
  };
  std::mt19937 random(1);
  std::uniform_int_distribution<size_t> pick(0, src.size() - 1);
  std::vector<Eigen::Vector3d> best_src, best_dst, candidate_src, candidate_dst;
  constexpr int kNumIterations = 500;
  for (int iteration = 0; iteration < kNumIterations; ++iteration) {
    const size_t a = pick(random), b = pick(random), c = pick(random);
    if (a == b || b == c || a == c) continue;
    const std::optional<Sim3d> sim =
        EstimateSim3dUmeyama({src[a], src[b], src[c]}, {dst[a], dst[b], dst[c]});
    if (!sim || !(sim->scale > 0)) continue;
    if (count_inliers(*sim, &candidate_src, &candidate_dst) > best_src.size()) {
      best_src.swap(candidate_src);
      best_dst.swap(candidate_dst);
    }
  }
  std::optional<Sim3d> sim;
  for (int round = 0; round < 2 && best_src.size() >= 3; ++round) {
    sim = EstimateSim3dUmeyama(best_src, best_dst);
    if (!sim) return std::nullopt;
    if (count_inliers(*sim, &candidate_src, &candidate_dst) < best_src.size()) break;
    best_src.swap(candidate_src);
    best_dst.swap(candidate_dst);
  }
  const int agreeing = static_cast<int>(best_src.size());
  if (num_inliers != nullptr) *num_inliers = agreeing;
  if (!sim || agreeing < min_num_inliers ||
      agreeing < min_inlier_ratio * static_cast<double>(src.size())) {
    return std::nullopt;
  }
  return sim;
}

}  // namespace comic::sfm
