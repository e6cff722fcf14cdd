// Evaluation of estimated camera poses against ground truth, on plain per-frame poses so any
// reconstruction (ours, or COLMAP's read back from its model) is measured by the same code:
// Sim(3) alignment of the camera centres (Umeyama), absolute trajectory error (ATE), and rotation
// error.
//
//   std::vector<std::optional<Rigid3d>> estimated(num_frames), ground_truth(num_frames);
//   ... fill the frames each side knows ...
//   if (const auto evaluation = EvaluateTrajectory(estimated, ground_truth)) {
//     evaluation->ate_rmse;  evaluation->ate_fraction_of_path; evaluation->mean_rotation_error_deg;
//   }
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <optional>
#include <vector>

#include "sfm/rigid3d.h"

namespace comic::sfm {

// The similarity dst ≈ s R src + t minimising the sum of squared distances (Umeyama 1991).
// std::nullopt for fewer than 3 pairs, mismatched sizes, or coincident source points.
std::optional<Sim3d> EstimateSim3dUmeyama(const std::vector<Eigen::Vector3d>& src,
                                          const std::vector<Eigen::Vector3d>& dst);

struct TrajectoryEvaluation {
  std::vector<int> frames;  // frames with both an estimate and ground truth, ascending
  // Maps the estimated world into the ground-truth world (fitted on the camera centres).
  Sim3d gt_from_estimated;
  // Per evaluated frame: distance between the aligned estimated centre and the true one (GT
  // units, e.g. metres).
  std::vector<double> position_errors;
  // Per evaluated frame: angle between the estimated and true camera orientations, after the
  // rotation alignment below (degrees).
  std::vector<double> rotation_errors_deg;
  double ate_rmse = 0.0;  // RMS of position_errors
  double ate_mean = 0.0;
  double ate_max = 0.0;
  // Length of the true path through the evaluated frames (sum of consecutive centre distances).
  double path_length = 0.0;
  double ate_fraction_of_path = 0.0;  // ate_rmse / path_length (0 if the path has no length)
  // The error of the last evaluated frame's position relative to the first's, after the
  // alignment: |(ĉ_last − ĉ_first) − (c_last − c_first)| (GT units). On a path that returns to
  // its start this is the loop's drift as the model leaves it (what loop closure corrects).
  double end_to_start_error = 0.0;
  // Mean of rotation_errors_deg. The rotation alignment is the chordal mean of the per-frame
  // rotations between the two worlds, not the Sim(3)'s rotation: on a straight path (KITTI) the
  // centres leave the roll about the path undetermined, which would show up as rotation error.
  double mean_rotation_error_deg = 0.0;
  // The same, with the Sim(3)'s rotation (well defined only for a path that is not a line).
  double mean_rotation_error_sim3_deg = 0.0;
  // That rotation alignment: the chordal mean over the evaluated frames of the rotation taking
  // the estimated world to the true one (defined whatever the shape of the path).
  Eigen::Quaterniond gt_from_estimated_rotation = Eigen::Quaterniond::Identity();
};

// `estimated` and `ground_truth` are cam_from_world poses indexed by frame (std::nullopt where
// unknown) and must have the same size (comic::Error otherwise). std::nullopt when fewer than 3
// frames have both or the alignment is degenerate.
std::optional<TrajectoryEvaluation> EvaluateTrajectory(
    const std::vector<std::optional<Rigid3d>>& estimated,
    const std::vector<std::optional<Rigid3d>>& ground_truth);

}  // namespace comic::sfm
