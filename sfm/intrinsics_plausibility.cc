#include "sfm/intrinsics_plausibility.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

#include "io/core/error.h"

namespace comic::sfm {

void IntrinsicsPlausibilityOptions::Check() const {
  COMIC_CHECK(max_focal_ratio > 1.0, kInvalidArgument,
              "plausible intrinsics max_focal_ratio must be > 1, got " << max_focal_ratio);
  COMIC_CHECK(
      max_corner_distortion > 0.0, kInvalidArgument,
      "plausible intrinsics max_corner_distortion must be > 0, got " << max_corner_distortion);
}

IntrinsicsPlausibility CheckIntrinsicsPlausibility(const Camera& prior, const Camera& refined,
                                                   const IntrinsicsPlausibilityOptions& options) {
  options.Check();
  IntrinsicsPlausibility result;
  std::ostringstream reason;
  reason << std::setprecision(3);
  // The focal ratio farthest from 1 (in either direction).
  for (const auto& [value, prior_value] :
       {std::pair(refined.fx, prior.fx), std::pair(refined.fy, prior.fy)}) {
    const double ratio = value / prior_value;
    if (std::abs(std::log(ratio)) > std::abs(std::log(result.focal_ratio))) {
      result.focal_ratio = ratio;
    }
  }
  if (!(result.focal_ratio <= options.max_focal_ratio &&
        result.focal_ratio >= 1.0 / options.max_focal_ratio)) {
    result.plausible = false;
    reason << "focal length " << std::fixed << std::setprecision(1) << refined.fx << " px is "
           << std::setprecision(2) << result.focal_ratio << "x the prior " << std::setprecision(1)
           << prior.fx << " px (the plausible range is 1/" << std::setprecision(0)
           << options.max_focal_ratio << "x to " << options.max_focal_ratio << "x)";
  }
  // The image corner farthest from the principal point, normalised.
  const double dx = std::max(refined.cx + 0.5, refined.width - 0.5 - refined.cx) / refined.fx;
  const double dy = std::max(refined.cy + 0.5, refined.height - 0.5 - refined.cy) / refined.fy;
  const double r2 = dx * dx + dy * dy;
  result.corner_distortion = refined.k1 * r2 + refined.k2 * r2 * r2;
  // d/dr of r (1 + k1 r^2 + k2 r^4) must stay positive out to the corner.
  const double slope = 1.0 + 3.0 * refined.k1 * r2 + 5.0 * refined.k2 * r2 * r2;
  if (std::abs(result.corner_distortion) > options.max_corner_distortion || slope <= 0.0) {
    if (!result.plausible) reason << "; ";
    result.plausible = false;
    reason << std::defaultfloat << std::setprecision(3) << "radial distortion k1 = " << refined.k1
           << ", k2 = " << refined.k2 << " moves the image corner by " << std::fixed
           << std::setprecision(0) << 100.0 * result.corner_distortion
           << " % of its radius (at most " << 100.0 * options.max_corner_distortion << " %"
           << (slope <= 0.0 ? ", and folds the image over" : "") << ")";
  }
  result.reason = reason.str();
  return result;
}

}  // namespace comic::sfm
