#include "sfm/focal_observability.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "io/core/error.h"

namespace comic::sfm {

void FocalObservabilityOptions::Check() const {
  COMIC_CHECK(min_viewing_angle_deg > 0 && min_viewing_angle_deg < 180, kInvalidArgument,
              "focal observability min_viewing_angle_deg must be > 0 and < 180, got "
                  << min_viewing_angle_deg);
}

FocalObservability AssessFocalObservability(const Reconstruction& reconstruction,
                                            const FocalObservabilityOptions& options) {
  options.Check();
  // Optical axes in world coordinates: the third row of each rotation cam_from_world.
  std::vector<Eigen::Vector3d> axes;
  for (image_t image_id : reconstruction.RegisteredImageIds()) {
    const Eigen::Matrix3d rotation =
        reconstruction.image(image_id).cam_from_world.rotation.normalized().toRotationMatrix();
    axes.push_back(rotation.row(2).transpose());
  }
  double min_cosine = 1.0;
  for (size_t i = 0; i < axes.size(); ++i) {
    for (size_t j = i + 1; j < axes.size(); ++j)
      min_cosine = std::min(min_cosine, axes[i].dot(axes[j]));
  }
  FocalObservability result;
  result.max_viewing_angle_deg = std::acos(std::clamp(min_cosine, -1.0, 1.0)) * 180.0 / M_PI;
  result.observable = result.max_viewing_angle_deg >= options.min_viewing_angle_deg;
  return result;
}

}  // namespace comic::sfm
