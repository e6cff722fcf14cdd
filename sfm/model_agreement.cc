#include "sfm/model_agreement.h"

#include <Eigen/SVD>
#include <algorithm>
#include <vector>

namespace comic::sfm {

ModelAgreement CompareModelRotations(const Reconstruction& a, const Reconstruction& b) {
  std::vector<std::pair<Eigen::Matrix3d, Eigen::Matrix3d>> rotations;  // (a's, b's) per frame
  for (const image_t image_id : a.RegisteredImageIds()) {
    if (!b.ExistsImage(image_id) || !b.image(image_id).registered) continue;
    rotations.emplace_back(a.image(image_id).cam_from_world.rotation.toRotationMatrix(),
                           b.image(image_id).cam_from_world.rotation.toRotationMatrix());
  }
  ModelAgreement agreement;
  agreement.common_frames = static_cast<int>(rotations.size());
  if (rotations.size() < 2) return agreement;
  // b's camera i in a's world is R_b,i G, with G the rotation that best makes R_b,i G = R_a,i
  // for every i: the SO(3) projection of the sum of R_b,iᵀ R_a,i (chordal mean).
  Eigen::Matrix3d sum = Eigen::Matrix3d::Zero();
  for (const auto& [rotation_a, rotation_b] : rotations) sum += rotation_b.transpose() * rotation_a;
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(sum, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d sign = Eigen::Matrix3d::Identity();
  sign(2, 2) = (svd.matrixU() * svd.matrixV().transpose()).determinant() < 0 ? -1.0 : 1.0;
  const Eigen::Matrix3d common = svd.matrixU() * sign * svd.matrixV().transpose();
  std::vector<double> differences;
  for (const auto& [rotation_a, rotation_b] : rotations) {
    differences.push_back(
        RotationAngleDeg(Eigen::Quaterniond(rotation_a), Eigen::Quaterniond(rotation_b * common)));
  }
  agreement.max_rotation_difference_deg = *std::max_element(differences.begin(), differences.end());
  std::nth_element(differences.begin(), differences.begin() + differences.size() / 2,
                   differences.end());
  agreement.median_rotation_difference_deg = differences[differences.size() / 2];
  return agreement;
}

}  // namespace comic::sfm
