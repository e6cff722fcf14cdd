#include "sfm/trajectory_evaluation.h"

#include <Eigen/Geometry>
#include <Eigen/SVD>
#include <algorithm>
#include <cmath>

#include "io/core/error.h"

namespace comic::sfm {

std::optional<Sim3d> EstimateSim3dUmeyama(const std::vector<Eigen::Vector3d>& src,
                                          const std::vector<Eigen::Vector3d>& dst) {
  if (src.size() != dst.size() || src.size() < 3) return std::nullopt;
  Eigen::Matrix3Xd src_matrix(3, src.size());
  Eigen::Matrix3Xd dst_matrix(3, dst.size());
  for (size_t i = 0; i < src.size(); ++i) {
    src_matrix.col(i) = src[i];
    dst_matrix.col(i) = dst[i];
  }
  const Eigen::Vector3d src_mean = src_matrix.rowwise().mean();
  if ((src_matrix.colwise() - src_mean).norm() < 1e-12) return std::nullopt;
  const Eigen::Matrix4d transform = Eigen::umeyama(src_matrix, dst_matrix, true);
  if (!transform.allFinite()) return std::nullopt;
  Sim3d sim3;
  const Eigen::Matrix3d scaled_rotation = transform.topLeftCorner<3, 3>();
  sim3.scale = std::cbrt(scaled_rotation.determinant());
  if (!(sim3.scale > 0)) return std::nullopt;
  sim3.rotation = Eigen::Quaterniond(scaled_rotation / sim3.scale).normalized();
  sim3.translation = transform.topRightCorner<3, 1>();
  return sim3;
}

std::optional<TrajectoryEvaluation> EvaluateTrajectory(
    const std::vector<std::optional<Rigid3d>>& estimated,
    const std::vector<std::optional<Rigid3d>>& ground_truth) {
  COMIC_CHECK(estimated.size() == ground_truth.size(), kInvalidArgument,
              "trajectory evaluation: " << estimated.size() << " estimated poses for "
                                        << ground_truth.size() << " ground-truth poses");
  TrajectoryEvaluation evaluation;
  std::vector<Eigen::Vector3d> estimated_centers, true_centers;
  for (size_t i = 0; i < estimated.size(); ++i) {
    if (!estimated[i] || !ground_truth[i]) continue;
    evaluation.frames.push_back(static_cast<int>(i));
    estimated_centers.push_back(ProjectionCenter(*estimated[i]));
    true_centers.push_back(ProjectionCenter(*ground_truth[i]));
  }
  const auto sim3 = EstimateSim3dUmeyama(estimated_centers, true_centers);
  if (!sim3) return std::nullopt;
  evaluation.gt_from_estimated = *sim3;

  // Rotation alignment from the orientations: R_gt_i^T R_est_i maps the estimated world to the
  // true one for every frame; average them.
  std::vector<Eigen::Matrix3d> world_rotations;
  for (int frame : evaluation.frames) {
    world_rotations.push_back(ground_truth[frame]->RotationMatrix().transpose() *
                              estimated[frame]->RotationMatrix());
  }
  const Eigen::Quaterniond gt_from_estimated_rotation(ChordalMeanRotation(world_rotations));
  evaluation.gt_from_estimated_rotation = gt_from_estimated_rotation;

  double sum_squared = 0.0, sum = 0.0, sum_rotation = 0.0, sum_rotation_sim3 = 0.0;
  for (size_t k = 0; k < evaluation.frames.size(); ++k) {
    const int frame = evaluation.frames[k];
    const double error = (*sim3 * estimated_centers[k] - true_centers[k]).norm();
    evaluation.position_errors.push_back(error);
    sum_squared += error * error;
    sum += error;
    evaluation.ate_max = std::max(evaluation.ate_max, error);
    const Eigen::Quaterniond aligned =
        estimated[frame]->rotation * gt_from_estimated_rotation.conjugate();
    evaluation.rotation_errors_deg.push_back(
        RotationAngleDeg(aligned, ground_truth[frame]->rotation));
    sum_rotation += evaluation.rotation_errors_deg.back();
    sum_rotation_sim3 += RotationAngleDeg(sim3->TransformPose(*estimated[frame]).rotation,
                                          ground_truth[frame]->rotation);
    if (k > 0) evaluation.path_length += (true_centers[k] - true_centers[k - 1]).norm();
  }
  const double n = static_cast<double>(evaluation.frames.size());
  evaluation.ate_rmse = std::sqrt(sum_squared / n);
  evaluation.ate_mean = sum / n;
  evaluation.ate_fraction_of_path =
      evaluation.path_length > 0 ? evaluation.ate_rmse / evaluation.path_length : 0.0;
  const size_t last = evaluation.frames.size() - 1;
  evaluation.end_to_start_error =
      ((*sim3 * estimated_centers[last] - *sim3 * estimated_centers[0]) -
       (true_centers[last] - true_centers[0]))
          .norm();
  evaluation.mean_rotation_error_deg = sum_rotation / n;
  evaluation.mean_rotation_error_sim3_deg = sum_rotation_sim3 / n;
  return evaluation;
}

}  // namespace comic::sfm
