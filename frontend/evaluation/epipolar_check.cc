#include "frontend/evaluation/epipolar_check.h"

#include <cmath>

#include "io/core/error.h"

namespace comic::frontend {

cv::Matx33d ScaleIntrinsics(const cv::Matx33d& K, const cv::Size& from, const cv::Size& to) {
  COMIC_CHECK(from.width > 0 && from.height > 0 && to.width > 0 && to.height > 0, kInvalidArgument,
              "ScaleIntrinsics: sizes must be positive");
  const double sx = static_cast<double>(to.width) / from.width;
  const double sy = static_cast<double>(to.height) / from.height;
  cv::Matx33d scaled = K;
  scaled(0, 0) *= sx;
  scaled(0, 1) *= sx;
  scaled(0, 2) = (K(0, 2) + 0.5) * sx - 0.5;
  scaled(1, 1) *= sy;
  scaled(1, 2) = (K(1, 2) + 0.5) * sy - 0.5;
  return scaled;
}

cv::Matx33d FundamentalFromPoses(const cv::Matx33d& K, const cv::Matx34d& world_from_camera_a,
                                 const cv::Matx34d& world_from_camera_b) {
  const cv::Matx33d ra = world_from_camera_a.get_minor<3, 3>(0, 0);
  const cv::Matx33d rb = world_from_camera_b.get_minor<3, 3>(0, 0);
  const cv::Vec3d ta(world_from_camera_a(0, 3), world_from_camera_a(1, 3),
                     world_from_camera_a(2, 3));
  const cv::Vec3d tb(world_from_camera_b(0, 3), world_from_camera_b(1, 3),
                     world_from_camera_b(2, 3));
  // X_b = R X_a + t with R = R_bᵀ R_a, t = R_bᵀ (t_a − t_b); E = [t]x R.
  const cv::Matx33d r = rb.t() * ra;
  const cv::Vec3d t = rb.t() * (ta - tb);
  const cv::Matx33d tx(0, -t[2], t[1], t[2], 0, -t[0], -t[1], t[0], 0);
  const cv::Matx33d k_inv = K.inv();
  return k_inv.t() * (tx * r) * k_inv;
}

double EpipolarDistance(const cv::Matx33d& F, const cv::Point2f& a, const cv::Point2f& b) {
  const cv::Vec3d line = F * cv::Vec3d(a.x, a.y, 1.0);
  const double norm = std::hypot(line[0], line[1]);
  if (norm == 0.0) return 0.0;  // a is the epipole: every point is on its (degenerate) line
  return std::abs(line[0] * b.x + line[1] * b.y + line[2]) / norm;
}

std::vector<bool> EpipolarConsistency(const cv::Matx33d& F, const FeatureSet& features_a,
                                      const FeatureSet& features_b,
                                      const std::vector<PatchMatch>& matches, double tolerance) {
  std::vector<bool> consistent;
  consistent.reserve(matches.size());
  for (const PatchMatch& m : matches) {
    COMIC_CHECK(m.index1 >= 0 && m.index1 < static_cast<int>(features_a.size()) && m.index2 >= 0 &&
                    m.index2 < static_cast<int>(features_b.size()),
                kInvalidArgument, "epipolar check: match index out of range");
    consistent.push_back(EpipolarDistance(F, features_a[m.index1].Position(),
                                          features_b[m.index2].Position()) <= tolerance);
  }
  return consistent;
}

}  // namespace comic::frontend
