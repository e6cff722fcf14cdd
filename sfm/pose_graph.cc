#include "sfm/pose_graph.h"

#include <ceres/ceres.h>

#include <Eigen/Geometry>
#include <cmath>
#include <memory>

#include "io/core/error.h"

namespace comic::sfm {
namespace {

// One node's parameters: the rotation as Eigen's (x, y, z, w), the translation, the log-scale.
struct NodeParameters {
  double rotation[4];
  double translation[3];
  double log_scale[1];
};

NodeParameters ToParameters(const Sim3d& pose) {
  NodeParameters p;
  const Eigen::Quaterniond q = pose.rotation.normalized();
  p.rotation[0] = q.x();
  p.rotation[1] = q.y();
  p.rotation[2] = q.z();
  p.rotation[3] = q.w();
  for (int k = 0; k < 3; ++k) p.translation[k] = pose.translation[k];
  p.log_scale[0] = std::log(pose.scale);
  return p;
}

Sim3d FromParameters(const NodeParameters& p) {
  Sim3d pose;
  pose.rotation =
      Eigen::Quaterniond(p.rotation[3], p.rotation[0], p.rotation[1], p.rotation[2]).normalized();
  pose.translation = Eigen::Vector3d(p.translation[0], p.translation[1], p.translation[2]);
  pose.scale = std::exp(p.log_scale[0]);
  return pose;
}

// The error of an edge, E = measured⁻¹ · (T_j · T_i⁻¹), as 7 residuals: its translation (relative
// to the measured baseline), twice the vector part of its rotation (≈ the angle in radians) and its
// log-scale, each weighted.
class SimilarityEdgeCost {
 public:
  SimilarityEdgeCost(const Sim3d& j_from_i, const Eigen::Vector3d& weights)
      : measured_(j_from_i), weights_(weights) {
    const double baseline = j_from_i.translation.norm();
    inverse_baseline_ = baseline > 1e-12 ? 1.0 / baseline : 1.0;
  }

  template <typename T>
  bool operator()(const T* q_i, const T* t_i, const T* l_i, const T* q_j, const T* t_j,
                  const T* l_j, T* residuals) const {
    const Eigen::Map<const Eigen::Quaternion<T>> rotation_i(q_i);
    const Eigen::Map<const Eigen::Quaternion<T>> rotation_j(q_j);
    const Eigen::Map<const Eigen::Matrix<T, 3, 1>> translation_i(t_i);
    const Eigen::Map<const Eigen::Matrix<T, 3, 1>> translation_j(t_j);
    // T_j · T_i⁻¹ = (s_j / s_i, R_j R_iᵀ, t_j − (s_j / s_i) R_j R_iᵀ t_i).
    const T relative_log_scale = l_j[0] - l_i[0];
    const Eigen::Quaternion<T> relative_rotation = rotation_j * rotation_i.conjugate();
    const Eigen::Matrix<T, 3, 1> relative_translation =
        translation_j - exp(relative_log_scale) * (relative_rotation * translation_i);

    const Eigen::Matrix<T, 3, 1> translation_error =
        (relative_translation - measured_.translation.cast<T>()) * T(inverse_baseline_);
    Eigen::Quaternion<T> rotation_error =
        measured_.rotation.cast<T>().conjugate() * relative_rotation;
    if (rotation_error.w() < T(0)) rotation_error.coeffs() = -rotation_error.coeffs();
    for (int k = 0; k < 3; ++k) {
      residuals[k] = T(weights_[0]) * translation_error[k];
      residuals[3 + k] = T(2.0 * weights_[1]) * rotation_error.vec()[k];
    }
    residuals[6] = T(weights_[2]) * (relative_log_scale - T(std::log(measured_.scale)));
    return true;
  }

 private:
  Sim3d measured_;
  Eigen::Vector3d weights_;
  double inverse_baseline_ = 1.0;
};

void CheckGraph(const std::vector<PoseGraphEdge>& edges, const std::set<int>& fixed_nodes,
                const std::vector<Sim3d>& poses) {
  const int nodes = static_cast<int>(poses.size());
  COMIC_CHECK(!fixed_nodes.empty(), kInvalidArgument, "pose graph: no fixed node (the gauge)");
  for (int node : fixed_nodes) {
    COMIC_CHECK(node >= 0 && node < nodes, kInvalidArgument,
                "pose graph: fixed node " << node << " of " << nodes);
  }
  for (const Sim3d& pose : poses) {
    COMIC_CHECK(pose.scale > 0 && std::isfinite(pose.scale), kInvalidArgument,
                "pose graph: a node's scale must be > 0, got " << pose.scale);
  }
  for (const PoseGraphEdge& edge : edges) {
    COMIC_CHECK(
        edge.i >= 0 && edge.i < nodes && edge.j >= 0 && edge.j < nodes && edge.i != edge.j,
        kInvalidArgument,
        "pose graph: edge " << edge.i << " -> " << edge.j << " among " << nodes << " nodes");
    COMIC_CHECK(edge.j_from_i.scale > 0 && std::isfinite(edge.j_from_i.scale), kInvalidArgument,
                "pose graph: edge scale must be > 0, got " << edge.j_from_i.scale);
    COMIC_CHECK(edge.weight > 0 && std::isfinite(edge.weight), kInvalidArgument,
                "pose graph: edge weight must be > 0, got " << edge.weight);
  }
}

}  // namespace

void PoseGraphOptions::Check() const {
  COMIC_CHECK(translation_weight > 0 && rotation_weight > 0 && scale_weight > 0, kInvalidArgument,
              "pose graph weights must be > 0, got " << translation_weight << ", "
                                                     << rotation_weight << ", " << scale_weight);
  COMIC_CHECK(max_num_iterations >= 1, kInvalidArgument,
              "pose graph max_num_iterations must be >= 1, got " << max_num_iterations);
}

Sim3d ComposeSim3(const Sim3d& c_from_b, const Sim3d& b_from_a) {
  Sim3d c_from_a;
  c_from_a.scale = c_from_b.scale * b_from_a.scale;
  c_from_a.rotation = (c_from_b.rotation * b_from_a.rotation).normalized();
  c_from_a.translation = c_from_b * b_from_a.translation;
  return c_from_a;
}

Sim3d InverseSim3(const Sim3d& b_from_a) {
  Sim3d a_from_b;
  a_from_b.scale = 1.0 / b_from_a.scale;
  a_from_b.rotation = b_from_a.rotation.conjugate();
  a_from_b.translation = -(a_from_b.scale * (a_from_b.rotation * b_from_a.translation));
  return a_from_b;
}

Sim3d Sim3FromRigid(const Rigid3d& cam_from_world) {
  Sim3d pose;
  pose.rotation = cam_from_world.rotation;
  pose.translation = cam_from_world.translation;
  return pose;
}

PoseGraphSummary OptimizePoseGraph(const PoseGraphOptions& options,
                                   const std::vector<PoseGraphEdge>& edges,
                                   const std::set<int>& fixed_nodes, std::vector<Sim3d>* poses) {
  options.Check();
  COMIC_CHECK(poses != nullptr, kInvalidArgument, "pose graph: poses is null");
  CheckGraph(edges, fixed_nodes, *poses);

  std::vector<NodeParameters> nodes;
  nodes.reserve(poses->size());
  for (const Sim3d& pose : *poses) nodes.push_back(ToParameters(pose));

  ceres::Problem problem;
  for (const PoseGraphEdge& edge : edges) {
    const Eigen::Vector3d weights =
        edge.weight *
        Eigen::Vector3d(options.translation_weight, options.rotation_weight, options.scale_weight);
    auto* cost = new ceres::AutoDiffCostFunction<SimilarityEdgeCost, 7, 4, 3, 1, 4, 3, 1>(
        new SimilarityEdgeCost(edge.j_from_i, weights));
    NodeParameters& a = nodes[edge.i];
    NodeParameters& b = nodes[edge.j];
    problem.AddResidualBlock(cost, nullptr, a.rotation, a.translation, a.log_scale, b.rotation,
                             b.translation, b.log_scale);
  }
  for (size_t n = 0; n < nodes.size(); ++n) {
    NodeParameters& p = nodes[n];
    if (!problem.HasParameterBlock(p.rotation)) continue;  // a node without edges stays
    problem.SetManifold(p.rotation, new ceres::EigenQuaternionManifold);
    if (fixed_nodes.count(static_cast<int>(n)) > 0) {
      problem.SetParameterBlockConstant(p.rotation);
      problem.SetParameterBlockConstant(p.translation);
      problem.SetParameterBlockConstant(p.log_scale);
    } else if (options.fix_scale) {
      problem.SetParameterBlockConstant(p.log_scale);
    }
  }

  ceres::Solver::Options solver;
  solver.linear_solver_type =
      ceres::IsSparseLinearAlgebraLibraryTypeAvailable(ceres::SUITE_SPARSE) ||
              ceres::IsSparseLinearAlgebraLibraryTypeAvailable(ceres::EIGEN_SPARSE)
          ? ceres::SPARSE_NORMAL_CHOLESKY
          : ceres::DENSE_QR;
  solver.max_num_iterations = options.max_num_iterations;
  solver.num_threads = 1;  // Ceres' threaded sums depend on the schedule (bundle_adjuster.cc)
  solver.logging_type = ceres::SILENT;
  ceres::Solver::Summary ceres_summary;
  ceres::Solve(solver, &problem, &ceres_summary);

  for (size_t n = 0; n < nodes.size(); ++n) (*poses)[n] = FromParameters(nodes[n]);
  PoseGraphSummary summary;
  summary.converged = ceres_summary.termination_type == ceres::CONVERGENCE;
  summary.iterations = static_cast<int>(ceres_summary.iterations.size());
  summary.initial_cost = ceres_summary.initial_cost;
  summary.final_cost = ceres_summary.final_cost;
  return summary;
}

}  // namespace comic::sfm
