#include "sfm/model_agreement.h"

#include <algorithm>
#include <vector>

namespace comic::sfm {

namespace {

double Median(std::vector<double> values) {
  std::nth_element(values.begin(), values.begin() + values.size() / 2, values.end());
  return values[values.size() / 2];
}

// Over the pairs of `common` (ascending) at most `neighbour_ids` apart: the angle of
// R_a,j R_a,iᵀ (R_b,j R_b,iᵀ)ᵀ, how much more one model turns the camera from i to j than the
// other. A world rotation cancels in each product, so no alignment is needed.
std::vector<double> RelativeRotationDifferences(const Reconstruction& a, const Reconstruction& b,
                                                const std::vector<image_t>& common,
                                                int neighbour_ids) {
  std::vector<double> differences;
  for (size_t i = 0; i < common.size(); ++i) {
    const Eigen::Quaterniond& a_i = a.image(common[i]).cam_from_world.rotation;
    const Eigen::Quaterniond& b_i = b.image(common[i]).cam_from_world.rotation;
    for (size_t j = i + 1;
         j < common.size() && common[j] - common[i] <= static_cast<image_t>(neighbour_ids); ++j) {
      const Eigen::Quaterniond a_ij = a.image(common[j]).cam_from_world.rotation * a_i.conjugate();
      const Eigen::Quaterniond b_ij = b.image(common[j]).cam_from_world.rotation * b_i.conjugate();
      differences.push_back(RotationAngleDeg(a_ij, b_ij));
    }
  }
  return differences;
}

}  // namespace

ModelAgreement CompareModelRotations(const Reconstruction& a, const Reconstruction& b,
                                     int neighbour_ids) {
  std::vector<image_t> common;
  for (const image_t image_id : a.RegisteredImageIds()) {  // ascending
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
  agreement.median_rotation_difference_deg = Median(differences);
  const std::vector<double> relative = RelativeRotationDifferences(a, b, common, neighbour_ids);
  agreement.neighbour_pairs = static_cast<int>(relative.size());
  if (!relative.empty()) agreement.median_relative_rotation_difference_deg = Median(relative);
  return agreement;
}

}  // namespace comic::sfm
