#include "sfm/model_agreement.h"

#include <algorithm>
#include <vector>

namespace comic::sfm {

ModelAgreement CompareModelRotations(const Reconstruction& a, const Reconstruction& b) {
  std::vector<image_t> common;
  for (const image_t image_id : a.RegisteredImageIds()) {
    if (b.ExistsImage(image_id) && b.image(image_id).registered) common.push_back(image_id);
  }
  ModelAgreement agreement;
  agreement.common_frames = static_cast<int>(common.size());
  if (common.size() < 2) return agreement;
  // R_a,iᵀ R_b,i takes b's world to a's for every frame; their chordal mean G is the one rotation
  // that best does so for all (as EvaluateTrajectory aligns a model with the truth), and b's
  // camera i in a's world is R_b,i Gᵀ.
  std::vector<Eigen::Matrix3d> world_rotations;
  for (const image_t image_id : common) {
    world_rotations.push_back(a.image(image_id).cam_from_world.RotationMatrix().transpose() *
                              b.image(image_id).cam_from_world.RotationMatrix());
  }
  const Eigen::Quaterniond a_from_b(ChordalMeanRotation(world_rotations));
  std::vector<double> differences;
  for (const image_t image_id : common) {
    differences.push_back(
        RotationAngleDeg(a.image(image_id).cam_from_world.rotation,
                         b.image(image_id).cam_from_world.rotation * a_from_b.conjugate()));
  }
  agreement.max_rotation_difference_deg = *std::max_element(differences.begin(), differences.end());
  std::nth_element(differences.begin(), differences.begin() + differences.size() / 2,
                   differences.end());
  agreement.median_rotation_difference_deg = differences[differences.size() / 2];
  return agreement;
}

}  // namespace comic::sfm
