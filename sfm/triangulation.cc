#include "sfm/triangulation.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

#include "io/core/error.h"
#include "sfm/reconstruction.h"

namespace comic::sfm {

std::optional<Eigen::Vector3d> TriangulatePointDlt(
    const std::vector<Rigid3d>& cams_from_world,
    const std::vector<Eigen::Vector2d>& points_normalized) {
  COMIC_CHECK(cams_from_world.size() == points_normalized.size(), kInvalidArgument,
              "triangulation: " << cams_from_world.size() << " poses for "
                                << points_normalized.size() << " points");
  if (cams_from_world.size() < 2) return std::nullopt;
  // Each view gives two rows x·P₃ − P₁ and y·P₃ − P₂ of A X = 0; X is the eigenvector of the
  // 4×4 AᵀA with the smallest eigenvalue (as COLMAP's multi-view triangulation). The SVD of the
  // 2n×4 A gives the same vector but cost a tenth of the mapper's time (it runs for every
  // candidate pair of every track after each global bundle adjustment).
  Eigen::Matrix4d ata = Eigen::Matrix4d::Zero();
  for (size_t i = 0; i < cams_from_world.size(); ++i) {
    const Eigen::Matrix<double, 3, 4> p = cams_from_world[i].ToMatrix();
    const Eigen::RowVector4d row_x = points_normalized[i].x() * p.row(2) - p.row(0);
    const Eigen::RowVector4d row_y = points_normalized[i].y() * p.row(2) - p.row(1);
    ata.noalias() += row_x.transpose() * row_x;
    ata.noalias() += row_y.transpose() * row_y;
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix4d> eigen(ata);
  if (eigen.info() != Eigen::Success) return std::nullopt;
  const Eigen::Vector4d x = eigen.eigenvectors().col(0);  // eigenvalues ascending
  if (std::abs(x(3)) < 1e-12 * x.head<3>().norm() || x(3) == 0.0) return std::nullopt;
  const Eigen::Vector3d point = x.head<3>() / x(3);
  if (!point.allFinite()) return std::nullopt;
  return point;
}

double TriangulationAngleDeg(const Eigen::Vector3d& center1, const Eigen::Vector3d& center2,
                             const Eigen::Vector3d& point3D) {
  const Eigen::Vector3d ray1 = point3D - center1;
  const Eigen::Vector3d ray2 = point3D - center2;
  const double norms = ray1.norm() * ray2.norm();
  if (norms <= 0.0) return 0.0;
  const double cosine = std::clamp(ray1.dot(ray2) / norms, -1.0, 1.0);
  return std::acos(cosine) * 180.0 / M_PI;
}

void TriangulationOptions::Check() const {
  COMIC_CHECK(min_angle_deg >= 0 && min_angle_deg < 90, kInvalidArgument,
              "triangulation min_angle_deg must be in [0, 90), got " << min_angle_deg);
  COMIC_CHECK(max_reprojection_error_px > 0, kInvalidArgument,
              "triangulation max_reprojection_error_px must be > 0");
  COMIC_CHECK(max_depth_to_baseline > 0, kInvalidArgument,
              "triangulation max_depth_to_baseline must be > 0");
  COMIC_CHECK(min_num_views >= 2, kInvalidArgument, "triangulation min_num_views must be >= 2");
}

namespace {

Eigen::Vector2d Normalize(const Camera& camera, const Eigen::Vector2d& pixel) {
  return camera.CamFromImage(pixel);
}

// The views that see `point` in front and within the reprojection threshold, and the sum of their
// errors (for tie-breaking).
std::vector<int> ConsistentViews(const std::vector<TriangulationView>& views,
                                 const Eigen::Vector3d& point, double max_error,
                                 double* error_sum) {
  std::vector<int> inliers;
  *error_sum = 0.0;
  for (size_t i = 0; i < views.size(); ++i) {
    const auto projection = ProjectPoint(*views[i].camera, views[i].cam_from_world, point);
    if (!projection) continue;
    const double error = (*projection - views[i].point2D).norm();
    if (error <= max_error) {
      inliers.push_back(static_cast<int>(i));
      *error_sum += error;
    }
  }
  return inliers;
}

std::optional<Eigen::Vector3d> TriangulateSubset(const std::vector<TriangulationView>& views,
                                                 const std::vector<int>& subset) {
  std::vector<Rigid3d> poses;
  std::vector<Eigen::Vector2d> points;
  for (int i : subset) {
    poses.push_back(views[i].cam_from_world);
    points.push_back(Normalize(*views[i].camera, views[i].point2D));
  }
  return TriangulatePointDlt(poses, points);
}

}  // namespace

std::optional<TriangulatedPoint> TriangulateMultiView(const std::vector<TriangulationView>& views,
                                                      const TriangulationOptions& options) {
  options.Check();
  const int n = static_cast<int>(views.size());
  if (n < options.min_num_views) return std::nullopt;
  for (const TriangulationView& view : views) {
    COMIC_CHECK(view.camera != nullptr, kInvalidArgument, "triangulation view without camera");
  }
  std::vector<Eigen::Vector3d> centers;
  for (const TriangulationView& view : views)
    centers.push_back(ProjectionCenter(view.cam_from_world));

  // Candidate pairs: all of them for short tracks; for long ones the pairs with the first or the
  // last view (the newest registered one in the mapper) and those half the track apart, which
  // keeps the cost linear in the track length while every view is in some wide pair.
  std::vector<std::pair<int, int>> pairs;
  constexpr int kExhaustiveViews = 12;
  for (int i = 0; i < n; ++i) {
    for (int j = i + 1; j < n; ++j) {
      const bool keep = n <= kExhaustiveViews || i == 0 || j == n - 1 || (j - i) == n / 2;
      if (keep) pairs.emplace_back(i, j);
    }
  }

  std::vector<int> best_inliers;
  double best_error = 0.0;
  for (const auto& [i, j] : pairs) {
    const auto point = TriangulateSubset(views, {i, j});
    if (!point) continue;
    double error_sum = 0.0;
    std::vector<int> inliers =
        ConsistentViews(views, *point, options.max_reprojection_error_px, &error_sum);
    if (inliers.size() > best_inliers.size() ||
        (inliers.size() == best_inliers.size() && !inliers.empty() && error_sum < best_error)) {
      best_inliers = std::move(inliers);
      best_error = error_sum;
    }
  }
  if (static_cast<int>(best_inliers.size()) < options.min_num_views) return std::nullopt;

  // Re-estimate from all agreeing views; they must still agree afterwards.
  const auto point = TriangulateSubset(views, best_inliers);
  if (!point) return std::nullopt;
  double error_sum = 0.0;
  const std::vector<int> final_inliers =
      ConsistentViews(views, *point, options.max_reprojection_error_px, &error_sum);
  if (static_cast<int>(final_inliers.size()) < options.min_num_views) return std::nullopt;

  TriangulatedPoint result;
  result.xyz = *point;
  result.inlier_views = final_inliers;
  double max_baseline = 0.0;
  for (size_t a = 0; a < final_inliers.size(); ++a) {
    for (size_t b = a + 1; b < final_inliers.size(); ++b) {
      const Eigen::Vector3d& ca = centers[final_inliers[a]];
      const Eigen::Vector3d& cb = centers[final_inliers[b]];
      result.max_angle_deg = std::max(result.max_angle_deg, TriangulationAngleDeg(ca, cb, *point));
      max_baseline = std::max(max_baseline, (ca - cb).norm());
    }
  }
  if (result.max_angle_deg < options.min_angle_deg) return std::nullopt;
  for (int i : final_inliers) {
    const double depth = (views[i].cam_from_world * *point).z();
    if (depth > options.max_depth_to_baseline * max_baseline) return std::nullopt;
  }
  return result;
}

}  // namespace comic::sfm
